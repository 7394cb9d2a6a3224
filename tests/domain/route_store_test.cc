// SPDX-License-Identifier: MIT
#include "route_store.h"

#include <vector>

#include <gtest/gtest.h>

#include "graph_search.h"
#include "position_graph.h"
#include "support/ais_testbed.h"

namespace sewerplan::domain::detail {
namespace {

// Routes kept from a search read back as that search's paths, each its own stretch.
TEST(RouteStore, KeepsEachRouteAsTheSearchsPath) {
  const testing::AisTestbed bed = testing::load_ais_testbed();
  PositionGraph graph(bed.map, bed.mission);
  GraphSearch search(graph);
  const Node source = graph.in_manhole(ManholeId{0});
  std::vector<Node> targets;
  for (PipeId p : bed.map.pipe_ids()) {
    targets.push_back(graph.pipe_end(p, 0));
    targets.push_back(graph.pipe_end(p, 1));
  }
  search.run(std::span<const Node>(&source, 1), targets, kInfiniteCost,
             GraphSearch::Direction::kForward);
  // The pipe ends the robot can reach (some it cannot enter from the start's side).
  std::erase_if(targets, [&](Node n) { return search.distance(n) == kInfiniteCost; });
  ASSERT_GE(targets.size(), 5U);
  RouteStore store;
  std::vector<RouteRef> refs;
  for (Node n : targets) refs.push_back(store.keep(search, n));
  std::size_t total = 0;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    std::vector<Node> path;
    search.path(targets[i], path);
    ASSERT_FALSE(path.empty());
    const std::span<const Node> kept = store.route(refs[i]);
    EXPECT_EQ(std::vector<Node>(kept.begin(), kept.end()), path);
    total += path.size();
  }
  EXPECT_EQ(store.size(), total);
}

// The one-time reservation follows the first row but is capped: a row times a huge key count
// would ask for more memory than exists (before the cap: start routes x 1.5 k, unbounded).
TEST(RouteStore, CapsItsReservation) {
  const testing::AisTestbed bed = testing::load_ais_testbed();
  PositionGraph graph(bed.map, bed.mission);
  GraphSearch search(graph);
  const Node source = graph.in_manhole(ManholeId{0});
  const Node target = graph.pipe_end(PipeId{0}, 1);
  search.run(std::span<const Node>(&source, 1), std::span<const Node>(&target, 1), kInfiniteCost,
             GraphSearch::Direction::kForward);
  ASSERT_NE(search.distance(target), kInfiniteCost);
  RouteStore store;
  store.keep(search, target);
  store.reserve_rows(std::size_t{1} << 40U);
  EXPECT_LE(store.capacity(), RouteStore::kMaxReservedNodes);
  EXPECT_GE(store.capacity(), store.size());
  RouteStore small;
  small.keep(search, target);
  small.reserve_rows(10);
  EXPECT_GE(small.capacity(), small.size() * 15) << "a row, for 10 keys and half again";
}

}  // namespace
}  // namespace sewerplan::domain::detail
