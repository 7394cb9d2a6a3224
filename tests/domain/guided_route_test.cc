// SPDX-License-Identifier: MIT
// Issue 35's guided searches (GraphSearch::run_toward, the compile's guided_routes): where the
// search toward a target says its way is the only shortest one, it is the plain search's way,
// on graphs with moves of cost 0 (free passages: cycles of cost 0), risk weights, exclusions,
// closed passages and sources at extra spots; and whole compiles with the index are the
// compiles afresh through replans with those, and from a robot in a pipe with no way out or two.
// (Written by a review of the change; the tie check's defects it was asked to look for are the
// ones these catch: a way declared the only one where run() keeps another.)
#include <algorithm>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/rng.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"

#include "contraction_hierarchy.h"
#include "graph_search.h"
#include "joined_search.h"
#include "position_graph.h"
#include "support/scrambled_network.h"
#include "support/task_compare.h"

namespace sewerplan::domain {
namespace {

using detail::ChQuery;
using detail::ContractionHierarchy;
using detail::GraphSearch;
using detail::JoinedSearch;
using detail::Node;
using detail::PositionGraph;
using detail::SearchScratch;
using testing::driven_pipes;

struct Counts {
  std::size_t unique = 0, tied = 0, unreached = 0, gave_up = 0, differ = 0, joined = 0;
};

void free_moves(Mission& m) {
  m.profile.manhole_pass_s = 0;
  m.profile.turn_s_per_deg = 0;
  m.profile.step_s_per_m = 0;
}

Counts toward_vs_run(const SewerMap& map, Mission mission, std::uint32_t every, double risk,
                     bool exclude, std::uint64_t seed) {
  Rng rng(seed);
  for (std::uint32_t p = 3; p < map.pipe_count(); p += every) {
    mission.blockages.push_back({PipeId{p}, map.pipe(PipeId{p}).length_m * rng.uniform(0.1, 0.9)});
  }
  for (std::uint32_t p = 11; p < map.pipe_count(); p += every * 5 / 2) {
    mission.closed_pipes.push_back(PipeId{p});
  }
  for (std::uint32_t p = 7; p < map.pipe_count(); p += every / 2 + 1) {
    mission.hazards.push_back({PipeId{p}, map.pipe(PipeId{p}).length_m / 2, 0.3, "roots"});
  }
  for (std::uint32_t m = 2; m < map.manhole_count(); m += every) {
    if (map.manhole(ManholeId{m}).slot_count > 2) {
      mission.closed_passages.push_back({ManholeId{m}, SlotIndex{0}, SlotIndex{1}});
    }
  }
  PositionGraph graph(map, mission);
  EXPECT_TRUE(graph.build_adjacency(nullptr));
  const auto& core = graph.core();
  auto ch = ContractionHierarchy::build(core.adjacency_begin, core.adjacency_to,
                                        core.adjacency_cost, {.keep_ties = true});
  EXPECT_TRUE(ch.has_value());
  ChQuery index(*ch);
  graph.set_risk_weight(risk);
  if (exclude) {
    for (std::uint32_t p = 13; p < map.pipe_count(); p += every * 3) {
      graph.exclude_pipe(PipeId{p}, true);
    }
  }
  std::vector<Node> sources;
  for (std::uint32_t m = 0; m < map.manhole_count(); m += 23) {
    sources.push_back(graph.in_manhole(ManholeId{m}));
    sources.push_back(graph.at_slot(ManholeId{m}, SlotIndex{0}));
  }
  for (std::uint32_t p = 5; p < map.pipe_count(); p += 19) {
    sources.push_back(graph.spot(PipeId{p}, map.pipe(PipeId{p}).length_m * 0.4));
  }
  SearchScratch scratch;
  GraphSearch search(graph, &scratch);
  JoinedSearch joined_search(graph, index);
  Counts c;
  const Node first = static_cast<Node>(map.manhole_count());
  const auto ch_nodes = static_cast<Node>(core.adjacency_begin.size() - 1);
  for (Node source : sources) {
    for (int i = 0; i < 16; ++i) {
      const auto t = static_cast<Node>(first + rng.below(ch_nodes - first));
      if (t == source) continue;
      const Cost bound = i % 5 == 4 ? 200000 : kInfiniteCost;
      search.run(std::span<const Node>(&source, 1), std::span<const Node>(&t, 1), bound,
                 GraphSearch::Direction::kForward);
      const Cost want = search.distance(t);
      std::vector<Node> want_path;
      search.path(t, want_path);
      const auto guide = [&](Node n) {
        return graph.is_extra_spot(n) ? 0 : index.distance_to_aim(n);
      };
      // With the rest taken from the index where it is known (as the compile runs it): the same
      // answer, way and cost as without.
      index.aim_at(t);
      const JoinedSearch::Way joined = joined_search.run(search, source, t, bound, guide);
      if (joined.joined) ++c.joined;
      index.aim_at(t);
      const auto got = search.run_toward(source, t, bound, graph.size(), guide);
      SCOPED_TRACE(std::to_string(source) + " -> " + std::to_string(t));
      if (got != GraphSearch::Toward::kGaveUp) {
        EXPECT_EQ(joined.result, got);
      }
      if (got == GraphSearch::Toward::kUnique) {
        EXPECT_EQ(joined.cost, want);
        EXPECT_EQ(joined.path, want_path);
      }
      switch (got) {
        case GraphSearch::Toward::kUnreached:
          EXPECT_EQ(want, kInfiniteCost);
          ++c.unreached;
          break;
        case GraphSearch::Toward::kTied:
          EXPECT_NE(want, kInfiniteCost);
          ++c.tied;
          break;
        case GraphSearch::Toward::kGaveUp:
          ++c.gave_up;
          break;
        case GraphSearch::Toward::kUnique: {
          ++c.unique;
          std::vector<Node> path;
          search.path(t, path);
          EXPECT_EQ(search.distance(t), want);
          EXPECT_EQ(path, want_path);
          if (path != want_path) ++c.differ;
          break;
        }
      }
    }
  }
  return c;
}

TEST(GuidedRouteIssue35, TowardAgreesWithRunWithFreeMovesRiskAndExclusions) {
  const SewerMap lattice =
      *generate_network({.manholes = 400, .seed = 3, .topology = Topology::kMeshed});
  const SewerMap scrambled = *bench::generate_scrambled_network({.manholes = 400, .seed = 4});
  for (int variant = 0; variant < 8; ++variant) {
    SCOPED_TRACE("variant " + std::to_string(variant));
    const bool scr = variant % 2 == 1;
    const SewerMap& map = scr ? scrambled : lattice;
    Mission mission = scr ? *bench::scrambled_mission(map, 3, 1)
                          : *generate_mission(map, {.tasks = 3, .seed = 1});
    if (variant & 2) free_moves(mission);
    const double risk = variant & 4 ? 600.0 : 0.0;
    const Counts c = toward_vs_run(map, mission, scr ? 17 : 61, risk, variant >= 4,
                                   static_cast<std::uint64_t>(5 + variant));
    std::printf("variant %d: unique %zu tied %zu unreached %zu gave_up %zu differ %zu joined %zu\n",
                variant, c.unique, c.tied, c.unreached, c.gave_up, c.differ, c.joined);
    EXPECT_EQ(c.differ, 0U);
    if (!(variant & 2)) {
      EXPECT_GT(c.joined, c.unique / 4);  // with free moves no rest is taken
    }
  }
}

// Whole compiles: a kAlways cache through replans (blockages, closed passages, closed pipes on
// the routes; the robot in pipes and at slots) against afresh, with free moves and risk.

struct Totals {
  std::size_t guided = 0, index_rows = 0, compared = 0, failed = 0;
};

void replans(const SewerMap& map, Mission mission, const CompileOptions& options, Totals& totals) {
  CompileCache cache(CompileCache::RoutingIndex::kAlways);
  CompileOptions cached = options;
  cached.cache = &cache;
  MissionProgress progress = initial_progress(mission, map);
  std::vector<PipeId> used;
  {
    const auto first = compile_sewer_task(map, mission, progress, cached);
    if (!first.has_value()) return;
    used = driven_pipes(*first);
  }
  if (used.size() < 6) return;
  for (std::size_t step = 0; step < 12; ++step) {
    SCOPED_TRACE("step " + std::to_string(step));
    const PipeId p = used[step * used.size() / 12];
    const Pipe& pipe = map.pipe(p);
    switch (step % 4) {
      case 0:
        progress.position = InPipe{p, pipe.length_m / 3};
        break;
      case 1:
        mission.blockages.push_back({p, pipe.length_m * 0.37});
        break;
      case 2: {
        const PipeEnd& end = pipe.ends[1];
        if (end.manhole && map.manhole(*end.manhole).slot_count > 1) {
          const auto other = static_cast<std::uint16_t>(end.slot.value() == 0 ? 1 : 0);
          mission.closed_passages.push_back({*end.manhole, end.slot, SlotIndex{other}});
          progress.position = AtSlot{*end.manhole, end.slot};
        }
        break;
      }
      default:
        mission.closed_pipes.push_back(p);
        break;
    }
    {
      auto with = compile_sewer_task(map, mission, progress, cached);
      const auto without = compile_sewer_task(map, mission, progress, options);
      EXPECT_EQ(with.has_value(), without.has_value());
      if (!with.has_value() || !without.has_value()) {
        ++totals.failed;
        continue;
      }
      testing::expect_identical_task(*with, *without);
      totals.guided += with->statistics().guided_searches;
      totals.index_rows += with->statistics().index_rows;
      ++totals.compared;
    }
  }
}

TEST(GuidedRouteIssue35, ReplansWithTheIndexAsAfreshWithFreeMovesAndRisk) {
  const SewerMap lattice =
      *generate_network({.manholes = 300, .seed = 3, .topology = Topology::kMeshed});
  const SewerMap scrambled = *bench::generate_scrambled_network({.manholes = 400, .seed = 5});
  Totals totals;
  for (std::uint64_t seed = 0; seed < 6; ++seed) {
    for (int variant = 0; variant < 4; ++variant) {
      SCOPED_TRACE("seed " + std::to_string(seed) + " variant " + std::to_string(variant));
      const bool scr = seed % 2 == 1;
      const SewerMap& map = scr ? scrambled : lattice;
      Mission m = scr ? *bench::scrambled_mission(map, 8, seed)
                      : *generate_mission(
                            map, {.tasks = 8, .seed = seed, .spread = MissionSpread::kUniform});
      if (variant & 1) free_moves(m);
      CompileOptions options{.select_goals = true};
      if (variant & 2) {
        for (std::uint32_t p = 0; p < map.pipe_count(); p += 7) {
          m.hazards.push_back({PipeId{p}, map.pipe(PipeId{p}).length_m / 2, 0.2, "roots"});
        }
        options.risk = kDefaultRiskCosts;
      }
      replans(map, m, options, totals);
    }
  }
  EXPECT_GT(totals.compared, 100U);
  EXPECT_GT(totals.guided, 0U);
  EXPECT_GT(totals.index_rows, 0U);
}

// The robot in a pipe blocked on both sides of it (no start for the start's own table) and in the
// middle of a pipe (two starts), on a replan with the index.
TEST(GuidedRouteIssue35, ReplansFromASpotWithNoneOrTwoStartsAsAfresh) {
  const SewerMap map =
      *generate_network({.manholes = 300, .seed = 3, .topology = Topology::kMeshed});
  std::size_t compared = 0;
  for (std::uint64_t seed = 0; seed < 4; ++seed) {
    Mission mission =
        *generate_mission(map, {.tasks = 8, .seed = seed, .spread = MissionSpread::kUniform});
    mission.profile.battery_wh = 5000;
    CompileCache cache(CompileCache::RoutingIndex::kAlways);
    const CompileOptions options{.select_goals = true};
    CompileOptions cached = options;
    cached.cache = &cache;
    MissionProgress progress = initial_progress(mission, map);
    std::vector<PipeId> used;
    {
      const auto first = compile_sewer_task(map, mission, progress, cached);
      ASSERT_TRUE(first.has_value());
      used = driven_pipes(*first);
    }
    for (std::size_t i = 0; i + 1 < used.size() && i < 6; ++i) {
      SCOPED_TRACE("seed " + std::to_string(seed) + " pipe " + std::to_string(i));
      const PipeId p = used[i];
      const double len = map.pipe(p).length_m;
      Mission m = mission;
      progress.position = InPipe{p, len / 2};
      if (i % 2 == 0) {
        m.blockages.push_back({p, len / 4});
        m.blockages.push_back({p, 3 * len / 4});
      }
      m.blockages.push_back({used[i + 1], map.pipe(used[i + 1]).length_m / 2});
      const auto with = compile_sewer_task(map, m, progress, cached);
      const auto without = compile_sewer_task(map, m, progress, options);
      EXPECT_EQ(with.has_value(), without.has_value());
      if (with.has_value() && without.has_value()) {
        testing::expect_identical_task(*with, *without);
        ++compared;
      } else if (!with.has_value() && !without.has_value()) {
        EXPECT_EQ(with.error().message, without.error().message);
      }
    }
  }
  EXPECT_GT(compared, 10U);
}

}  // namespace
}  // namespace sewerplan::domain
