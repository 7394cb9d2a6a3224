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
#include "sewerplan/domain/mission_generator.h"

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

}  // namespace
}  // namespace sewerplan::domain::detail
