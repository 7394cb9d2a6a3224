// SPDX-License-Identifier: MIT
// PassageMotion: planned motions through manholes, and the one rule that says whether a passage is
// allowed and what it costs.
//
// Passing a manhole from one pipe into another is MAKRO's hardest manoeuvre (Adria, Streich and
// Hertzberg 2004, sections 1 and 2). The domain's rules approximate it with two limits, the turn
// and the step (robot_profile.h); the motion planner (fusion/manhole_turn_planner.h, with OMPL)
// plans the body's real motion for each passage of a map. Its results are a PassageMotionTable: a
// plain value table keyed by (manhole, from slot, to slot), saved beside the map as
// MAP.motion.json and carrying fingerprints of the map's and the profile's geometry, so that a
// table made for another map or another robot is refused. A mission carries the table it is
// planned with (Mission::passage_motion); judge_passage() is the one place that decides a passage,
// so that the compiler, the validator, driveability and fusion agree:
//   - a passage the table has: allowed iff the planner found a motion; its duration is the
//     motion's (docs/motion.md);
//   - otherwise (no table, or a passage the table lacks): the angle-and-step rules of
//     docs/domain.md: turn <= max_turn_deg and |step| <= max_step_m, costing
//     manhole_pass_s + turn x turn_s_per_deg + |step| x step_s_per_m.
//
//   Result<PassageMotionTable> t = load_passage_motion("ais.motion.json", map, profile);
//   mission.passage_motion = std::make_shared<const PassageMotionTable>(std::move(*t));
//   PassageVerdict v = judge_passage(map, mission.profile, mission.passage_motion.get(), m, a, b);
//   if (v.allowed) cost_s += v.duration_s;
//
// Thread safety: A PassageMotionTable is immutable once read: share it (const) between threads.
#pragma once

#include <filesystem>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/job.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

// The planned motion of one passage.
struct PassageMotion {
  ManholeId manhole{0};
  SlotIndex from{0};
  SlotIndex to{0};
  bool feasible = false;
  double duration_s = 0;            // meaningful when feasible
  std::vector<Waypoint> waypoints;  // the head's path, manhole frame (job.h); empty if infeasible
  std::string reason;               // why not, when infeasible
  friend bool operator==(const PassageMotion&, const PassageMotion&) = default;
};

// Motions of the passages of one map for one robot geometry. Immutable once built.
class PassageMotionTable {
 public:
  PassageMotionTable() = default;
  // Sorts the entries by (manhole, from, to). Precondition: no two entries have the same key
  // (checked).
  PassageMotionTable(std::string map_fingerprint, std::string profile_fingerprint,
                     std::vector<PassageMotion> entries);

  const std::string& map_fingerprint() const { return map_fingerprint_; }
  const std::string& profile_fingerprint() const { return profile_fingerprint_; }
  std::span<const PassageMotion> entries() const { return entries_; }
  std::size_t size() const { return entries_.size(); }

  // The entry of a passage, or nullptr. Runtime: O(log entries).
  const PassageMotion* find(ManholeId manhole, SlotIndex from, SlotIndex to) const;

  friend bool operator==(const PassageMotionTable&, const PassageMotionTable&) = default;

 private:
  std::string map_fingerprint_;
  std::string profile_fingerprint_;
  std::vector<PassageMotion> entries_;
};

// Fingerprints (16 hex digits, FNV-1a over the numbers as text) of what a table depends on: every
// manhole's name, diameter and slots (azimuth, invert, pipe diameter); and the profile's body,
// joint limits, pipe range and manoeuvre times.
std::string map_geometry_fingerprint(const SewerMap& map);
std::string profile_geometry_fingerprint(const RobotProfile& profile);

inline constexpr std::string_view kPassageMotionJsonFormat = "sewerplan-passage-motion";
inline constexpr int kPassageMotionJsonVersion = 1;

// Reads a table and resolves manhole names against `map`; slots are numbered from 1, as in
// missions. Errors name the JSON path ("ais.motion.json:$.passages[3].to_slot: ..."). The
// fingerprints are read, not checked: see load_passage_motion.
Result<PassageMotionTable> read_passage_motion_json(std::string_view text,
                                                    const std::string& file_name,
                                                    const SewerMap& map, Diagnostics& diagnostics);
void write_passage_motion_json(const PassageMotionTable& table, const SewerMap& map,
                               std::ostream& out);

// Reads a table from a file and refuses (kInvalidArgument) a stale one: made for another map
// geometry or another robot geometry than `map` and `profile`, saying which and how to remake it.
Result<PassageMotionTable> load_passage_motion(const std::filesystem::path& path,
                                               const SewerMap& map, const RobotProfile& profile);

// Where a map's table is kept: beside it, "ais.json" -> "ais.motion.json".
std::filesystem::path default_motion_path(const std::filesystem::path& map_path);

// Whether a passage is allowed and what it costs (see the top of this file).
struct PassageVerdict {
  bool allowed = false;
  double duration_s = 0;  // meaningful when allowed
  double turn_deg = 0;
  double step_m = 0;
  bool by_motion = false;  // decided by the table, not by the rules
  const PassageMotion* motion = nullptr;
};

// Limits are compared with a 1e-9 tolerance, so that a 90 degree turn computed from azimuths with
// rounding error still counts as 90. The pipes' diameters and closures are not judged here.
// Runtime: O(log table entries).
PassageVerdict judge_passage(const SewerMap& map, const RobotProfile& profile,
                             const PassageMotionTable* motion, ManholeId manhole, SlotIndex from,
                             SlotIndex to);

}  // namespace sewerplan
