// SPDX-License-Identifier: MIT
// ContractionHierarchy against a plain Dijkstra over the same compressed-sparse-row graph (issue
// 35): distances point to point and in many-to-many tables, unreachable pairs, and unpacked ways
// that are ways of the graph at the distance found. On a hand-made graph, on our generator's
// networks and on the scrambled generator's (bench/support/scrambled_network.h), whose position
// graphs have the ties and the one-way moves (slots, passages) the index must handle.
#include "contraction_hierarchy.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <functional>
#include <queue>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/rng.h"
#include "sewerplan/domain/mission_generator.h"

#include "position_graph.h"
#include "support/scrambled_network.h"

namespace sewerplan::domain::detail {
namespace {

struct Csr {
  std::vector<std::uint32_t> begin;
  std::vector<Node> to;
  std::vector<Cost> cost;
};

// Rows from a list of moves (from, to, cost) over n nodes.
Csr csr_of(std::uint32_t n, std::vector<std::tuple<Node, Node, Cost>> moves) {
  std::sort(moves.begin(), moves.end());
  Csr g;
  std::size_t i = 0;
  for (Node u = 0; u < n; ++u) {
    g.begin.push_back(static_cast<std::uint32_t>(g.to.size()));
    for (; i < moves.size() && std::get<0>(moves[i]) == u; ++i) {
      g.to.push_back(std::get<1>(moves[i]));
      g.cost.push_back(std::get<2>(moves[i]));
    }
  }
  g.begin.push_back(static_cast<std::uint32_t>(g.to.size()));
  return g;
}

// The position graph's adjacency (the moves the compile reads) of a map without closures.
Csr csr_of(const SewerMap& map, const Mission& mission) {
  PositionGraph graph(map, mission);
  EXPECT_TRUE(graph.build_adjacency(nullptr));
  const GraphCore& core = graph.core();
  return {core.adjacency_begin, core.adjacency_to, core.adjacency_cost};
}

std::vector<Cost> dijkstra(const Csr& g, Node source) {
  std::vector<Cost> dist(g.begin.size() - 1, kInfiniteCost);
  using Entry = std::pair<Cost, Node>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  dist[source] = 0;
  open.emplace(0, source);
  while (!open.empty()) {
    const auto [d, u] = open.top();
    open.pop();
    if (d != dist[u]) continue;
    for (std::uint32_t e = g.begin[u]; e < g.begin[u + 1]; ++e) {
      if (d + g.cost[e] < dist[g.to[e]]) {
        dist[g.to[e]] = d + g.cost[e];
        open.emplace(d + g.cost[e], g.to[e]);
      }
    }
  }
  return dist;
}

ContractionHierarchy build(const Csr& g) {
  auto ch = ContractionHierarchy::build(g.begin, g.to, g.cost);
  EXPECT_TRUE(ch.has_value()) << ch.error();
  return std::move(*ch);
}

// `path` runs s ... t over moves of g, and costs `want` taking the cheapest move at each step.
void expect_way(const Csr& g, Node s, Node t, const std::vector<Node>& path, Cost want) {
  ASSERT_FALSE(path.empty()) << s << " -> " << t;
  EXPECT_EQ(path.front(), s);
  EXPECT_EQ(path.back(), t);
  Cost total = 0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    Cost step = kInfiniteCost;
    for (std::uint32_t e = g.begin[path[i - 1]]; e < g.begin[path[i - 1] + 1]; ++e) {
      if (g.to[e] == path[i]) step = std::min(step, g.cost[e]);
    }
    ASSERT_NE(step, kInfiniteCost) << "no move " << path[i - 1] << " -> " << path[i];
    total += step;
  }
  EXPECT_EQ(total, want) << s << " -> " << t;
}

// Every pair's distance and way, and the table of all nodes against all nodes.
void expect_all_pairs(const Csr& g) {
  const ContractionHierarchy ch = build(g);
  ChQuery query(ch);
  const auto n = static_cast<Node>(g.begin.size() - 1);
  std::vector<Node> all(n);
  for (Node u = 0; u < n; ++u) all[u] = u;
  std::vector<Cost> table;
  query.table(all, all, table);
  std::vector<Node> path;
  for (Node s = 0; s < n; ++s) {
    const std::vector<Cost> want = dijkstra(g, s);
    for (Node t = 0; t < n; ++t) {
      ASSERT_EQ(query.distance(s, t), want[t]) << s << " -> " << t;
      ASSERT_EQ(table[s * n + t], want[t]) << s << " -> " << t;
      ASSERT_EQ(query.path(s, t, path), want[t]);
      if (want[t] == kInfiniteCost) {
        EXPECT_TRUE(path.empty());
      } else {
        expect_way(g, s, t, path, want[t]);
      }
    }
  }
}

TEST(ContractionHierarchy, AnswersEveryPairOfAHandMadeGraphAsDijkstra) {
  // One-way moves, parallel moves of other costs, a loop, ties (0 -> 3 costs 4 two ways), a node
  // nothing reaches (6) and one that reaches nothing (7).
  const Csr g = csr_of(8, {{0, 1, 1},
                           {1, 2, 1},
                           {2, 3, 2},
                           {0, 4, 2},
                           {4, 3, 2},
                           {3, 0, 5},
                           {1, 0, 1},
                           {2, 5, 7},
                           {2, 5, 3},
                           {5, 5, 1},
                           {5, 1, 0},
                           {6, 0, 9},
                           {3, 7, 1}});
  expect_all_pairs(g);
  const ContractionHierarchy ch = build(g);
  ChQuery query(ch);
  EXPECT_EQ(query.distance(0, 6), kInfiniteCost);
  EXPECT_EQ(query.distance(7, 0), kInfiniteCost);
  EXPECT_EQ(query.distance(6, 7), 14);
  EXPECT_EQ(query.distance(2, 1), 3);  // 2 -> 5 -> 1 over the cheaper of the parallel moves
  EXPECT_EQ(ch.statistics().moves, 11U);
}

TEST(ContractionHierarchy, AnswersEveryPairOfSmallPositionGraphsAsDijkstra) {
  const SewerMap ours =
      *generate_network({.manholes = 30, .seed = 2, .topology = Topology::kMeshed});
  expect_all_pairs(csr_of(ours, *generate_mission(ours, {.tasks = 2, .seed = 1})));
  const SewerMap scrambled = *bench::generate_scrambled_network({.manholes = 40, .seed = 5});
  const Csr g = csr_of(scrambled, *bench::scrambled_mission(scrambled, 2, 1));
  expect_all_pairs(g);
  // The check means something only with pairs of both kinds and shortcuts to unpack.
  const ContractionHierarchy ch = build(g);
  EXPECT_GT(ch.statistics().shortcuts, 0U);
  std::size_t unreachable = 0;
  for (Node s = 0; s + 1 < g.begin.size(); ++s) {
    for (Cost d : dijkstra(g, s)) unreachable += d == kInfiniteCost ? 1 : 0;
  }
  EXPECT_GT(unreachable, 0U);
}

// Random pairs (distance and way) and a table of 40 sources by 60 targets against Dijkstra.
void expect_random_pairs_and_table(const Csr& g, std::uint64_t seed) {
  const ContractionHierarchy ch = build(g);
  ChQuery query(ch);
  const auto n = static_cast<Node>(g.begin.size() - 1);
  Rng rng(seed);
  std::vector<Node> path;
  std::size_t reached = 0;
  for (int i = 0; i < 300; ++i) {
    const auto s = static_cast<Node>(rng.below(n));
    const auto t = static_cast<Node>(rng.below(n));
    const std::vector<Cost> want = dijkstra(g, s);
    ASSERT_EQ(query.distance(s, t), want[t]) << s << " -> " << t;
    ASSERT_EQ(query.path(s, t, path), want[t]);
    if (want[t] != kInfiniteCost) {
      ++reached;
      expect_way(g, s, t, path, want[t]);
    }
  }
  EXPECT_GT(reached, 100U);  // manhole nodes (only a start) are reached by no move
  std::vector<Node> sources(40), targets(60);
  for (Node& s : sources) s = static_cast<Node>(rng.below(n));
  for (Node& t : targets) t = static_cast<Node>(rng.below(n));
  targets[7] = sources[3];  // a pair of one node
  std::vector<Cost> table;
  query.table(sources, targets, table);
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const std::vector<Cost> want = dijkstra(g, sources[i]);
    for (std::size_t j = 0; j < targets.size(); ++j) {
      ASSERT_EQ(table[i * targets.size() + j], want[targets[j]]) << i << ", " << j;
    }
  }
}

TEST(ContractionHierarchy, AnswersRandomPairsAndTablesOnOurNetworkAsDijkstra) {
  const SewerMap map =
      *generate_network({.manholes = 1000, .seed = 1, .topology = Topology::kMeshed});
  expect_random_pairs_and_table(csr_of(map, *generate_mission(map, {.tasks = 3, .seed = 1})), 11);
}

TEST(ContractionHierarchy, AnswersRandomPairsAndTablesOnAScrambledNetworkAsDijkstra) {
  const SewerMap map = *bench::generate_scrambled_network({.manholes = 1000, .seed = 1});
  expect_random_pairs_and_table(csr_of(map, *bench::scrambled_mission(map, 3, 1)), 12);
}

// The shortest ways to each node counted (1, or 2 for more; moves of equal cost between the same
// nodes counted apart) over the graph of tight moves, in a memoised walk back from each node:
// the position graph has moves of cost 0 (from a pipe's end to the slot at that end), so an
// order by distance alone could count a node before a predecessor at the same distance. No
// cycle costs 0.
struct Counted {
  std::vector<Cost> dist;
  std::vector<int> ways;     // 0: not yet counted
  std::vector<Node> parent;  // a shortest way's predecessor (the only one where ways is 1)
};
Counted counting_dijkstra(const Csr& g, Node source) {
  const std::size_t n = g.begin.size() - 1;
  Counted c{std::vector<Cost>(n, kInfiniteCost), std::vector<int>(n, 0),
            std::vector<Node>(n, static_cast<Node>(n))};
  using Entry = std::pair<Cost, Node>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  c.dist[source] = 0;
  open.emplace(0, source);
  while (!open.empty()) {
    const auto [d, u] = open.top();
    open.pop();
    if (d != c.dist[u]) continue;
    for (std::uint32_t e = g.begin[u]; e < g.begin[u + 1]; ++e) {
      if (d + g.cost[e] < c.dist[g.to[e]]) {
        c.dist[g.to[e]] = d + g.cost[e];
        c.parent[g.to[e]] = u;
        open.emplace(c.dist[g.to[e]], g.to[e]);
      }
    }
  }
  // The tight moves into each node.
  std::vector<std::vector<Node>> tight(n);
  for (Node u = 0; u < n; ++u) {
    if (c.dist[u] == kInfiniteCost) continue;
    for (std::uint32_t e = g.begin[u]; e < g.begin[u + 1]; ++e) {
      if (g.to[e] != source && c.dist[u] + g.cost[e] == c.dist[g.to[e]]) {
        tight[g.to[e]].push_back(u);
      }
    }
  }
  c.ways[source] = 1;
  std::function<int(Node)> count = [&](Node v) {
    if (c.ways[v] == 0) {
      int ways = 0;
      for (Node p : tight[v]) ways = std::min(2, ways + count(p));
      c.ways[v] = ways;
    }
    return c.ways[v];
  };
  for (Node v = 0; v < n; ++v) {
    if (c.dist[v] != kInfiniteCost) count(v);
  }
  return c;
}

// Whether each pair's shortest way is unique, by distance(), path() and table(), against the
// counting Dijkstra; a unique way is the reference's own. Returns the pairs with more than one.
std::size_t expect_uniqueness(const Csr& g, const std::vector<Node>& sources,
                              const std::vector<Node>& targets) {
  auto ch = ContractionHierarchy::build(g.begin, g.to, g.cost, {.keep_ties = true});
  EXPECT_TRUE(ch.has_value());
  ChQuery query(*ch);
  std::vector<Cost> table;
  std::vector<bool> unique_in_table;
  query.table(sources, targets, table, &unique_in_table);
  ChTable with_ways;
  query.table_with_ways(sources, targets, with_ways);
  std::size_t tied = 0;
  std::vector<Node> path, want;
  std::vector<Counted> refs;
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const Counted& ref = refs.emplace_back(counting_dijkstra(g, sources[i]));
    for (std::size_t j = 0; j < targets.size(); ++j) {
      const Node s = sources[i], t = targets[j];
      const bool want_unique = ref.ways[t] == 1;
      tied += ref.ways[t] > 1 ? 1U : 0U;
      bool unique = !want_unique;
      EXPECT_EQ(query.distance(s, t, &unique), ref.dist[t]);
      EXPECT_EQ(unique, want_unique) << s << " -> " << t;
      unique = !want_unique;
      EXPECT_EQ(query.path(s, t, path, &unique), ref.dist[t]);
      EXPECT_EQ(unique, want_unique) << s << " -> " << t;
      EXPECT_EQ(unique_in_table[i * targets.size() + j], want_unique) << s << " -> " << t;
      EXPECT_EQ(with_ways.distance(i, j), ref.dist[t]) << s << " -> " << t;
      EXPECT_EQ(with_ways.unique(i, j), want_unique) << s << " -> " << t;
      std::vector<Node> table_way;
      with_ways.way(i, j, table_way);
      if (want_unique) {
        want.clear();
        for (Node x = t; x != s; x = ref.parent[x]) want.push_back(x);
        want.push_back(s);
        std::reverse(want.begin(), want.end());
        EXPECT_EQ(path, want) << s << " -> " << t;
        EXPECT_EQ(table_way, want) << s << " -> " << t;
      } else if (ref.dist[t] != kInfiniteCost) {
        expect_way(g, s, t, table_way, ref.dist[t]);  // one of the shortest
      } else {
        EXPECT_TRUE(table_way.empty());
      }
    }
  }
  // The guide's own way (ChQuery::way_to_aim, issue 35): given exactly where it is the only one.
  ChQuery aim(*ch);
  for (std::size_t j = 0; j < targets.size(); ++j) {
    const Node t = targets[j];
    aim.aim_at(t);
    for (std::size_t i = 0; i < sources.size(); ++i) {
      const Node s = sources[i];
      const Counted& ref = refs[i];
      const bool want_unique = ref.ways[t] == 1 && ref.dist[t] != kInfiniteCost;
      Cost cost = kInfiniteCost;
      EXPECT_EQ(aim.way_to_aim(s, path, nullptr, &cost), want_unique) << s << " -> " << t;
      if (!want_unique) continue;
      want.clear();
      for (Node x = t; x != s; x = ref.parent[x]) want.push_back(x);
      want.push_back(s);
      std::reverse(want.begin(), want.end());
      EXPECT_EQ(path, want) << s << " -> " << t;
      EXPECT_EQ(cost, ref.dist[t]) << s << " -> " << t;
    }
  }
  return tied;
}

TEST(ContractionHierarchy, TellsWhetherTheShortestWayIsUniqueAsACountingDijkstra) {
  // Hand-made: 0 -> 3 two ways of 4, 0 -> 5 through two parallel moves of 2, 0 -> 6 unique.
  const Csr hand = csr_of(7, {{0, 1, 1},
                              {1, 3, 3},
                              {0, 2, 2},
                              {2, 3, 2},
                              {3, 4, 1},
                              {4, 5, 2},
                              {4, 5, 2},
                              {4, 5, 3},
                              {0, 6, 9},
                              {6, 0, 1}});
  std::vector<Node> all(7);
  for (Node u = 0; u < 7; ++u) all[u] = u;
  EXPECT_GT(expect_uniqueness(hand, all, all), 3U);
  // Moves of cost 0 (a pipe's end to its slot, in the position graph) into a node with a tie.
  const Csr zero = csr_of(6, {{0, 1, 2}, {1, 2, 0}, {0, 3, 1}, {3, 2, 1}, {2, 4, 1}, {5, 2, 0}});
  all.resize(6);
  for (Node u = 0; u < 6; ++u) all[u] = u;
  EXPECT_GT(expect_uniqueness(zero, all, all), 1U);

  const SewerMap small = *bench::generate_scrambled_network({.manholes = 40, .seed = 5});
  const Csr g = csr_of(small, *bench::scrambled_mission(small, 2, 1));
  all.resize(g.begin.size() - 1);
  for (Node u = 0; u < all.size(); ++u) all[u] = u;
  EXPECT_GT(expect_uniqueness(g, all, all), 10U);

  const SewerMap map = *bench::generate_scrambled_network({.manholes = 1000, .seed = 1});
  const Csr big = csr_of(map, *bench::scrambled_mission(map, 3, 1));
  Rng rng(13);
  std::vector<Node> sources(30), targets(200);
  for (Node& s : sources) s = static_cast<Node>(rng.below(big.begin.size() - 1));
  for (Node& t : targets) t = static_cast<Node>(rng.below(big.begin.size() - 1));
  EXPECT_GT(expect_uniqueness(big, sources, targets), 10U);
}

TEST(ContractionHierarchy, RefusesNegativeAndOversizedCosts) {
  const Csr negative = csr_of(2, {{0, 1, -1}});
  EXPECT_FALSE(ContractionHierarchy::build(negative.begin, negative.to, negative.cost).has_value());
  const Csr large = csr_of(2, {{0, 1, 5'000'000'000}});
  EXPECT_FALSE(ContractionHierarchy::build(large.begin, large.to, large.cost).has_value());
  // Two hubs (0, 1) with three leaves each, joined both ways through node 2, which is contracted
  // before them: each move fits 32 bits, the shortcuts 0 -> 1 and 1 -> 0 over 2 do not.
  auto hubs = [](Cost half) {
    std::vector<std::tuple<Node, Node, Cost>> moves{
        {0, 2, half}, {2, 1, half}, {1, 2, half}, {2, 0, half}};
    for (Node leaf = 3; leaf < 9; ++leaf) {
      const Node hub = leaf < 6 ? 0 : 1;
      moves.emplace_back(hub, leaf, 1);
      moves.emplace_back(leaf, hub, 1);
    }
    return csr_of(9, moves);
  };
  const Csr too_far = hubs(3'000'000'000);
  const auto ch = ContractionHierarchy::build(too_far.begin, too_far.to, too_far.cost);
  ASSERT_FALSE(ch.has_value());
  EXPECT_EQ(ch.error().code, ErrorCode::kInvalidArgument);
  const Csr fits = hubs(2'000'000'000);
  auto ok = ContractionHierarchy::build(fits.begin, fits.to, fits.cost);
  ASSERT_TRUE(ok.has_value());
  EXPECT_GT(ok->statistics().shortcuts, 0U);
  ChQuery query(*ok);
  EXPECT_EQ(query.distance(3, 8), 4'000'000'002);
}

// A build stopped by its stop condition fails as cancelled, naming how far it got, and one that
// is not stopped is built whole.
TEST(ContractionHierarchy, StopsItsBuildWhenAskedAndSaysHowFarItGot) {
  const SewerMap map = *bench::generate_scrambled_network({.manholes = 400, .seed = 5});
  const Csr g = csr_of(map, *bench::scrambled_mission(map, 2, 1));
  std::atomic<bool> cancel{true};
  const StopCondition stop = StopCondition().with_cancel(cancel);
  const auto stopped = ContractionHierarchy::build(g.begin, g.to, g.cost, {.stop = &stop});
  ASSERT_FALSE(stopped.has_value());
  EXPECT_EQ(stopped.error().code, ErrorCode::kCancelled);
  EXPECT_NE(stopped.error().message.find("was stopped"), std::string::npos)
      << stopped.error().message;
  cancel = false;
  const auto built = ContractionHierarchy::build(g.begin, g.to, g.cost, {.stop = &stop});
  ASSERT_TRUE(built.has_value());
  EXPECT_EQ(built->size(), g.begin.size() - 1);
}

}  // namespace
}  // namespace sewerplan::domain::detail
