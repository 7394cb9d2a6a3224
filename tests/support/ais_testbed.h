// SPDX-License-Identifier: MIT
// The AIS test bed (datasets/ais-testbed) with the paper's mission, and the paper's plan, for
// domain tests.
#pragma once

#include <string_view>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::testing {

struct AisTestbed {
  SewerMap map;
  Mission mission;  // missions/paper.json
};

// Loads the map and the paper's mission; a test failure if either does not load.
AisTestbed load_ais_testbed();

// The plan of the paper's section 6, literally. In sewerplan INSPECT_PIPE drives the pipe while
// scanning it, so its step 11 comes one step too late: the robot has already left P4.
inline constexpr std::string_view kPaperPlan =
    "DRIVE_PIPE_TO_MANHOLE P12 M2\n"
    "DRIVE_MANHOLE_TYPE_2_FROM_1_TO_2 M2 P12 P1\n"
    "DRIVE_PIPE_TO_MANHOLE P1 M3\n"
    "DRIVE_MANHOLE_TYPE_3_TYPE_B_FROM_3_TO_1 M3 P5 P2 P1\n"
    "DRIVE_PIPE_TO_MANHOLE P5 M6\n"
    "DRIVE_MANHOLE_TYPE_4_FROM_3_TO_4 M6 P10 P4 P5 P6\n"
    "TAKE_WATER_SAMPLE P6\n"
    "DRIVE_PIPE_TO_MANHOLE P6 M6\n"
    "DRIVE_MANHOLE_TYPE_4_FROM_4_TO_2 M6 P10 P4 P5 P6\n"
    "DRIVE_PIPE_TO_MANHOLE P4 M5\n"
    "INSPECT_PIPE P4\n"
    "DRIVE_MANHOLE_TYPE_4_FROM_4_TO_1 M5 P8 P13 P3 P4\n"
    "DRIVE_PIPE_TO_MANHOLE P8 M9\n"
    "DRIVE_MANHOLE_TYPE_3_TYPE_B_FROM_1_TO_2 M9 P8 P9 P14\n";

// The paper's plan with steps 10 and 11 swapped: P4 is inspected on the way to M5.
inline constexpr std::string_view kCorrectedPaperPlan =
    "DRIVE_PIPE_TO_MANHOLE P12 M2\n"
    "DRIVE_MANHOLE_TYPE_2_FROM_1_TO_2 M2 P12 P1\n"
    "DRIVE_PIPE_TO_MANHOLE P1 M3\n"
    "DRIVE_MANHOLE_TYPE_3_TYPE_B_FROM_3_TO_1 M3 P5 P2 P1\n"
    "DRIVE_PIPE_TO_MANHOLE P5 M6\n"
    "DRIVE_MANHOLE_TYPE_4_FROM_3_TO_4 M6 P10 P4 P5 P6\n"
    "TAKE_WATER_SAMPLE P6\n"
    "DRIVE_PIPE_TO_MANHOLE P6 M6\n"
    "DRIVE_MANHOLE_TYPE_4_FROM_4_TO_2 M6 P10 P4 P5 P6\n"
    "INSPECT_PIPE P4\n"
    "DRIVE_PIPE_TO_MANHOLE P4 M5\n"
    "DRIVE_MANHOLE_TYPE_4_FROM_4_TO_1 M5 P8 P13 P3 P4\n"
    "DRIVE_PIPE_TO_MANHOLE P8 M9\n"
    "DRIVE_MANHOLE_TYPE_3_TYPE_B_FROM_1_TO_2 M9 P8 P9 P14\n";

}  // namespace sewerplan::testing
