// SPDX-License-Identifier: MIT
// Plan: a sequence of the sewer domain's primitive actions, in the MAKRO paper's vocabulary.
//
// The planner produces a Plan; the validator (validator.h) replays one against the map, the mission
// and the robot profile; plan_text.h reads and writes the paper's text form, one action a line:
//
//   DRIVE_PIPE_TO_MANHOLE P12 M2
//   DRIVE_MANHOLE_TYPE_2_FROM_1_TO_2 M2 P12 P1
//   TAKE_WATER_SAMPLE P6
//
// What each action means, costs and needs is docs/domain.md. A PlanStep refers to the map and the
// mission by ID, so a plan is only meaningful with them.
//
// Thread-safety: plain value types.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <variant>
#include <vector>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::domain {

struct DrivePipeToManhole {
  PipeId pipe{0};
  ManholeId manhole{0};
  friend bool operator==(const DrivePipeToManhole&, const DrivePipeToManhole&) = default;
};

struct DriveManhole {
  ManholeId manhole{0};
  SlotIndex from{0};
  SlotIndex to{0};
  friend bool operator==(const DriveManhole&, const DriveManhole&) = default;
};

struct EnterPipe {
  ManholeId manhole{0};
  PipeId pipe{0};
  friend bool operator==(const EnterPipe&, const EnterPipe&) = default;
};

struct TakeWaterSample {
  PipeId pipe{0};
  TaskId task{0};
  friend bool operator==(const TakeWaterSample&, const TakeWaterSample&) = default;
};

struct InspectPipe {
  PipeId pipe{0};
  TaskId task{0};
  // The end (0 or 1) where the inspection finishes; empty: the end opposite the robot's.
  std::optional<std::uint8_t> finish_end;
  friend bool operator==(const InspectPipe&, const InspectPipe&) = default;
};

struct GoToPoint {
  PipeId pipe{0};
  TaskId task{0};
  friend bool operator==(const GoToPoint&, const GoToPoint&) = default;
};

struct GoToManhole {
  ManholeId manhole{0};
  TaskId task{0};
  friend bool operator==(const GoToManhole&, const GoToManhole&) = default;
};

using PlanStep = std::variant<DrivePipeToManhole, DriveManhole, EnterPipe, TakeWaterSample,
                              InspectPipe, GoToPoint, GoToManhole>;

struct Plan {
  std::vector<PlanStep> steps;
  friend bool operator==(const Plan&, const Plan&) = default;
};

}  // namespace sewerplan::domain
