// SPDX-License-Identifier: MIT
#include "sewerplan/domain/mission_generator.h"

#include <algorithm>

#include "sewerplan/core/rng.h"

#include "graph_search.h"
#include "position_graph.h"

namespace sewerplan::domain {
namespace {

using detail::GraphSearch;
using detail::Node;
using detail::PositionGraph;

// Pipes reachable from inside manhole `start`, nearest first (by the cost of entering them).
std::vector<PipeId> reachable_pipes(const PositionGraph& graph, ManholeId start,
                                    std::size_t limit) {
  const SewerMap& map = graph.map();
  GraphSearch search(graph);
  std::vector<Node> targets;
  targets.reserve(2 * map.pipe_count());
  for (PipeId p : map.pipe_ids()) {
    for (std::size_t e = 0; e < 2; ++e) targets.push_back(graph.pipe_end(p, e));
  }
  const Node source = graph.in_manhole(start);
  search.run(std::span<const Node>(&source, 1), targets, kInfiniteCost,
             GraphSearch::Direction::kForward);
  std::vector<std::pair<Cost, PipeId>> found;
  for (PipeId p : map.pipe_ids()) {
    const Cost d =
        std::min(search.distance(graph.pipe_end(p, 0)), search.distance(graph.pipe_end(p, 1)));
    if (d != kInfiniteCost && graph.pipe_drivable(p)) found.emplace_back(d, p);
  }
  std::sort(found.begin(), found.end());
  if (found.size() > limit)
    found.erase(found.begin() + static_cast<std::ptrdiff_t>(limit), found.end());
  std::vector<PipeId> pipes;
  for (const auto& f : found) pipes.push_back(f.second);
  return pipes;
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

}  // namespace

Result<Mission> generate_mission(const SewerMap& map, const MissionOptions& options) {
  Mission mission;
  auto profile = builtin_profile(options.profile);
  if (!profile)
    return Error{ErrorCode::kInvalidArgument, "unknown profile '" + options.profile + "'"};
  mission.profile = *profile;
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
  for (std::size_t attempt = 0; attempt < order.size() && attempt < 20; ++attempt) {
    const std::size_t nearest = std::min(options.radius_pipes, 2 * options.tasks + 10);
    std::vector<PipeId> pipes = reachable_pipes(graph, order[attempt], 2 * nearest);
    const std::size_t keep =
        std::min(std::max(pipes.size() / 2, std::min(pipes.size(), options.tasks)), nearest);
    pipes.erase(pipes.begin() + static_cast<std::ptrdiff_t>(keep), pipes.end());
    if (pipes.size() < options.tasks) continue;
    for (std::size_t i = 0; i < options.tasks; ++i) {  // partial Fisher-Yates
      std::swap(pipes[i], pipes[i + rng.below(pipes.size() - i)]);
      mission.tasks.push_back(make_task(map, pipes[i], i, rng));
    }
    mission.start = order[attempt];
    mission.name = "generated-" + std::to_string(options.tasks) + "-tasks-seed-" +
                   std::to_string(options.seed);
    return mission;
  }
  return Error{ErrorCode::kInvalidArgument, "no exit of map " + map.name() + " reaches " +
                                                std::to_string(options.tasks) +
                                                " pipes the robot can drive"};
}

}  // namespace sewerplan::domain
