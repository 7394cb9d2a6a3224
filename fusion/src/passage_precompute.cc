// SPDX-License-Identifier: MIT
#include "sewerplan/fusion/passage_precompute.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iterator>
#include <numbers>

#include "sewerplan/core/map_fingerprint.h"
#include "sewerplan/core/map_queries.h"

#include "plan_numbers.h"

namespace sewerplan::fusion {
namespace {

using detail::kDegToRad;
using detail::rounded;

bool fits(const RobotProfile& p, double diameter_m) {
  return diameter_m >= p.min_pipe_diameter_m && diameter_m <= p.max_pipe_diameter_m;
}

}  // namespace

Result<const TurnPlan*> PassageMotionCache::plan(const PassageGeometry& geometry,
                                                 const StopCondition& stop) {
  const PassageKey key = passage_key(geometry);
  if (auto it = plans_.find(key); it != plans_.end()) {
    ++hits_;
    return &it->second;
  }
  Result<TurnPlan> plan = planner_.plan(geometry, stop);
  if (!plan.has_value()) return plan.error();
  return &plans_.emplace(key, std::move(*plan)).first->second;
}

bool PassageMotionCache::release(std::size_t count) {
  auto end = plans_.begin();
  std::advance(end, std::min(count, plans_.size()));
  plans_.erase(plans_.begin(), end);
  return !plans_.empty();
}

std::ostream& operator<<(std::ostream& os, const PrecomputeStatistics& s) {
  return os << s.passages << " passages, " << s.distinct_geometries << " geometries, " << s.feasible
            << " feasible; motion rejects " << s.rejected_by_motion_rules_allow
            << " the rules allow, allows " << s.allowed_by_motion_rules_reject << " they reject; "
            << std::fixed << std::setprecision(2) << s.time_s << " s";
}

std::vector<Waypoint> to_manhole_frame(const TurnPlan& plan, const SewerMap& map, ManholeId m,
                                       SlotIndex from, SlotIndex to) {
  bool mirrored = false;
  (void)passage_geometry(map, m, from, to, &mirrored);
  const Slot& a = map.slot(m, from);
  const Slot& b = map.slot(m, to);
  const double rotation_deg = a.azimuth_deg - 180.0;
  const double c = std::cos(rotation_deg * kDegToRad);
  const double s = std::sin(rotation_deg * kDegToRad);
  const double floor_z = std::min(a.invert_z_m, b.invert_z_m) - map.manhole(m).position.z_m;
  std::vector<Waypoint> out;
  out.reserve(plan.waypoints.size());
  for (const Waypoint& w : plan.waypoints) {
    const double y = mirrored ? -w.y_m : w.y_m;
    const double heading = mirrored ? -w.heading_deg : w.heading_deg;
    out.push_back(Waypoint{rounded(c * w.x_m - s * y, 1e4), rounded(s * w.x_m + c * y, 1e4),
                           rounded(w.z_m + floor_z, 1e4),
                           rounded(normalize_deg(heading + rotation_deg), 1e2)});
  }
  return out;
}

Result<PrecomputeResult> precompute_passage_motion(const SewerMap& map, const RobotProfile& profile,
                                                   const PrecomputeOptions& options,
                                                   const Clock& clock) {
  if (Result<void> valid = validate_profile(profile); !valid.has_value()) return valid.error();
  if (options.head_paths == nullptr) {
    return Error{ErrorCode::kUnsupportedFormat,
                 "the motion precompute needs the OMPL motion planner (a HeadPathPlanner), but "
                 "none was given"};
  }
  const double start_s = clock.now_s();
  PassageMotionCache cache(
      ManholeTurnPlanner(options.head_paths, robot_body(profile), profile, options.planner));
  PrecomputeStatistics stats;
  // Sized once (issue 14): a vector doubling copied every entry into fresh memory between two stop
  // checks (up to 1.8 ms on 1,000 manholes); counted with a check per manhole.
  std::size_t passages = 0;
  for (ManholeId m : map.manhole_ids()) {
    if (auto stopped = options.stop.interrupted()) {
      return stopped_error(*stopped, "the motion precompute");
    }
    std::size_t fitting = 0;
    for (const Slot& slot : map.slots(m)) fitting += fits(profile, map.pipe(slot.pipe).diameter_m);
    passages += fitting * (fitting > 0 ? fitting - 1 : 0);
  }
  std::vector<PassageMotion> entries;
  entries.reserve(passages);
  for (ManholeId m : map.manhole_ids()) {
    const auto slots = map.slots(m);
    for (std::uint16_t i = 0; i < slots.size(); ++i) {
      if (!fits(profile, map.pipe(slots[i].pipe).diameter_m)) continue;
      for (std::uint16_t j = 0; j < slots.size(); ++j) {
        if (i == j || !fits(profile, map.pipe(slots[j].pipe).diameter_m)) continue;
        const SlotIndex from{i};
        const SlotIndex to{j};
        if (auto stopped = options.stop.interrupted()) {
          return stopped_error(*stopped, "the motion precompute");
        }
        const PassageGeometry g = passage_geometry(map, m, from, to);
        Result<const TurnPlan*> plan = cache.plan(g, options.stop);
        if (!plan.has_value()) {
          const ErrorCode code = plan.error().code;
          if (code == ErrorCode::kCancelled || code == ErrorCode::kSearchLimit) return plan.error();
          return Error{
              code == ErrorCode::kInvalidArgument ? ErrorCode::kInvalidMap : plan.error().code,
              "manhole " + map.manhole(m).name + " slot " + std::to_string(to_paper_number(from)) +
                  " -> " + std::to_string(to_paper_number(to)) + ": " + plan.error().message};
        }
        const TurnPlan& p = **plan;
        PassageMotion entry{.manhole = m, .from = from, .to = to, .feasible = p.feasible};
        if (p.feasible) {
          entry.duration_s = p.duration_s;
          entry.waypoints = to_manhole_frame(p, map, m, from, to);
        } else {
          entry.reason = p.reason;
        }
        const bool rules = judge_passage(map, profile, nullptr, m, from, to).allowed;
        ++stats.passages;
        stats.feasible += p.feasible ? 1U : 0U;
        stats.rules_allow += rules ? 1U : 0U;
        stats.rejected_by_motion_rules_allow += rules && !p.feasible ? 1U : 0U;
        stats.allowed_by_motion_rules_reject += !rules && p.feasible ? 1U : 0U;
        entries.push_back(std::move(entry));
      }
    }
    if (options.progress) options.progress(m.index() + 1, map.manhole_count());
  }
  // After the last passage (issue 14: 3.5 ms from the last check to the return on 1,000
  // manholes): the map's fingerprint (1.3 ms) asks the stop as it goes, and the plans are freed in
  // slices (2 ms at once), each after a check; what is left, the entries' order, is one pass.
  const auto stopped = [&] {
    // Asked again: the check that fired does not say why. A flag cleared since reads as a cancel.
    return stopped_error(options.stop.interrupted().value_or(SearchStatus::kCancelled),
                         "the motion precompute");
  };
  std::optional<std::string> map_fingerprint = map_geometry_fingerprint(map, options.stop);
  if (!map_fingerprint) return stopped();
  stats.distinct_geometries = cache.size();
  constexpr std::size_t kReleaseSlice = 128;
  do {
    if (options.stop.interrupted()) return stopped();
  } while (cache.release(kReleaseSlice));
  stats.time_s = clock.now_s() - start_s;
  return PrecomputeResult{
      PassageMotionTable(std::move(*map_fingerprint), profile_geometry_fingerprint(profile),
                         std::move(entries)),
      stats};
}

}  // namespace sewerplan::fusion
