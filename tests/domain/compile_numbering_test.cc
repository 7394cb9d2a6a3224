// SPDX-License-Identifier: MIT
// Issue 35: the compile does not depend on how a network is numbered or named, and the moves it
// reads from the core's adjacency are the moves it generates from the map.
#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"

#include "position_graph.h"
#include "support/paths.h"
#include "support/scrambled_network.h"

namespace sewerplan::domain {
namespace {

// `mission` with every manhole and pipe renamed as `shuffled` renames them.
Mission renamed(const Mission& mission, const bench::ShuffledMap& shuffled) {
  Mission out = mission;
  auto place = [&](const Place& p) -> Place {
    if (const auto* m = std::get_if<ManholeId>(&p)) return shuffled.manhole_to[m->index()];
    PipeSpot spot = std::get<PipeSpot>(p);
    spot.pipe = shuffled.pipe_to[spot.pipe.index()];
    return spot;
  };
  out.start = place(mission.start);
  for (Task& t : out.tasks) t.place = place(t.place);
  for (ManholeId& e : out.exits) e = shuffled.manhole_to[e.index()];
  for (PipeId& p : out.closed_pipes) p = shuffled.pipe_to[p.index()];
  for (ClosedPassage& c : out.closed_passages) c.manhole = shuffled.manhole_to[c.manhole.index()];
  for (Blockage& b : out.blockages) b.pipe = shuffled.pipe_to[b.pipe.index()];
  return out;
}

// The two tasks are the same up to the renaming: the same variables, the same actions with the
// same preconditions, effects, costs, reserves and names, each expanding to as many steps.
void expect_same_task(const SewerTask& a, const SewerTask& b) {
  const CompiledTask& x = a.task();
  const CompiledTask& y = b.task();
  ASSERT_EQ(x.variable_count(), y.variable_count());
  ASSERT_EQ(x.action_count(), y.action_count());
  EXPECT_EQ(x.cost_bound(), y.cost_bound());
  for (ActionId id : x.action_ids()) {
    ASSERT_EQ(x.action_name(id), y.action_name(id));
    EXPECT_EQ(x.cost(id), y.cost(id)) << x.action_name(id);
    EXPECT_EQ(x.reserve(id), y.reserve(id)) << x.action_name(id);
    const auto pre_x = x.preconditions(id), pre_y = y.preconditions(id);
    const auto eff_x = x.effects(id), eff_y = y.effects(id);
    EXPECT_TRUE(std::equal(pre_x.begin(), pre_x.end(), pre_y.begin(), pre_y.end()));
    EXPECT_TRUE(std::equal(eff_x.begin(), eff_x.end(), eff_y.begin(), eff_y.end()));
    const ActionId one[] = {id};
    EXPECT_EQ(a.expand(one).steps.size(), b.expand(one).steps.size()) << x.action_name(id);
  }
}

void expect_same_on_shuffled_copy(const SewerMap& map, const Mission& mission) {
  const bench::ShuffledMap shuffled = bench::shuffle_ids(map, 7);
  const Mission other = renamed(mission, shuffled);
  const auto a =
      compile_sewer_task(map, mission, initial_progress(mission, map), {.select_goals = true});
  const auto b = compile_sewer_task(shuffled.map, other, initial_progress(other, shuffled.map),
                                    {.select_goals = true});
  ASSERT_TRUE(a.has_value()) << a.error().message;
  ASSERT_TRUE(b.has_value()) << b.error().message;
  expect_same_task(*a, *b);
}

TEST(CompileNumberingIssue35, GivesTheSameTaskOnAShuffledCopyOfTheTestBed) {
  Diagnostics d;
  const auto map = read_map(testing::dataset_path("ais-testbed/map.json"), d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  const auto mission =
      read_mission(testing::dataset_path("ais-testbed/missions/paper.json"), *map, d);
  ASSERT_TRUE(mission.has_value()) << mission.error().message;
  expect_same_on_shuffled_copy(*map, *mission);
}

TEST(CompileNumberingIssue35, GivesTheSameTaskOnAShuffledCopyOfAGeneratedNetwork) {
  const SewerMap map =
      *generate_network({.manholes = 300, .seed = 3, .topology = Topology::kMeshed});
  Mission mission =
      *generate_mission(map, {.tasks = 8, .seed = 2, .spread = MissionSpread::kUniform});
  expect_same_on_shuffled_copy(map, mission);
  // With a closure and a blockage too.
  mission.closed_pipes.push_back(PipeId{5});
  mission.blockages.push_back({PipeId{9}, map.pipe(PipeId{9}).length_m / 2});
  expect_same_on_shuffled_copy(map, mission);
}

TEST(CompileNumberingIssue35, GivesTheSameTaskOnAShuffledCopyOfAScrambledNetwork) {
  const SewerMap map = *bench::generate_scrambled_network({.manholes = 400, .seed = 5});
  const Mission mission = *bench::scrambled_mission(map, 8, 3);
  expect_same_on_shuffled_copy(map, mission);
}

TEST(CompileNumberingIssue35, ReadsTheMovesFromTheAdjacencyWhenTheSearchesCoverTheNetwork) {
  const SewerMap map = *bench::generate_scrambled_network({.manholes = 400, .seed = 5});
  const Mission spread = *bench::scrambled_mission(map, 8, 3);
  const auto task =
      compile_sewer_task(map, spread, initial_progress(spread, map), {.select_goals = true});
  ASSERT_TRUE(task.has_value()) << task.error().message;
  EXPECT_TRUE(task->statistics().adjacency);
  // A mission near the start on a large network: the searches stay small, nothing is built.
  const SewerMap city =
      *generate_network({.manholes = 20000, .seed = 1, .topology = Topology::kMeshed});
  const Mission local = *generate_mission(city, {.tasks = 3, .seed = 1});
  const auto small =
      compile_sewer_task(city, local, initial_progress(local, city), {.select_goals = true});
  ASSERT_TRUE(small.has_value()) << small.error().message;
  EXPECT_FALSE(small->statistics().adjacency);
}

// Every node's moves, as the graph gives them.
std::vector<std::vector<std::pair<detail::Node, Cost>>> moves(const detail::PositionGraph& g) {
  std::vector<std::vector<std::pair<detail::Node, Cost>>> out(g.size());
  for (detail::Node n = 0; n < g.size(); ++n) {
    g.for_each_successor(n, [&](detail::Node to, Cost c) { out[n].emplace_back(to, c); });
  }
  return out;
}

TEST(CompileNumberingIssue35, AdjacencyGivesTheMovesTheMapGivesWithClosuresAndExclusions) {
  const SewerMap map = *bench::generate_scrambled_network({.manholes = 300, .seed = 2});
  Mission mission = *bench::scrambled_mission(map, 5, 1);
  mission.closed_pipes = {PipeId{3}, PipeId{17}, PipeId{40}};
  detail::PositionGraph graph(map, mission);
  graph.spot(PipeId{8}, map.pipe(PipeId{8}).length_m / 3);
  graph.exclude_pipe(PipeId{21}, true);
  const auto generated = moves(graph);
  ASSERT_FALSE(graph.has_adjacency());
  ASSERT_TRUE(graph.build_adjacency(nullptr));
  ASSERT_TRUE(graph.has_adjacency());
  EXPECT_EQ(moves(graph), generated);
  graph.exclude_pipe(PipeId{21}, false);
  const auto read = moves(graph);
  // The same graph without the adjacency, on a core of its own.
  const detail::PositionGraph fresh(map, mission);
  EXPECT_FALSE(fresh.has_adjacency());
  auto expected = moves(fresh);
  expected.resize(read.size());  // the spot is not in the fresh graph
  for (std::size_t n = 0; n + 1 < read.size(); ++n) EXPECT_EQ(read[n], expected[n]) << n;
}

}  // namespace
}  // namespace sewerplan::domain
