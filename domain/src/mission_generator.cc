// SPDX-License-Identifier: MIT
#include "sewerplan/domain/mission_generator.h"

#include <algorithm>

#include "sewerplan/core/enum_names.h"
#include "sewerplan/core/limits.h"
#include "sewerplan/core/rng.h"

#include "graph_search.h"
#include "position_graph.h"

namespace sewerplan::domain {
namespace {

using detail::GraphSearch;
using detail::Node;
using detail::PositionGraph;

// Each drivable pipe's cost from inside manhole `source` (the nearer of its ends), kInfiniteCost
// where out of reach.
std::vector<Cost> pipe_costs(const PositionGraph& graph, ManholeId source) {
  const SewerMap& map = graph.map();
  GraphSearch search(graph);
  std::vector<Node> targets;
  targets.reserve(2 * map.pipe_count());
  for (PipeId p : map.pipe_ids()) {
    for (std::size_t e = 0; e < 2; ++e) targets.push_back(graph.pipe_end(p, e));
  }
  const Node from = graph.in_manhole(source);
  search.run(std::span<const Node>(&from, 1), targets, kInfiniteCost,
             GraphSearch::Direction::kForward);
  std::vector<Cost> costs(map.pipe_count(), kInfiniteCost);
  for (PipeId p : map.pipe_ids()) {
    if (!graph.pipe_drivable(p)) continue;
    costs[p.index()] =
        std::min(search.distance(graph.pipe_end(p, 0)), search.distance(graph.pipe_end(p, 1)));
  }
  return costs;
}

// The pipes with a cost, nearest first, at most `limit`.
std::vector<PipeId> nearest(const std::vector<Cost>& costs, std::size_t limit) {
  std::vector<std::pair<Cost, PipeId>> found;
  for (std::size_t p = 0; p < costs.size(); ++p) {
    if (costs[p] != kInfiniteCost)
      found.emplace_back(costs[p], PipeId{static_cast<std::uint32_t>(p)});
  }
  const std::size_t keep = std::min(limit, found.size());
  std::partial_sort(found.begin(), found.begin() + static_cast<std::ptrdiff_t>(keep), found.end());
  std::vector<PipeId> pipes;
  for (std::size_t i = 0; i < keep; ++i) pipes.push_back(found[i].second);
  return pipes;
}

// The pipes a mission of this spread draws its tasks from, starting at `start`.
std::vector<PipeId> candidate_pipes(const PositionGraph& graph, ManholeId start,
                                    const MissionOptions& options, Cost range, Rng& rng) {
  const std::vector<Cost> from_start = pipe_costs(graph, start);
  const std::size_t local = std::min(options.radius_pipes, 2 * options.tasks + 10);
  std::vector<PipeId> in_range;
  for (std::size_t p = 0; p < from_start.size(); ++p) {
    if (from_start[p] <= range) in_range.push_back(PipeId{static_cast<std::uint32_t>(p)});
  }
  switch (options.spread) {
    case MissionSpread::kUniform:
      return in_range;
    case MissionSpread::kClustered: {
      if (in_range.empty()) return {};
      const Pipe& centre = graph.map().pipe(in_range[rng.below(in_range.size())]);
      const ManholeId m =
          centre.ends[0].manhole ? *centre.ends[0].manhole : *centre.ends[1].manhole;
      std::vector<Cost> around = pipe_costs(graph, m);
      for (std::size_t p = 0; p < around.size(); ++p) {
        if (from_start[p] > range) around[p] = kInfiniteCost;
      }
      return nearest(around, local);
    }
    case MissionSpread::kNearExit: {
      std::vector<PipeId> pipes = nearest(from_start, 2 * local);
      const std::size_t keep =
          std::min(std::max(pipes.size() / 2, std::min(pipes.size(), options.tasks)), local);
      pipes.erase(pipes.begin() + static_cast<std::ptrdiff_t>(keep), pipes.end());
      return pipes;
    }
  }
  return {};
}

Task make_task(const SewerMap& map, PipeId pipe, std::size_t index, Rng& rng) {
  Task t;
  const double draw = rng.uniform01();
  const Pipe& p = map.pipe(pipe);
  if (draw < 0.25) {
    t.kind = TaskKind::kInspectPipe;
    t.name = "inspect-" + p.name;
    t.place = PipeSpot{pipe, {}, {}};
  } else if (draw < 0.55) {
    t.kind = TaskKind::kTakeWaterSample;
    t.name = "sample-" + p.name;
    t.place = PipeSpot{pipe, p.length_m / 2, {}};
  } else {
    t.kind = TaskKind::kGoTo;
    t.name = "visit-" + p.name;
    t.place = PipeSpot{pipe, {}, {}};
  }
  t.name += "-" + std::to_string(index + 1);
  return t;
}

// sewerplan::detail in full: domain::detail (graph_search.h) hides it here.
constexpr sewerplan::detail::EnumNames<MissionSpread, 3> kSpreads{{
    {MissionSpread::kUniform, "uniform"},
    {MissionSpread::kClustered, "clustered"},
    {MissionSpread::kNearExit, "near-exit"},
}};
static_assert(sewerplan::detail::distinct(kSpreads));

}  // namespace

std::string_view to_string(MissionSpread spread) {
  return sewerplan::detail::name_of(kSpreads, spread);
}

std::optional<MissionSpread> mission_spread_from_string(std::string_view name) {
  return sewerplan::detail::value_of(kSpreads, name);
}

std::string mission_spread_names() { return sewerplan::detail::names_joined(kSpreads); }

Result<Mission> generate_mission(const SewerMap& map, const MissionOptions& options) {
  Mission mission;
  auto profile = builtin_profile(options.profile);
  if (!profile)
    return Error{ErrorCode::kInvalidArgument, "unknown profile '" + options.profile + "'"};
  mission.profile = *profile;
  if (options.battery_wh) {
    if (!(*options.battery_wh > 0 && *options.battery_wh <= kMaxBattery_wh)) {
      return Error{ErrorCode::kInvalidArgument, "battery_wh must be above 0 and at most 1e6"};
    }
    mission.profile.battery_wh = *options.battery_wh;
  }
  mission.battery_reserve_fraction = options.battery_reserve;
  for (ManholeId m : map.manhole_ids()) {
    if (map.manhole(m).exit) mission.exits.push_back(m);
  }
  if (mission.exits.empty()) {
    return Error{ErrorCode::kInvalidArgument, "map " + map.name() + " has no exit manhole"};
  }
  Rng rng(options.seed);
  const PositionGraph graph(map, mission);
  // Try exits in a seeded order until one reaches enough pipes.
  std::vector<ManholeId> order = mission.exits;
  for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng.below(i)]);
  // Uniform and clustered tasks lie where the robot can drive to and back on half its usable
  // battery, so that each task alone fits it.
  const double usable_wh = mission.profile.battery_wh * (1 - options.battery_reserve);
  const Cost range = to_cost(mission.profile.seconds_for(usable_wh) / 4);
  for (std::size_t attempt = 0; attempt < order.size() && attempt < 20; ++attempt) {
    std::vector<PipeId> pipes = candidate_pipes(graph, order[attempt], options, range, rng);
    if (pipes.size() < options.tasks) continue;
    for (std::size_t i = 0; i < options.tasks; ++i) {  // partial Fisher-Yates
      std::swap(pipes[i], pipes[i + rng.below(pipes.size() - i)]);
      mission.tasks.push_back(make_task(map, pipes[i], i, rng));
    }
    mission.start = order[attempt];
    mission.name = "generated-" + std::to_string(options.tasks) + "-tasks-" +
                   (options.spread == MissionSpread::kNearExit
                        ? std::string()
                        : std::string(to_string(options.spread)) + "-") +
                   "seed-" + std::to_string(options.seed);
    return mission;
  }
  return Error{ErrorCode::kInvalidArgument, "no exit of map " + map.name() + " reaches " +
                                                std::to_string(options.tasks) +
                                                " pipes the robot can drive"};
}

}  // namespace sewerplan::domain
