// SPDX-License-Identifier: MIT
// GraphSearch against a reference Dijkstra: the same distances and the same paths, ties and all.
//
// The compile's routes (and so its plans, byte for byte) rest on how the search breaks ties: nodes
// settled in the order of (distance, node), a node's parent the first settled node reaching it at
// its distance. The reference here is the textbook form of that rule (a binary heap of
// (distance, node) pairs, lazy deletion, a parent replaced only by a shorter way); the search's
// own heap, arrays and encodings may change (issue 35), its answers may not.
#include "graph_search.h"

#include <algorithm>
#include <functional>
#include <queue>
#include <span>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/rng.h"
#include "sewerplan/domain/mission_generator.h"

#include "contraction_hierarchy.h"
#include "joined_search.h"
#include "position_graph.h"
#include "support/scrambled_network.h"

namespace sewerplan::domain::detail {
namespace {

struct Reference {
  std::vector<Cost> dist;
  std::vector<Node> parent;  // kNone: none
  std::size_t ties = 0;      // nodes reached at their distance by more than one settled node
};
constexpr Node kNone = 0xffffffffU;

Reference reference(const PositionGraph& graph, Node source, GraphSearch::Direction direction) {
  Reference r{std::vector<Cost>(graph.size(), kInfiniteCost),
              std::vector<Node>(graph.size(), kNone), 0};
  std::vector<bool> settled(graph.size(), false);
  using Entry = std::pair<Cost, Node>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  r.dist[source] = 0;
  open.emplace(0, source);
  while (!open.empty()) {
    const Entry top = open.top();
    open.pop();
    const Cost d = top.first;
    const Node n = top.second;
    if (settled[n] || d != r.dist[n]) continue;
    settled[n] = true;
    auto relax = [&](Node to, Cost c) {
      if (d + c == r.dist[to] && r.parent[to] != n) ++r.ties;
      if (d + c < r.dist[to]) {
        r.dist[to] = d + c;
        r.parent[to] = n;
        open.emplace(d + c, to);
      }
    };
    if (direction == GraphSearch::Direction::kForward) {
      graph.for_each_successor(n, relax);
    } else {
      graph.for_each_predecessor(n, relax);
    }
  }
  return r;
}

// Every node's distance and path from (or, backward, to) each of a few sources, as the reference
// finds them; `min_ties`: how many ties the graph must have for the check to mean something.
void expect_same_as_reference(const SewerMap& map, const Mission& mission, std::size_t min_ties) {
  PositionGraph graph(map, mission);
  std::vector<Node> all(graph.size());
  for (Node n = 0; n < graph.size(); ++n) all[n] = n;
  SearchScratch scratch;  // shared by both directions' searches, as the compile's is
  std::size_t ties = 0;
  std::size_t total_reached = 0;  // nodes checked, over every source and direction
  for (const auto direction :
       {GraphSearch::Direction::kForward, GraphSearch::Direction::kBackward}) {
    GraphSearch search(graph, &scratch);
    for (std::size_t i = 0; i < 12; ++i) {
      // Sources over the map: manholes (forward), slots (backward), spread over the numbers.
      const Node source =
          direction == GraphSearch::Direction::kForward
              ? graph.in_manhole(
                    ManholeId{static_cast<std::uint32_t>(i * map.manhole_count() / 12)})
              : graph.at_slot(ManholeId{static_cast<std::uint32_t>(i * map.manhole_count() / 12)},
                              SlotIndex{0});
      const Reference want = reference(graph, source, direction);
      ties += want.ties;
      search.run(std::span<const Node>(&source, 1), all, kInfiniteCost, direction);
      std::vector<Node> path, expected;
      std::size_t reached = 0;
      for (Node n = 0; n < graph.size(); ++n) {
        ASSERT_EQ(search.distance(n), want.dist[n]) << "node " << n << " source " << source;
        if (want.dist[n] == kInfiniteCost) continue;
        ++reached;
        expected.clear();
        for (Node at = n; at != kNone; at = want.parent[at]) expected.push_back(at);
        if (direction == GraphSearch::Direction::kForward) {
          std::reverse(expected.begin(), expected.end());
        }
        search.path(n, path);
        ASSERT_EQ(path, expected) << "node " << n << " source " << source;
      }
      total_reached += reached;
    }
  }
  EXPECT_GT(total_reached, 2 * graph.size());
  EXPECT_GE(ties, min_ties);
}

// Our generator's network, numbered street by street.
TEST(GraphSearch, SettlesAndBreaksTiesAsTheReferenceOnALattice) {
  const SewerMap map =
      *generate_network({.manholes = 400, .seed = 3, .topology = Topology::kMeshed});
  const Mission mission = *generate_mission(map, {.tasks = 3, .seed = 1});
  expect_same_as_reference(map, mission, 0);
}

// Numbered without spatial order (issue 35), with hundreds of ties (ways of equal cost from
// nodes settled in another order than their numbers).
TEST(GraphSearch, SettlesAndBreaksTiesAsTheReferenceOnAScrambledNetwork) {
  const SewerMap map = *bench::generate_scrambled_network({.manholes = 400, .seed = 4});
  const Mission mission = *bench::scrambled_mission(map, 3, 1);
  expect_same_as_reference(map, mission, 100);
}

// The shortest ways from the reference's source to n: 1, or 2 for more (memoised over the moves
// into n at its distance; no cycle costs 0).
int ways_to(const PositionGraph& graph, const Reference& ref, Node source, Node n,
            std::vector<int>& memo) {
  if (n == source) return 1;
  if (memo[n] != 0) return memo[n];
  int ways = 0;
  graph.for_each_predecessor(n, [&](Node u, Cost c) {
    if (ref.dist[u] != kInfiniteCost && ref.dist[u] + c == ref.dist[n]) {
      ways = std::min(2, ways + ways_to(graph, ref, source, u, memo));
    }
  });
  memo[n] = ways;
  return ways;
}

// run_toward (issue 35) on a mission's graph with blockages and closed pipes, guided by the
// routing index of the map's graph without them: for pairs from manholes, slots and spots inside
// pipes, the target's distance and, where the shortest way is the only one, the reference's way;
// kTied exactly where the reference counts more than one; kUnreached where none is within the
// bound; kGaveUp when the settle limit is too small.
// `every`: one pipe in so many blocked (and one in 2.5 times as many closed).
void expect_toward_as_reference(const SewerMap& map, Mission mission, std::uint32_t every,
                                std::size_t min_tied) {
  Rng rng(5);
  for (std::uint32_t p = 3; p < map.pipe_count(); p += every) {
    mission.blockages.push_back({PipeId{p}, map.pipe(PipeId{p}).length_m * rng.uniform(0.1, 0.9)});
  }
  for (std::uint32_t p = 11; p < map.pipe_count(); p += every * 5 / 2) {
    mission.closed_pipes.push_back(PipeId{p});
  }
  PositionGraph graph(map, mission);
  ASSERT_TRUE(graph.build_adjacency(nullptr));
  const GraphCore& core = graph.core();
  auto ch = ContractionHierarchy::build(core.adjacency_begin, core.adjacency_to,
                                        core.adjacency_cost, {.keep_ties = true});
  ASSERT_TRUE(ch.has_value());
  ChQuery index(*ch);
  // The search ended where the index's own way is the rest (as the compile does it).
  JoinedSearch joined_search(graph, index);
  std::size_t joined = 0;
  std::vector<Node> sources;
  for (std::uint32_t m = 0; m < map.manhole_count(); m += 29) {
    sources.push_back(graph.in_manhole(ManholeId{m}));
    sources.push_back(graph.at_slot(ManholeId{m}, SlotIndex{0}));
  }
  for (std::uint32_t p = 5; p < map.pipe_count(); p += 37) {
    sources.push_back(graph.spot(PipeId{p}, map.pipe(PipeId{p}).length_m * 0.4));
  }
  SearchScratch scratch;
  GraphSearch search(graph, &scratch);
  std::size_t unique = 0, tied = 0, unreached = 0, gave_up = 0;
  for (Node source : sources) {
    const Reference want = reference(graph, source, GraphSearch::Direction::kForward);
    std::vector<int> memo(graph.size(), 0);
    for (int i = 0; i < 12; ++i) {
      const auto t =
          static_cast<Node>(map.manhole_count() + rng.below(graph.size() - map.manhole_count()));
      if (t == source || graph.is_extra_spot(t)) continue;
      SCOPED_TRACE(std::to_string(source) + " -> " + std::to_string(t));
      index.aim_at(t);
      const auto guide = [&](Node n) {
        return graph.is_extra_spot(n) ? 0 : index.distance_to_aim(n);
      };
      // Half the pairs within a bound short of the way's cost.
      const Cost bound =
          want.dist[t] != kInfiniteCost && i % 4 == 3 ? want.dist[t] - 1 : kInfiniteCost;
      const GraphSearch::Toward got = search.run_toward(source, t, bound, graph.size(), guide);
      index.aim_at(t);
      const JoinedSearch::Way way = joined_search.run(search, source, t, bound, guide);
      const GraphSearch::Toward got_joined = way.result;
      if (way.joined) ++joined;
      index.aim_at(t);
      (void)search.run_toward(source, t, bound, graph.size(), guide);  // path() below: this run's
      if (want.dist[t] == kInfiniteCost || bound < want.dist[t]) {
        EXPECT_EQ(got, GraphSearch::Toward::kUnreached);
        EXPECT_EQ(got_joined, GraphSearch::Toward::kUnreached);
        ++unreached;
        continue;
      }
      if (ways_to(graph, want, source, t, memo) > 1) {
        EXPECT_EQ(got, GraphSearch::Toward::kTied);
        EXPECT_EQ(got_joined, GraphSearch::Toward::kTied);
        ++tied;
        continue;
      }
      ASSERT_EQ(got, GraphSearch::Toward::kUnique);
      ++unique;
      EXPECT_EQ(search.distance(t), want.dist[t]);
      std::vector<Node> path, expected;
      for (Node at = t; at != kNone; at = want.parent[at]) expected.push_back(at);
      std::reverse(expected.begin(), expected.end());
      search.path(t, path);
      EXPECT_EQ(path, expected);
      ASSERT_EQ(got_joined, GraphSearch::Toward::kUnique);
      EXPECT_EQ(way.cost, want.dist[t]);
      EXPECT_EQ(way.path, expected);
      // Too small a limit gives up rather than answer wrong.
      if (path.size() > 3) {
        index.aim_at(t);
        if (search.run_toward(source, t, kInfiniteCost, 1, guide) == GraphSearch::Toward::kGaveUp) {
          ++gave_up;
        }
      }
    }
  }
  EXPECT_GT(unique, 100U);
  EXPECT_GE(tied, min_tied);
  EXPECT_GT(unreached, 20U);
  EXPECT_GT(gave_up, 50U);
  EXPECT_GT(joined, unique / 4);  // many unique ways end where the index knows the rest
}

TEST(GraphSearch, FindsTheWayTowardATargetAroundClosuresAsTheReferenceOnALattice) {
  const SewerMap map =
      *generate_network({.manholes = 400, .seed = 3, .topology = Topology::kMeshed});
  // A tree with a few loops: fewer blockages, or most pairs are cut off.
  expect_toward_as_reference(map, *generate_mission(map, {.tasks = 3, .seed = 1}), 97, 0);
}

TEST(GraphSearch, FindsTheWayTowardATargetAroundClosuresAsTheReferenceOnAScrambledNetwork) {
  const SewerMap map = *bench::generate_scrambled_network({.manholes = 400, .seed = 4});
  expect_toward_as_reference(map, *bench::scrambled_mission(map, 3, 1), 17, 3);
}

}  // namespace
}  // namespace sewerplan::domain::detail
