// SPDX-License-Identifier: MIT
#include "zeroed_array.h"

#include <cstdint>
#include <utility>

#include <gtest/gtest.h>

#include "graph_search.h"
#include "position_graph.h"
#include "support/ais_testbed.h"

namespace sewerplan::domain::detail {
namespace {

// New entries read zero; entries written before a growth keep their values through it, both
// within the room taken at once and past it (a new block).
TEST(ZeroedArray, GrowsWithZerosAndKeepsWhatWasWritten) {
  ZeroedArray<std::int64_t> a;
  EXPECT_EQ(a.size(), 0U);
  a.grow(3);
  ASSERT_EQ(a.size(), 3U);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(a[i], 0);
  a[0] = -7;
  a[2] = 42;
  a.grow(5);  // past the 3 asked first: a new block, with room for 6
  a.grow(2);  // never shrinks
  ASSERT_EQ(a.size(), 5U);
  a[4] = 9;
  a.grow(6);  // within that room
  EXPECT_EQ(a[4], 9);
  EXPECT_EQ(a[5], 0);
  a.grow(1000);  // a new block
  ASSERT_EQ(a.size(), 1000U);
  EXPECT_EQ(a[0], -7);
  EXPECT_EQ(a[1], 0);
  EXPECT_EQ(a[2], 42);
  EXPECT_EQ(a[3], 0);
  EXPECT_EQ(a[4], 9);
  for (std::size_t i = 5; i < 1000; ++i) ASSERT_EQ(a[i], 0) << i;
}

// A clean array (every entry zero) grows without a copy and reads zero; a moved-from array is
// empty and grows again like a new one.
TEST(ZeroedArray, GrowsCleanAndMovesOut) {
  ZeroedArray<std::uint32_t> a;
  a.grow_clean(4);
  ASSERT_EQ(a.size(), 4U);
  a[3] = 5;
  a[3] = 0;  // restored, as a search restores what it touched
  a.grow_clean(100000);
  ASSERT_EQ(a.size(), 100000U);
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], 0U) << i;
  a[99999] = 1;
  ZeroedArray<std::uint32_t> b = std::move(a);
  EXPECT_EQ(b.size(), 100000U);
  EXPECT_EQ(b[99999], 1U);
  EXPECT_EQ(a.size(), 0U);  // NOLINT(bugprone-use-after-move): the moved-from state is the test
  a.grow(3);
  ASSERT_EQ(a.size(), 3U);
  EXPECT_EQ(a[2], 0U);
}

// A search on a shared scratch leaves it clean (zero: every distance infinite, no parent), so the
// next search on it, on a larger graph size too, finds the same distances as on fresh arrays.
TEST(ZeroedArray, SearchScratchIsCleanAfterASearch) {
  const testing::AisTestbed bed = testing::load_ais_testbed();
  PositionGraph graph(bed.map, bed.mission);
  const Node source = graph.in_manhole(ManholeId{0});
  std::vector<Node> targets;
  for (PipeId p : bed.map.pipe_ids()) targets.push_back(graph.pipe_end(p, 1));
  SearchScratch scratch;
  std::vector<Cost> first;
  {
    GraphSearch search(graph, &scratch);
    search.run(std::span<const Node>(&source, 1), targets, kInfiniteCost,
               GraphSearch::Direction::kForward);
    for (Node t : targets) first.push_back(search.distance(t));
  }
  ASSERT_GE(scratch.dist_left.size(), graph.size());
  for (std::size_t n = 0; n < scratch.dist_left.size(); ++n) {
    ASSERT_EQ(scratch.dist_left[n], 0) << n;
    ASSERT_EQ(scratch.parent_plus_one[n], 0U) << n;
  }
  ASSERT_TRUE(GraphSearch::grow(scratch, graph.size() + 100, nullptr));
  GraphSearch again(graph, &scratch);
  GraphSearch fresh(graph);
  for (GraphSearch* s : {&again, &fresh}) {
    s->run(std::span<const Node>(&source, 1), targets, kInfiniteCost,
           GraphSearch::Direction::kForward);
  }
  std::size_t reached = 0;
  for (std::size_t k = 0; k < targets.size(); ++k) {
    EXPECT_EQ(again.distance(targets[k]), first[k]);
    EXPECT_EQ(fresh.distance(targets[k]), first[k]);
    if (first[k] != kInfiniteCost) ++reached;
  }
  EXPECT_GE(reached, 5U);
}

}  // namespace
}  // namespace sewerplan::domain::detail
