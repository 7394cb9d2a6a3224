// SPDX-License-Identifier: MIT
// Issue 35: the compile does not depend on how a network is numbered or named, and the moves it
// reads from the core's adjacency are the moves it generates from the map.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"

#include "position_graph.h"
#include "support/paths.h"
#include "support/scrambled_network.h"
#include "support/task_compare.h"

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

using testing::driven_pipes;
using testing::expect_identical_task;
using testing::expect_same_task;

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

// Issue 35: a blockage, a closed passage or a hazard changes the moves of a few nodes only; the
// others are read from the adjacency, and every node's moves are still the map's.
TEST(CompileNumberingIssue35, AdjacencyGivesTheMovesTheMapGivesWithBlockagesPassagesAndHazards) {
  const SewerMap map = *bench::generate_scrambled_network({.manholes = 300, .seed = 2});
  Mission mission = *bench::scrambled_mission(map, 5, 1);
  mission.closed_pipes = {PipeId{3}};
  for (std::uint32_t p : {8U, 30U, 55U}) {
    mission.blockages.push_back({PipeId{p}, map.pipe(PipeId{p}).length_m / 2});
  }
  for (std::uint32_t p = 1; p < map.pipe_count(); p += 9) {
    mission.hazards.push_back({PipeId{p}, map.pipe(PipeId{p}).length_m / 3, 0.3, "roots"});
  }
  std::size_t passages = 0;
  for (ManholeId m : map.manhole_ids()) {
    if (map.manhole(m).slot_count > 2 && passages < 4) {
      mission.closed_passages.push_back({m, SlotIndex{2}, SlotIndex{0}});
      ++passages;
    }
  }
  ASSERT_GT(passages, 0U);
  detail::PositionGraph graph(map, mission);
  graph.spot(PipeId{30}, map.pipe(PipeId{30}).length_m / 4);
  detail::PositionGraph fresh(map, mission);
  for (const double weight_s : {0.0, 600.0}) {
    SCOPED_TRACE("risk weight " + std::to_string(weight_s));
    graph.set_risk_weight(weight_s);
    fresh.set_risk_weight(weight_s);
    if (!graph.has_adjacency()) {
      ASSERT_TRUE(graph.build_adjacency(nullptr));
    }
    auto read = moves(graph);
    auto expected = moves(fresh);
    ASSERT_FALSE(fresh.has_adjacency());
    read.pop_back();  // the spot is not in the fresh graph
    ASSERT_EQ(read.size(), expected.size());
    for (std::size_t n = 0; n < read.size(); ++n) EXPECT_EQ(read[n], expected[n]) << n;
  }
}

}  // namespace
}  // namespace sewerplan::domain

namespace sewerplan::domain {
namespace {

// Issue 35, incremental replanning: a compile on a CompileCache takes the rows the last compile's
// searches found (RouteMemo) where nothing that changed since could alter them. The task must be
// the one compiled afresh, action for action and route for route (expect_identical_task).

// Compiles on a CompileCache and afresh, side by side. The first compile fills the cache (a task
// holds the cache's core while it lives: the next compile takes it after).
class CachedAndFresh {
 public:
  CachedAndFresh(const SewerMap& map, const CompileOptions& options,
                 CompileCache::RoutingIndex index = CompileCache::RoutingIndex::kNever)
      : map_(map), cache_(index), fresh_(options), cached_(options) {
    cached_.cache = &cache_;
  }

  // The pipes the first compile's routes drive; empty, with a failure, when it fails.
  std::vector<PipeId> first(const Mission& mission, const MissionProgress& progress) {
    const auto task = compile_sewer_task(map_, mission, progress, cached_);
    if (!task.has_value()) {
      ADD_FAILURE() << task.error().message;
      return {};
    }
    return driven_pipes(*task);
  }

  // Both compiles of the same inputs, checked identical (or failing alike): the cached one's
  // statistics and the fresh one's; none when both failed.
  struct Statistics {
    CompileStatistics cached;
    CompileStatistics fresh;
  };
  std::optional<Statistics> compare(const Mission& mission, const MissionProgress& progress) {
    const auto with = compile_sewer_task(map_, mission, progress, cached_);
    const auto without = compile_sewer_task(map_, mission, progress, fresh_);
    EXPECT_EQ(with.has_value(), without.has_value());
    if (with.has_value() != without.has_value()) return std::nullopt;
    if (!without.has_value()) {
      EXPECT_EQ(with.error().message, without.error().message);
      return std::nullopt;
    }
    expect_identical_task(*with, *without);
    return Statistics{with->statistics(), without->statistics()};
  }

 private:
  const SewerMap& map_;
  CompileCache cache_;
  CompileOptions fresh_;
  CompileOptions cached_;
};

// A replan's changes one after the other, each compiled with the cache and afresh: the robot on
// in a pipe past the start, a task done, energy used, a blockage on a pipe the routes use, a
// passage closed, a pipe closed, then a closure lifted (which the memo cannot follow: it must not
// be used) and a closure again.
// `index`: the cache's routing index (by default none: the rows come from the memo or searches).
// Returns the rows and exit ways the cached compiles took from the index.
std::size_t expect_replans_as_afresh(
    const SewerMap& map, Mission mission, CompileOptions options,
    CompileCache::RoutingIndex index = CompileCache::RoutingIndex::kNever) {
  CachedAndFresh compiles(map, options, index);
  MissionProgress progress = initial_progress(mission, map);
  const std::vector<PipeId> used = compiles.first(mission, progress);
  EXPECT_GE(used.size(), 6U);
  if (used.size() < 6) return 0;
  std::size_t reused = 0;
  std::size_t index_rows = 0;
  for (int step = 0; step < 8; ++step) {
    SCOPED_TRACE("step " + std::to_string(step));
    const PipeId p = used[static_cast<std::size_t>(step) * used.size() / 9];
    switch (step) {
      case 0:  // nothing changed: every row from the memo
        break;
      case 1:
        progress.position = InPipe{used[0], map.pipe(used[0]).length_m / 3};
        progress.done[0] = true;
        progress.energy_used_wh += 2;
        break;
      case 2:
        mission.blockages.push_back({p, map.pipe(p).length_m / 2});
        break;
      case 3: {
        const PipeEnd& end = map.pipe(p).ends[0];
        if (end.manhole && map.manhole(*end.manhole).slot_count > 1) {
          const auto other = static_cast<std::uint16_t>(end.slot.value() == 0 ? 1 : 0);
          mission.closed_passages.push_back({*end.manhole, end.slot, SlotIndex{other}});
        }
        break;
      }
      case 4:
        mission.closed_pipes.push_back(p);
        break;
      case 5:
        mission.blockages.clear();  // lifted
        break;
      case 6:
        mission.closed_pipes.push_back(p);
        progress.energy_used_wh += 1;
        break;
      default:
        progress.done[1] = true;
        break;
    }
    const auto stats = compiles.compare(mission, progress);
    if (!stats) continue;
    EXPECT_EQ(stats->fresh.reused_searches, 0U);
    if (step == 0) {
      // Nothing changed: every row from the memo, the spots' too; only the start's is searched
      // (or taken from the index).
      EXPECT_LE(stats->cached.route_searches, 1U);
      if (index == CompileCache::RoutingIndex::kNever) {
        EXPECT_EQ(stats->cached.route_searches, 1U);
      }
    }
    if (step == 5) {
      EXPECT_EQ(stats->cached.reused_searches, 0U) << "a lifted closure must not reuse";
    }
    reused += stats->cached.reused_searches;
    index_rows += stats->cached.index_rows;
    EXPECT_EQ(stats->fresh.index_rows, 0U);
  }
  // The memo must have been used, or the comparison proves nothing.
  EXPECT_GT(reused, 0U);
  return index_rows;
}

TEST(IncrementalReplanIssue35, ReplansOnAGeneratedNetworkAsAfresh) {
  const SewerMap map =
      *generate_network({.manholes = 300, .seed = 3, .topology = Topology::kMeshed});
  const Mission mission =
      *generate_mission(map, {.tasks = 8, .seed = 2, .spread = MissionSpread::kUniform});
  expect_replans_as_afresh(map, mission, {.select_goals = true});
}

TEST(IncrementalReplanIssue35, ReplansOnAScrambledNetworkAsAfresh) {
  const SewerMap map = *bench::generate_scrambled_network({.manholes = 400, .seed = 5});
  const Mission mission = *bench::scrambled_mission(map, 8, 3);
  expect_replans_as_afresh(map, mission, {.select_goals = true});
}

// The pipes of the mission's tasks at a spot inside the pipe (an extra spot: a key whose row is a
// spot row, RouteMemo::SpotRow), with the spot's offset.
std::vector<std::pair<PipeId, double>> task_spots(const Mission& mission) {
  std::vector<std::pair<PipeId, double>> spots;
  for (const Task& t : mission.tasks) {
    const auto* spot = std::get_if<PipeSpot>(&t.place);
    if (spot != nullptr && spot->offset_m && t.kind != TaskKind::kInspectPipe) {
      spots.emplace_back(spot->pipe, *spot->offset_m);
    }
  }
  return spots;
}

// Spot rows keep every key their search settled before it stopped: taken from the memo only when
// the blockage cannot have moved that stop or the routes. A blockage in a spot's own pipe changes
// the spot's moves: its row must be searched again. Blockages one after the other on the pipes
// the routes use, each compiled with the cache and afresh.
TEST(IncrementalReplanIssue35, TakesSpotRowsOnlyWhereABlockageCannotChangeThem) {
  const SewerMap map = *bench::generate_scrambled_network({.manholes = 400, .seed = 5});
  Mission mission = *bench::scrambled_mission(map, 8, 3);
  const auto spots = task_spots(mission);
  ASSERT_FALSE(spots.empty());
  CachedAndFresh compiles(map, {.select_goals = true});
  const MissionProgress progress = initial_progress(mission, map);
  const std::vector<PipeId> used = compiles.first(mission, progress);
  ASSERT_GE(used.size(), 12U);
  std::size_t reused = 0;
  for (std::size_t step = 0; step <= 12; ++step) {
    SCOPED_TRACE("step " + std::to_string(step));
    // The last step blocks the first spot's pipe between the spot and the pipe's first end.
    const bool own_pipe = step == 12;
    const PipeId p = own_pipe ? spots[0].first : used[step * used.size() / 12];
    const double at = own_pipe ? spots[0].second / 2 : map.pipe(p).length_m * 0.37;
    mission.blockages.push_back({p, at});
    const auto stats = compiles.compare(mission, progress);
    if (!stats) continue;
    reused += stats->cached.reused_searches;
    if (own_pipe) {
      // The start's search and the blocked spot's at least.
      EXPECT_GE(stats->cached.route_searches, 2U);
    }
  }
  EXPECT_GT(reused, 0U);
}

// Risk-aware, the hazards weigh the routes. A hazard added or more likely since (a blockage met
// there) only makes drives dearer, as a closure does: the rows whose routes avoid its pipe may be
// taken. A hazard less likely (a pass observed) or gone makes some cheaper: the memo must not be
// used then. With the same hazards it may be.
TEST(IncrementalReplanIssue35, ReplansRiskAwareAsAfreshAcrossRisenHazardsNotFallenOnes) {
  const SewerMap map =
      *generate_network({.manholes = 300, .seed = 4, .topology = Topology::kMeshed});
  Mission mission =
      *generate_mission(map, {.tasks = 6, .seed = 4, .spread = MissionSpread::kUniform});
  for (std::uint32_t p = 0; p < map.pipe_count(); p += 7) {
    mission.hazards.push_back({PipeId{p}, map.pipe(PipeId{p}).length_m / 2, 0.2, "roots"});
  }
  const CompileOptions options{.select_goals = true, .risk = kDefaultRiskCosts};
  expect_replans_as_afresh(map, mission, options);
  CachedAndFresh compiles(map, options);
  const MissionProgress progress = initial_progress(mission, map);
  const std::vector<PipeId> used = compiles.first(mission, progress);
  ASSERT_GE(used.size(), 2U);
  // The hazard of a pipe the routes drive, if one has one.
  std::size_t on_route = 0;
  for (std::size_t h = 0; h < mission.hazards.size(); ++h) {
    if (std::find(used.begin(), used.end(), mission.hazards[h].pipe) != used.end()) on_route = h;
  }
  std::size_t reused = 0;
  for (int step = 0; step < 4; ++step) {
    SCOPED_TRACE("step " + std::to_string(step));
    const bool fell = step >= 2;
    switch (step) {
      case 0:  // learnt on a pipe the routes drive
        mission.hazards.push_back({used[1], map.pipe(used[1]).length_m / 3, 0.5, "obstacle"});
        break;
      case 1:  // a blockage met there: certain
        mission.hazards[on_route].probability = 1;
        break;
      case 2:  // passed: less likely
        mission.hazards[on_route].probability = 0.05;
        break;
      default:  // gone
        mission.hazards.pop_back();
        break;
    }
    const auto stats = compiles.compare(mission, progress);
    ASSERT_TRUE(stats.has_value());
    if (fell) {
      EXPECT_EQ(stats->cached.reused_searches, 0U);
    } else {
      reused += stats->cached.reused_searches;
    }
  }
  EXPECT_GT(reused, 0U);
}

// Issue 35, the routing index (CompileCache::RoutingIndex::kAlways): a route is taken from the
// index only where it is the only shortest way and no closure, blockage, closed passage or hazard
// touches it; every other row is searched. The tasks must be the ones compiled afresh, route for
// route, through the replan steps above: on our network (no ties), a scrambled one (ties: the
// index's way among equal ones is not always the search's), and risk-aware with hazards.
TEST(IncrementalReplanIssue35, ReplansFromTheRoutingIndexAsAfresh) {
  constexpr auto kAlways = CompileCache::RoutingIndex::kAlways;
  const SewerMap ours =
      *generate_network({.manholes = 300, .seed = 3, .topology = Topology::kMeshed});
  const Mission uniform =
      *generate_mission(ours, {.tasks = 8, .seed = 2, .spread = MissionSpread::kUniform});
  EXPECT_GT(expect_replans_as_afresh(ours, uniform, {.select_goals = true}, kAlways), 0U);
  const SewerMap scrambled = *bench::generate_scrambled_network({.manholes = 400, .seed = 5});
  const Mission spread = *bench::scrambled_mission(scrambled, 8, 3);
  EXPECT_GT(expect_replans_as_afresh(scrambled, spread, {.select_goals = true}, kAlways), 0U);
  Mission hazards = uniform;
  for (std::uint32_t p = 0; p < ours.pipe_count(); p += 7) {
    hazards.hazards.push_back({PipeId{p}, ours.pipe(PipeId{p}).length_m / 2, 0.2, "roots"});
  }
  EXPECT_GT(expect_replans_as_afresh(ours, hazards,
                                     {.select_goals = true, .risk = kDefaultRiskCosts}, kAlways),
            0U);
}

// Compiles `mission` from `progress` afresh and twice on a fresh kAlways cache (the first builds
// the index after the start's search, the second takes the start's row from it too); each must
// be the fresh task. Returns whether the second settled fewer nodes (took anything from the
// index).
bool expect_index_compiles_as_afresh(const SewerMap& map, const Mission& mission,
                                     const MissionProgress& progress,
                                     const CompileOptions& options) {
  const auto fresh = compile_sewer_task(map, mission, progress, options);
  CompileCache cache(CompileCache::RoutingIndex::kAlways);
  CompileOptions cached = options;
  cached.cache = &cache;
  bool saved = false;
  for (int pass = 0; pass < 2; ++pass) {
    SCOPED_TRACE("pass " + std::to_string(pass));
    const auto indexed = compile_sewer_task(map, mission, progress, cached);
    EXPECT_EQ(indexed.has_value(), fresh.has_value());
    if (!indexed.has_value() || !fresh.has_value()) continue;
    expect_identical_task(*indexed, *fresh);
    saved = indexed->statistics().settled_nodes < fresh->statistics().settled_nodes;
  }
  return saved;
}

// A robot at the end slot of a closed pipe with a task in it: the rows from the task's keys in
// that pipe are searches that leave it, onto slots no target list has; the index must not take
// them. (Found by review: 10 of 16 such starts lost actions from those keys.)
TEST(IncrementalReplanIssue35, TakesNoRowFromTheIndexOutOfAClosedPipe) {
  const SewerMap map =
      *generate_network({.manholes = 300, .seed = 3, .topology = Topology::kMeshed});
  Mission base = *generate_mission(map, {.tasks = 8, .seed = 2, .spread = MissionSpread::kUniform});
  base.profile.battery_wh = 5000;
  std::size_t starts = 0;
  std::size_t saved = 0;
  for (const Task& task : base.tasks) {
    const auto* spot = std::get_if<PipeSpot>(&task.place);
    if (spot == nullptr) continue;
    for (const PipeEnd& end : map.pipe(spot->pipe).ends) {
      if (!end.manhole) continue;
      SCOPED_TRACE(task.name);
      Mission m = base;
      m.closed_pipes = {spot->pipe};
      MissionProgress p = initial_progress(m, map);
      p.position = AtSlot{*end.manhole, end.slot};
      saved += expect_index_compiles_as_afresh(map, m, p, {.select_goals = true}) ? 1U : 0U;
      ++starts;
    }
  }
  EXPECT_GE(starts, 8U);
  EXPECT_GT(saved, 0U);
}

// Free passages (no time to pass, turn or step: a profile may say so) make moves of cost 0, and
// a search does not settle the exit nodes at one distance by number then: exits tied in
// distance go to the search. (Found by review: 2 of 8 missions had a longer way out from the
// index.)
TEST(IncrementalReplanIssue35, LeavesExitsTiedByFreeMovesToTheSearch) {
  const SewerMap map =
      *generate_network({.manholes = 300, .seed = 3, .topology = Topology::kMeshed});
  std::size_t saved = 0;
  for (std::uint64_t seed = 0; seed < 8; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Mission m =
        *generate_mission(map, {.tasks = 8, .seed = seed, .spread = MissionSpread::kUniform});
    m.profile.manhole_pass_s = 0;
    m.profile.turn_s_per_deg = 0;
    m.profile.step_s_per_m = 0;
    saved +=
        expect_index_compiles_as_afresh(map, m, initial_progress(m, map), {.select_goals = true})
            ? 1U
            : 0U;
  }
  EXPECT_GT(saved, 0U);  // the index served, or the comparison proves little
}

// A replan's course on a scrambled network, compiled from the index and afresh: the robot in a
// pipe (its routes start with a drive to either end: not a node of the index), at a slot, then a
// blockage on a pipe the routes use, in turn. The routes that pass a blockage are searched
// toward their targets, guided by the index (or, where that finds no single shortest way, by a
// search of the row), the others (the robot's new place, the ways to the exits) taken from the
// index, and the tasks are the same.
TEST(IncrementalReplanIssue35, SearchesTheRowsWhoseIndexRoutesABlockageTouches) {
  const SewerMap map = *bench::generate_scrambled_network({.manholes = 400, .seed = 5});
  Mission mission = *bench::scrambled_mission(map, 8, 3);
  CachedAndFresh compiles(map, {.select_goals = true}, CompileCache::RoutingIndex::kAlways);
  MissionProgress progress = initial_progress(mission, map);
  const std::vector<PipeId> used = compiles.first(mission, progress);
  ASSERT_GE(used.size(), 12U);
  std::size_t from_index = 0;
  std::size_t searched = 0;
  std::size_t guided = 0;
  for (std::size_t step = 0; step < 12; ++step) {
    SCOPED_TRACE("step " + std::to_string(step));
    const PipeId p = used[step * used.size() / 12];
    const Pipe& pipe = map.pipe(p);
    if (step % 3 == 0) {
      progress.position = InPipe{p, pipe.length_m / 3};
    } else if (step % 3 == 1 && pipe.ends[1].manhole) {
      progress.position = AtSlot{*pipe.ends[1].manhole, pipe.ends[1].slot};
    } else {
      mission.blockages.push_back({p, pipe.length_m * 0.37});
    }
    const auto stats = compiles.compare(mission, progress);
    if (!stats) continue;
    from_index += stats->cached.index_rows;
    searched += stats->cached.route_searches;
    guided += stats->cached.guided_searches;
  }
  // Every way was taken, or the comparison proves little.
  EXPECT_GT(from_index, 0U);
  EXPECT_GT(searched, 0U);
  EXPECT_GT(guided, 0U);
}

}  // namespace
}  // namespace sewerplan::domain
