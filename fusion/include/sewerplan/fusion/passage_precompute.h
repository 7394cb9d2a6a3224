// SPDX-License-Identifier: MIT
// Precomputing a map's manhole motions: every passage planned once per distinct geometry.
//
// A network has far fewer passage geometries than passages: manholes come in a few diameters,
// pipes in a few sizes, and many slots are at right angles or opposite. PassageMotionCache keeps
// one TurnPlan per quantised geometry (manhole_geometry.h), in memory, so each is planned once;
// precompute_passage_motion() plans every ordered slot pair of every manhole between two pipes the
// robot fits (the passages the domain could use), turns each cached plan into the passage's own
// frame, and returns the table the domain and fusion use (core/passage_motion.h), with a summary
// that compares the planner with the angle-and-step rules. `sewerplan motion precompute MAP`
// writes the table beside the map (docs/motion.md).
//
//   SteadyClock clock;
//   const motion::OmplHeadPathPlanner ompl;  // head_path_planner.h
//   Result<PrecomputeResult> r =
//       precompute_passage_motion(map, profile, {.head_paths = &ompl}, clock);
//   write_passage_motion_json(r->table, map, out);
//   std::cout << r->statistics.distinct_geometries << " geometries planned\n";
//
// Thread safety: A PassageMotionCache is not thread-safe: plan() fills it and counts hits, so
// one thread at a time. precompute_passage_motion and to_manhole_frame share nothing (the former
// calls `progress` on the calling thread).
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <ostream>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/passage_motion.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/core/stop_condition.h"
#include "sewerplan/fusion/manhole_geometry.h"
#include "sewerplan/fusion/manhole_turn_planner.h"

namespace sewerplan::fusion {

// One TurnPlan per distinct quantised geometry, for one robot.
class PassageMotionCache {
 public:
  explicit PassageMotionCache(ManholeTurnPlanner planner) : planner_(std::move(planner)) {}

  // The plan of `geometry`, planned on first use. The pointer stays valid while the cache lives.
  // A planning that `stop` ended (kCancelled, kSearchLimit) is not kept.
  Result<const TurnPlan*> plan(const PassageGeometry& geometry, const StopCondition& stop = {});

  std::size_t size() const { return plans_.size(); }
  std::size_t hits() const { return hits_; }
  // Frees up to `count` plans (the pointers to them die); whether any is left. Freeing them all at
  // once took 2 ms on 1,000 manholes, so the precompute frees them in slices between stop checks.
  bool release(std::size_t count);

 private:
  ManholeTurnPlanner planner_;
  std::map<PassageKey, TurnPlan> plans_;
  std::size_t hits_ = 0;
};

struct PrecomputeStatistics {
  std::size_t passages = 0;             // ordered slot pairs planned
  std::size_t distinct_geometries = 0;  // plans made
  std::size_t feasible = 0;
  std::size_t rules_allow = 0;                     // passages the angle-and-step rules allow
  std::size_t rejected_by_motion_rules_allow = 0;  // the planner says no, the rules yes
  std::size_t allowed_by_motion_rules_reject = 0;  // the planner says yes, the rules no
  double time_s = 0;
  friend bool operator==(const PrecomputeStatistics&, const PrecomputeStatistics&) = default;
};

// "412 passages, 37 geometries, 380 feasible; motion rejects 20 the rules allow, allows 4 they
// reject; 1.52 s"
std::ostream& operator<<(std::ostream& os, const PrecomputeStatistics& s);

struct PrecomputeResult {
  PassageMotionTable table;
  PrecomputeStatistics statistics;
};

struct PrecomputeOptions {
  // The planner of the head's paths (head_path_planner.h), not owned; required.
  const HeadPathPlanner* head_paths = nullptr;
  TurnPlannerOptions planner;
  // Called after each manhole with (manholes done, manholes in the map).
  std::function<void(std::size_t, std::size_t)> progress;
  // Its cancel flag and time limit end the precompute (core/stop_condition.h): asked before each
  // passage, at every RRT iteration, and while the table is assembled (the map's fingerprint, the
  // plans' release), with no check-free stretch after the last passage.
  StopCondition stop;
};

// The waypoints of a canonical plan in the manhole's frame (job.h): rotated to the from-slot's
// azimuth, mirrored for a right turn, z above the manhole's floor (its position's z).
std::vector<Waypoint> to_manhole_frame(const TurnPlan& plan, const SewerMap& map, ManholeId m,
                                       SlotIndex from, SlotIndex to);

// Errors: kUnsupportedFormat without options.head_paths; kInvalidProfile for a profile that fails
// validate_profile; kInvalidMap for a passage with a non-finite or non-positive size; kCancelled
// or kSearchLimit when options.stop fires (no table: a part of one would read as complete).
Result<PrecomputeResult> precompute_passage_motion(const SewerMap& map, const RobotProfile& profile,
                                                   const PrecomputeOptions& options,
                                                   const Clock& clock);

}  // namespace sewerplan::fusion
