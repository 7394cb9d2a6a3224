// SPDX-License-Identifier: MIT
// RobotAction: one step of a plan with every parameter the robot needs resolved from the map and
// the robot profile, the parameterised actions of the MAKRO paper (Adria, Streich and Hertzberg
// 2004, section 4.6).
//
// A symbolic plan step (domain/plan.h) names objects: "DRIVE_PIPE_TO_MANHOLE P12 M2". Plan fusion
// (fuse.h) replays the plan and turns each step into one RobotAction that says how: drive forward
// 2.83 m at 0.30 m/s in a 0.60 m pipe towards a TYPE_2 manhole. Each action expands into the
// base machine's jobs (jobs.h, core/job.h), which a robot runs one at a time; action_json.h writes
// one for the executor's event log. What every action means, its parameters and its jobs are
// docs/fusion.md.
//
//   Result<FusedPlan> fused = fuse(plan, map, mission, initial_progress(mission, map));
//   for (const RobotAction& action : fused->actions) {
//     std::cout << "step " << plan_step(action) + 1 << ": " << action << '\n';
//   }
//
// Directions are relative to the robot's heading in its pipe: forward is away from the pipe end
// the robot entered by (core/job.h's DriveForward), backward is towards it. Units: metres, metres
// per second, degrees, seconds. Actions refer to the map and the mission by ID and are only
// meaningful with them.
//
// Thread safety: Plain values and pure functions: const access from several threads is safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string_view>
#include <variant>
#include <vector>

#include "sewerplan/core/job.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::fusion {

enum class Direction : std::uint8_t { kForward, kBackward };

// "forward", "backward"
std::string_view to_string(Direction direction);
std::ostream& operator<<(std::ostream& os, Direction direction);

// A drive along the pipe the robot is in. A distance of 0 is no motion (and no job).
struct PipeDrive {
  Direction direction = Direction::kForward;
  double distance_m = 0;
  double speed_mps = 0;
  friend bool operator==(const PipeDrive&, const PipeDrive&) = default;
};

// DRIVE_PIPE_TO_MANHOLE: drive in `pipe` to its end in `manhole` (the paper's
// DriveToManhole(direction, distance, type, size, speed)).
struct DriveToManhole {
  std::size_t plan_step = 0;  // index of the plan step this action comes from
  PipeId pipe{0};
  ManholeId manhole{0};
  Direction direction = Direction::kForward;
  double distance_m = 0;
  std::uint16_t manhole_type = 0;       // the manhole's slot count
  std::optional<char> manhole_variant;  // its geometric variant ('B' of TYPE_3_TYPE_B)
  double pipe_diameter_m = 0;
  double speed_mps = 0;
  double from_offset_m = 0;  // offsets from the pipe's ends[0]
  double to_offset_m = 0;
  double duration_s = 0;
  friend bool operator==(const DriveToManhole&, const DriveToManhole&) = default;
};

// DRIVE_MANHOLE_TYPE_k_FROM_i_TO_j: pass `manhole` from the mouth of slot `from_slot` into the
// pipe of slot `to_slot`, turning `turn_deg` (deviation from straight through, 0..180) and
// climbing `step_m` (negative: down).
struct PassManhole {
  std::size_t plan_step = 0;
  ManholeId manhole{0};
  SlotIndex from_slot{0};
  SlotIndex to_slot{0};
  PipeId from_pipe{0};
  PipeId to_pipe{0};
  double turn_deg = 0;
  double step_m = 0;
  double manhole_diameter_m = 0;
  double duration_s = 0;
  // The motion planned for the passage (core/passage_motion.h, docs/motion.md), when the mission
  // has a motion table: the head's path in the manhole's frame. Empty otherwise.
  std::vector<Waypoint> waypoints;
  friend bool operator==(const PassManhole&, const PassManhole&) = default;
};

// ENTER_PIPE: leave the manhole the robot was lowered into, into the pipe of slot `slot`.
struct EnterPipe {
  std::size_t plan_step = 0;
  ManholeId manhole{0};
  SlotIndex slot{0};
  PipeId pipe{0};
  double duration_s = 0;
  friend bool operator==(const EnterPipe&, const EnterPipe&) = default;
};

// TAKE_WATER_SAMPLE: drive to `offset_m` in `pipe` (`drive`), stop, take a sample.
struct TakeWaterSample {
  std::size_t plan_step = 0;
  PipeId pipe{0};
  double offset_m = 0;  // where the sample is taken, from the pipe's ends[0]
  TaskId task{0};
  PipeDrive drive;
  double sample_s = 0;
  double duration_s = 0;  // drive and sample
  friend bool operator==(const TakeWaterSample&, const TakeWaterSample&) = default;
};

// INSPECT_PIPE: drive to the start end if the robot is not there (`approach`, at driving speed),
// then scan the whole pipe at `speed_mps` to the finish end. The scan goes backward when the
// finish end is the one the robot came in by (the robot cannot turn around in the pipe).
struct InspectPipe {
  std::size_t plan_step = 0;
  PipeId pipe{0};
  TaskId task{0};
  double length_m = 0;
  double speed_mps = 0;        // the profile's inspection speed
  std::uint8_t start_end = 0;  // 0 or 1: Pipe::ends index
  std::uint8_t finish_end = 1;
  Direction scan_direction = Direction::kForward;
  PipeDrive approach;
  double duration_s = 0;
  friend bool operator==(const InspectPipe&, const InspectPipe&) = default;
};

// GO_TO_POINT: drive to `offset_m` in `pipe`.
struct GoToPoint {
  std::size_t plan_step = 0;
  PipeId pipe{0};
  double offset_m = 0;
  TaskId task{0};
  PipeDrive drive;
  double duration_s = 0;
  friend bool operator==(const GoToPoint&, const GoToPoint&) = default;
};

// GO_TO_MANHOLE: the robot is already at `manhole`; marks the task done, no motion.
struct GoToManhole {
  std::size_t plan_step = 0;
  ManholeId manhole{0};
  TaskId task{0};
  double duration_s = 0;
  friend bool operator==(const GoToManhole&, const GoToManhole&) = default;
};

using RobotAction = std::variant<DriveToManhole, PassManhole, EnterPipe, TakeWaterSample,
                                 InspectPipe, GoToPoint, GoToManhole>;

// "drive_to_manhole", "pass_manhole", "enter_pipe", "take_water_sample", "inspect_pipe",
// "go_to_point", "go_to_manhole".
std::string_view action_kind(const RobotAction& action);

// The index of the plan step the action comes from, and its duration in seconds.
std::size_t plan_step(const RobotAction& action);
double duration_s(const RobotAction& action);

// "DriveToManhole(pipe #11 -> manhole #1, forward 2.83 m at 0.30 m/s, type 2, pipe 0.60 m)", ...
// IDs, not names: action_json.h names the objects.
std::ostream& operator<<(std::ostream& os, const RobotAction& action);

// A plan fused: one action per plan step, in plan order (actions[i] comes from step i).
struct FusedPlan {
  std::vector<RobotAction> actions;
  // The sum of the actions' durations, in plan order: the validator's total cost of the plan.
  double total_duration_s() const;
  friend bool operator==(const FusedPlan&, const FusedPlan&) = default;
};

std::ostream& operator<<(std::ostream& os, const FusedPlan& plan);

}  // namespace sewerplan::fusion
