// SPDX-License-Identifier: MIT
// Where the robot is, and how far a mission has come: the state planning starts from.
//
// A RobotPosition is one of the three kinds of place in docs/domain.md: in a manhole (only at the
// start), at a manhole's slot (having driven out of that slot's pipe), or in a pipe at an offset
// from its ends[0]. MissionProgress adds the tasks already done and the energy already used; a
// fresh mission starts from initial_progress(), and the executor replans from the progress it
// observed.
//
//   MissionProgress progress = initial_progress(mission, map);
//   std::cout << describe(progress.position, map);  // "in pipe P12 at 2.83 m"
//
// Thread-safety: plain value types and free functions; reentrant.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::domain {

struct InManhole {
  ManholeId manhole{0};
  friend bool operator==(const InManhole&, const InManhole&) = default;
};

struct AtSlot {
  ManholeId manhole{0};
  SlotIndex slot{0};
  friend bool operator==(const AtSlot&, const AtSlot&) = default;
};

struct InPipe {
  PipeId pipe{0};
  double offset_m = 0;
  friend bool operator==(const InPipe&, const InPipe&) = default;
};

using RobotPosition = std::variant<InManhole, AtSlot, InPipe>;

// "in manhole M1", "at M6 slot 3 (P5)", "in pipe P12 at 2.83 m"
std::string describe(const RobotPosition& position, const SewerMap& map);

// The manhole the robot is in or at, if any.
std::optional<ManholeId> manhole_of(const RobotPosition& position);

// The offset of a pipe's end (0 or 1): 0 or the pipe's length.
double end_offset_m(const Pipe& pipe, std::size_t end);

struct MissionProgress {
  RobotPosition position;
  std::vector<bool> done;  // per task, indexed by TaskId
  double energy_used_wh = 0;
  friend bool operator==(const MissionProgress&, const MissionProgress&) = default;
};

// The mission's start place as a position (a pipe without offset: its middle), nothing done.
MissionProgress initial_progress(const Mission& mission, const SewerMap& map);

}  // namespace sewerplan::domain
