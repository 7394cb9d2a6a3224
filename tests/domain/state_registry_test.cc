// SPDX-License-Identifier: MIT
// StateRegistry: IDs in insertion order and duplicates found, also while its hash table grows a
// slice per insert (issue 14); SegmentedVector: grows without moving what it holds.
#include "sewerplan/domain/state_registry.h"

#include <gtest/gtest.h>

#include "sewerplan/domain/segmented_vector.h"

namespace sewerplan::domain {
namespace {

// Two variables of 1,024 values and a bit: two 64-bit bins would not be needed, one is.
CompiledTask grid_task() {
  CompiledTask::Builder b;
  b.add_variable(1024, "x");
  b.add_variable(1024, "y");
  b.add_variable(2, "bit");
  b.set_initial({0, 0, 0});
  b.add_goal({VarId{2}, 1});
  return std::move(b).build();
}

std::vector<std::int32_t> state_of(std::uint32_t k) {
  return {static_cast<std::int32_t>(k % 1024), static_cast<std::int32_t>(k / 1024 % 1024),
          static_cast<std::int32_t>(k / (1024 * 1024) % 2)};
}

// 300,000 states (the table grows 13 times): every state gets the next ID, and between two new
// states an old one (the first, the previous, one half-way back) is found with its ID: lookups
// during the preparation and the move of every growth.
TEST(StateRegistry, GivesIdsInInsertionOrderAndFindsEveryStateWhileItGrows) {
  const CompiledTask task = grid_task();
  StateRegistry registry(task);
  constexpr std::uint32_t kStates = 300'000;
  // Spread over the key space so that neighbours in insertion order hash far apart.
  auto key = [](std::uint32_t i) { return (i * 2'654'435'761U) % (2U * 1024 * 1024); };
  for (std::uint32_t i = 0; i < kStates; ++i) {
    const auto [id, added] = registry.insert(state_of(key(i)));
    ASSERT_TRUE(added) << i;
    ASSERT_EQ(id.index(), i);
    for (std::uint32_t old : {0U, i / 2, i}) {
      const auto [again, added_again] = registry.insert(state_of(key(old)));
      ASSERT_FALSE(added_again) << i << " " << old;
      ASSERT_EQ(again.index(), old) << i;
    }
  }
  EXPECT_EQ(registry.size(), kStates);
  std::vector<std::int32_t> values;
  for (std::uint32_t i = 0; i < kStates; i += 997) {
    registry.unpack(StateId{i}, values);
    EXPECT_EQ(values, state_of(key(i))) << i;
  }
  // Every state is found again once the growth is over.
  for (std::uint32_t i = 0; i < kStates; ++i) {
    ASSERT_EQ(registry.insert(state_of(key(i))), std::make_pair(StateId{i}, false)) << i;
  }
  EXPECT_EQ(registry.bins_per_state(), 1U);
  EXPECT_GE(registry.memory_bytes(), kStates * (sizeof(std::uint64_t) + 2 * sizeof(std::uint32_t)));
}

TEST(SegmentedVector, GrowsWithoutMovingAndValueInitialises) {
  SegmentedVector<std::uint64_t> v;
  EXPECT_EQ(v.size(), 0U);
  v.grow_to(3);
  v[2] = 7;
  const std::uint64_t* third = &v[2];
  const std::size_t n = 10 * SegmentedVector<std::uint64_t>::kSegmentSize + 5;
  v.grow_to(n);
  EXPECT_EQ(v.size(), n);
  EXPECT_GE(v.capacity(), n);
  EXPECT_EQ(&v[2], third);
  EXPECT_EQ(v[2], 7U);
  for (std::size_t i = 0; i < n; ++i) {
    if (i != 2) {
      ASSERT_EQ(v[i], 0U) << i;
    }
  }
  v.grow_to(4);  // never shrinks
  EXPECT_EQ(v.size(), n);
}

}  // namespace
}  // namespace sewerplan::domain
