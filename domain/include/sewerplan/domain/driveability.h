// SPDX-License-Identifier: MIT
// Driveability: which parts of a sewer network a robot can drive, and why not the rest.
//
// Before planning on an imported network (map_swmm.h, map_isybau.h), an operator wants to know
// what the robot can do there at all. analyse_driveability applies the limits of docs/domain.md,
// the same rules, through the same position graph, as the planner and the validator:
//   - pipes outside the profile's diameter range [min_pipe_diameter_m, max_pipe_diameter_m]
//     (compared exactly);
//   - passages through a manhole between two pipes the robot fits that the motion table (when one
//     is given: core/passage_motion.h, docs/motion.md) rejects in either direction, with the
//     planner's reason; without a table, or for passages it lacks, those whose turn exceeds
//     max_turn_deg or whose step (in absolute value) exceeds max_step_m (with 1e-9 tolerance); a
//     passage and its reverse have the same turn and the same absolute step, so each pair of slots
//     is listed once;
//   - the part of the network the robot reaches when lowered into any of the start manholes:
//     the manholes it can stand in and the pipes it can drive.
//   - places closed by inspection findings (`closures`: the risk table's impassable findings,
//     core/condition_risk.h), as the planner closes them: the robot drives up to one, not across;
//     what it then cannot reach any more is listed as cut off.
// Other mission closures are not applied: this is about the network and the robot.
//
//   DriveabilityReport r = analyse_driveability(map, *builtin_profile("makro-plus"), starts);
//   std::cout << r.too_narrow.size() << " pipes too narrow, " << r.reachable_pipes.size()
//             << " of " << map.pipe_count() << " pipes reachable\n";
//
// Thread-safety: free functions over values they only read; reentrant.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/passage_motion.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::domain {

// A passage between two slots of one manhole beyond the robot's turn or step limit.
struct PassageLimit {
  ManholeId manhole{0};
  SlotIndex from{0};  // from < to; the passage is out of bounds both ways
  SlotIndex to{0};
  double turn_deg = 0;
  double step_m = 0;  // climbing from `from` into `to`
  bool turn_exceeded = false;
  bool step_exceeded = false;
  std::string motion_reason;  // rejected by the motion table: why (then no limit is exceeded)
  friend bool operator==(const PassageLimit&, const PassageLimit&) = default;
};

struct DriveabilityReport {
  std::vector<PipeId> too_narrow;      // diameter below the profile's minimum, in map order
  std::vector<PipeId> too_wide;        // above its maximum
  std::vector<PassageLimit> passages;  // in map order of manhole, then slots
  std::size_t passages_checked = 0;    // slot pairs between two pipes the robot fits
  std::vector<ManholeId> starts;
  std::vector<ManholeId> reachable_manholes;  // in map order
  std::vector<PipeId> reachable_pipes;        // in map order
  double reachable_length_m = 0;
  std::vector<Blockage> closures;           // as given
  std::vector<ManholeId> cut_off_manholes;  // reachable but for the closures, in map order
  std::vector<PipeId> cut_off_pipes;        // reachable but for the closures, in map order
  friend bool operator==(const DriveabilityReport&, const DriveabilityReport&) = default;
};

// The manholes an operator would start from by default: those marked exit in the map, or, if
// none is, the manholes of the largest connected part of the network (the first such part in map
// order on a tie). Runtime: O(manholes + slots).
std::vector<ManholeId> default_starts(const SewerMap& map);

// Precondition: every start belongs to `map`. Runtime: O(manholes + sum over manholes of the
// square of their slot count + pipes).
DriveabilityReport analyse_driveability(const SewerMap& map, const RobotProfile& profile,
                                        std::span<const ManholeId> starts,
                                        const PassageMotionTable* motion = nullptr,
                                        std::span<const Blockage> closures = {});

// Why the robot cannot drive `pipe`: "too narrow", "too wide", "cut off by a closure" or
// "unreachable"; empty when it can. Runtime: O(log pipes).
std::string_view why_not_driveable(PipeId pipe, const DriveabilityReport& report);

}  // namespace sewerplan::domain
