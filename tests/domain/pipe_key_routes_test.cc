// SPDX-License-Identifier: MIT
// PipeKeyRoutes: the rows of the keys in a pipe, from searches of its end slots, are the keys' own
// searches' rows, route for route (issue 16).
#include "pipe_key_routes.h"

#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"

#include "graph_search.h"
#include "position_graph.h"
#include "route_store.h"

namespace sewerplan::domain::detail {
namespace {

struct Instance {
  SewerMap map;
  Mission mission;
};

Instance uniform(std::size_t manholes, std::size_t tasks, std::uint64_t seed) {
  SewerMap map =
      *generate_network({.manholes = manholes, .seed = seed, .topology = Topology::kMeshed});
  Mission mission =
      *generate_mission(map, {.tasks = tasks, .seed = seed, .spread = MissionSpread::kUniform});
  return {std::move(map), std::move(mission)};
}

// Keys as the compile takes them: the start, then each task's pipe ends and spot (a sample's).
struct Keys {
  std::vector<Node> nodes;
  std::vector<Node> targets;                    // every key but the spots, which no move enters
  std::vector<std::vector<std::size_t>> pipes;  // the keys of each task's pipe
};

Keys keys_of(PositionGraph& graph, const Mission& mission) {
  Keys keys;
  keys.nodes.push_back(graph.in_manhole(std::get<ManholeId>(mission.start)));
  for (const Task& task : mission.tasks) {
    const auto& spot = std::get<PipeSpot>(task.place);
    std::vector<std::size_t> pipe;
    for (std::size_t e = 0; e < 2; ++e) {
      pipe.push_back(keys.nodes.size());
      keys.nodes.push_back(graph.pipe_end(spot.pipe, e));
      keys.targets.push_back(keys.nodes.back());
    }
    if (spot.offset_m) {
      pipe.push_back(keys.nodes.size());
      keys.nodes.push_back(graph.spot(spot.pipe, *spot.offset_m));
    }
    keys.pipes.push_back(pipe);
  }
  return keys;
}

std::vector<bool> exit_marks(const PositionGraph& graph, const SewerMap& map,
                             const Mission& mission) {
  std::vector<bool> marks(graph.size(), false);
  for (ManholeId e : mission.exits) {
    marks[graph.in_manhole(e)] = true;
    for (std::uint16_t s = 0; s < map.manhole(e).slot_count; ++s) {
      marks[graph.at_slot(e, SlotIndex{s})] = true;
    }
  }
  return marks;
}

std::vector<Node> as_vector(std::span<const Node> route) { return {route.begin(), route.end()}; }

// Every row a pipe's slot searches give is the key's own search's: the distance to every key, the
// route to each, and the way to the nearest exit; the spots within the whole bound, the ends
// within less (as the compile bounds them), so that the bounds cut some routes.
TEST(PipeKeyRoutes, RowsAreTheKeysOwnSearches) {
  for (std::uint64_t seed : {1U, 2U}) {
    const Instance instance = uniform(1000, 30, seed);
    PositionGraph graph(instance.map, instance.mission);
    const Keys keys = keys_of(graph, instance.mission);
    const std::vector<bool> exits = exit_marks(graph, instance.map, instance.mission);
    GraphSearch search(graph);
    // A bound that some routes pass: the start's distance to its farthest key.
    search.run(std::span<const Node>(keys.nodes.data(), 1), keys.targets, kInfiniteCost,
               GraphSearch::Direction::kForward);
    Cost farthest = 0;
    for (Node n : keys.targets) {
      if (search.distance(n) != kInfiniteCost) farthest = std::max(farthest, search.distance(n));
    }
    const Cost bound = farthest * 3 / 4;
    PipeKeyRoutes pipe_routes(graph, keys.nodes);
    const std::size_t k = keys.nodes.size();
    std::size_t derived = 0, groups = 0;
    for (const auto& pipe : keys.pipes) {
      std::vector<PipeKeyRoutes::Key> group;
      for (std::size_t i : pipe) {
        group.push_back({i, graph.is_extra_spot(keys.nodes[i]) ? bound : bound * 2 / 3});
      }
      if (!pipe_routes.usable(group, true)) continue;
      ASSERT_TRUE(pipe_routes.search(search, group, keys.targets, &exits));
      ++groups;
      for (const PipeKeyRoutes::Key& key : group) {
        std::vector<Cost> dist(k, -1);
        std::vector<RouteRef> routes(k);
        RouteStore store;
        PipeKeyRoutes::Exit exit;
        if (!pipe_routes.row(key, dist, routes, store, exit)) continue;  // a tie
        ++derived;
        const auto nearest =
            search.run(std::span<const Node>(&keys.nodes[key.index], 1), keys.targets, key.bound,
                       GraphSearch::Direction::kForward, &exits);
        for (std::size_t b = 0; b < k; ++b) {
          ASSERT_EQ(dist[b], search.distance(keys.nodes[b])) << "key " << key.index << " to " << b;
          std::vector<Node> path;
          if (b != key.index) search.path(keys.nodes[b], path);
          EXPECT_EQ(as_vector(store.route(routes[b])), path) << "key " << key.index << " to " << b;
        }
        ASSERT_EQ(exit.cost, nearest ? search.distance(*nearest) : kInfiniteCost);
        std::vector<Node> path;
        if (nearest) search.path(*nearest, path);
        EXPECT_EQ(as_vector(store.route(exit.route)), path) << "key " << key.index;
      }
    }
    // A sample's three keys take their rows from two searches.
    EXPECT_GT(groups, 3U) << "seed " << seed;
    EXPECT_EQ(pipe_routes.searches(), 2 * groups);
    EXPECT_GT(derived, 2 * groups) << "seed " << seed;
  }
}

// The compile searches from fewer places than it has keys where samples have three keys each.
TEST(PipeKeyRoutes, TheCompileSearchesLessThanOncePerKey) {
  const Instance instance = uniform(1000, 30, 1);
  auto task =
      compile_sewer_task(instance.map, instance.mission,
                         initial_progress(instance.mission, instance.map), {.select_goals = true});
  ASSERT_TRUE(task.has_value()) << task.error();
  std::size_t samples = 0;
  for (const Task& t : instance.mission.tasks) samples += t.kind == TaskKind::kTakeWaterSample;
  ASSERT_GT(samples, 3U);
  EXPECT_LT(task->statistics().route_searches + samples / 2, task->statistics().keys);
}

}  // namespace
}  // namespace sewerplan::domain::detail
