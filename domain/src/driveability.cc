// SPDX-License-Identifier: MIT
#include "sewerplan/domain/driveability.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "sewerplan/core/map_queries.h"
#include "sewerplan/core/mission.h"

#include "position_graph.h"

namespace sewerplan::domain {
namespace {

// As in position_graph.cc: a 90 degree turn computed with rounding error still counts as 90.
constexpr double kLimitTolerance = 1e-9;

void check_passages(const SewerMap& map, const RobotProfile& profile,
                    const PassageMotionTable* motion, const detail::PositionGraph& graph,
                    DriveabilityReport& report) {
  for (ManholeId m : map.manhole_ids()) {
    const auto slots = map.slots(m);
    for (std::uint16_t i = 0; i < slots.size(); ++i) {
      if (!graph.pipe_fits(slots[i].pipe)) continue;
      for (std::uint16_t j = static_cast<std::uint16_t>(i + 1); j < slots.size(); ++j) {
        if (!graph.pipe_fits(slots[j].pipe)) continue;
        ++report.passages_checked;
        const SlotIndex from{i};
        const SlotIndex to{j};
        if (motion != nullptr) {
          const PassageMotion* ways[] = {motion->find(m, from, to), motion->find(m, to, from)};
          if (ways[0] != nullptr || ways[1] != nullptr) {
            for (const PassageMotion* way : ways) {
              if (way == nullptr || way->feasible) continue;
              report.passages.push_back({m, from, to, passage_turn_deg(map, m, from, to),
                                         passage_step_m(map, m, from, to), false, false,
                                         way->reason.empty() ? "no motion" : way->reason});
              break;
            }
            continue;
          }
        }
        const double turn = passage_turn_deg(map, m, from, to);
        const double step = passage_step_m(map, m, from, to);
        const bool turn_exceeded = turn > profile.max_turn_deg + kLimitTolerance;
        const bool step_exceeded = std::abs(step) > profile.max_step_m + kLimitTolerance;
        if (turn_exceeded || step_exceeded) {
          report.passages.push_back({m, from, to, turn, step, turn_exceeded, step_exceeded});
        }
      }
    }
  }
}

// Every position the robot reaches from being lowered into a start; a manhole counts as reached
// when the robot stands in it or at one of its slots, a pipe when the robot is in it.
void find_reachable(const SewerMap& map, detail::PositionGraph& graph, DriveabilityReport& report) {
  std::vector<bool> seen(graph.size(), false);
  std::vector<detail::Node> stack;
  for (ManholeId m : report.starts) {
    seen[graph.in_manhole(m)] = true;
    stack.push_back(graph.in_manhole(m));
  }
  while (!stack.empty()) {
    const detail::Node n = stack.back();
    stack.pop_back();
    graph.for_each_successor(n, [&](detail::Node next, Cost) {
      if (seen[next]) return;
      seen[next] = true;
      stack.push_back(next);
    });
  }
  for (ManholeId m : map.manhole_ids()) {
    bool reached = seen[graph.in_manhole(m)];
    for (std::uint16_t s = 0; !reached && s < map.manhole(m).slot_count; ++s) {
      reached = seen[graph.at_slot(m, SlotIndex{s})];
    }
    if (reached) report.reachable_manholes.push_back(m);
  }
  for (PipeId p : map.pipe_ids()) {
    if (seen[graph.pipe_end(p, 0)] || seen[graph.pipe_end(p, 1)]) {
      report.reachable_pipes.push_back(p);
      report.reachable_length_m += map.pipe(p).length_m;
    }
  }
}

}  // namespace

std::vector<ManholeId> default_starts(const SewerMap& map) {
  std::vector<ManholeId> starts;
  for (ManholeId m : map.manhole_ids()) {
    if (map.manhole(m).exit) starts.push_back(m);
  }
  if (!starts.empty() || map.manhole_count() == 0) return starts;
  const Components parts = connected_components(map);
  const auto largest = static_cast<std::uint32_t>(
      std::max_element(parts.sizes.begin(), parts.sizes.end()) - parts.sizes.begin());
  for (ManholeId m : map.manhole_ids()) {
    if (parts.component_of[m.index()] == largest) starts.push_back(m);
  }
  return starts;
}

DriveabilityReport analyse_driveability(const SewerMap& map, const RobotProfile& profile,
                                        std::span<const ManholeId> starts,
                                        const PassageMotionTable* motion,
                                        std::span<const Blockage> closures) {
  Mission mission;  // the network and the robot, and the findings' closures only
  mission.profile = profile;
  // The caller's table, not owned (the aliasing constructor with no owner).
  mission.passage_motion = std::shared_ptr<const PassageMotionTable>(
      std::shared_ptr<const PassageMotionTable>(), motion);
  mission.blockages.assign(closures.begin(), closures.end());
  detail::PositionGraph graph(map, mission);
  DriveabilityReport report;
  for (PipeId p : map.pipe_ids()) {
    const double d = map.pipe(p).diameter_m;
    if (d < profile.min_pipe_diameter_m) report.too_narrow.push_back(p);
    if (d > profile.max_pipe_diameter_m) report.too_wide.push_back(p);
  }
  check_passages(map, profile, motion, graph, report);
  report.starts.assign(starts.begin(), starts.end());
  find_reachable(map, graph, report);
  report.closures = mission.blockages;
  if (!closures.empty()) {
    // What the closures cut off: the same search without them.
    mission.blockages.clear();
    detail::PositionGraph open(map, mission);
    DriveabilityReport without;
    without.starts = report.starts;
    find_reachable(map, open, without);
    std::set_difference(without.reachable_manholes.begin(), without.reachable_manholes.end(),
                        report.reachable_manholes.begin(), report.reachable_manholes.end(),
                        std::back_inserter(report.cut_off_manholes));
    std::set_difference(without.reachable_pipes.begin(), without.reachable_pipes.end(),
                        report.reachable_pipes.begin(), report.reachable_pipes.end(),
                        std::back_inserter(report.cut_off_pipes));
  }
  return report;
}

std::string_view why_not_driveable(PipeId pipe, const DriveabilityReport& r) {
  const auto contains = [](const std::vector<PipeId>& list, PipeId p) {
    return std::binary_search(list.begin(), list.end(), p);
  };
  if (contains(r.too_narrow, pipe)) return "too narrow";
  if (contains(r.too_wide, pipe)) return "too wide";
  if (contains(r.cut_off_pipes, pipe)) return "cut off by a closure";
  if (!contains(r.reachable_pipes, pipe)) return "unreachable";
  return "";
}

}  // namespace sewerplan::domain
