// SPDX-License-Identifier: MIT
// The tour search's incremental costs (search/src/tour_costs.h): a trial order priced from the
// current order's costs costs exactly what the trial order costs when read whole, so the tour
// search takes the same steps as when it evaluated every trial whole.
#include "tour_costs.h"

#include <algorithm>
#include <atomic>
#include <random>

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"

#include "tour_shape.h"

namespace sewerplan::search::detail {
namespace {

using domain::VarId;

Cost whole(const Shape& shape, const std::vector<std::size_t>& order) {
  OrderCosts costs(shape);
  costs.prepare(order);
  return costs.total();
}

TEST(OrderCosts, TrialOrdersCostWhatTheyCostWhole) {
  int shapes = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    auto map = generate_network({.manholes = 300, .seed = seed, .topology = Topology::kMeshed});
    ASSERT_TRUE(map.has_value());
    auto mission = domain::generate_mission(
        *map, {.tasks = 9, .seed = seed, .spread = domain::MissionSpread::kUniform});
    if (!mission.has_value()) continue;
    auto compiled =
        domain::compile_sewer_task(*map, *mission, domain::initial_progress(*mission, *map));
    if (!compiled.has_value()) continue;
    const std::optional<Shape> shape = read_shape(compiled->task());
    ASSERT_TRUE(shape.has_value());
    ++shapes;
    std::vector<std::size_t> order(shape->goals.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), std::mt19937_64(seed));
    const std::size_t n = order.size();
    OrderCosts costs(*shape);
    costs.prepare(order);
    EXPECT_LT(costs.total(), kInfiniteCost);
    std::vector<Cost> moved;
    for (std::size_t i = 0; i < n; ++i) {
      costs.moved(i, n, moved);
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i) continue;
        std::vector<std::size_t> trial = order;
        trial.erase(trial.begin() + static_cast<std::ptrdiff_t>(i));
        trial.insert(trial.begin() + static_cast<std::ptrdiff_t>(j), order[i]);
        EXPECT_EQ(moved[j], whole(*shape, trial)) << "seed " << seed << " move " << i << "->" << j;
      }
      for (std::size_t j = i + 2; j <= n; ++j) {
        std::vector<std::size_t> trial = order;
        std::reverse(trial.begin() + static_cast<std::ptrdiff_t>(i),
                     trial.begin() + static_cast<std::ptrdiff_t>(j));
        EXPECT_EQ(costs.reversed(i, j), whole(*shape, trial)) << "seed " << seed;
      }
    }
    // Insertion: the order without its last goal, that goal put back at every place.
    std::vector<std::size_t> shorter(order.begin(), order.end() - 1);
    costs.prepare(shorter);
    for (std::size_t at = 0; at <= shorter.size(); ++at) {
      std::vector<std::size_t> trial = shorter;
      trial.insert(trial.begin() + static_cast<std::ptrdiff_t>(at), order.back());
      EXPECT_EQ(costs.inserted(at, order.back()), whole(*shape, trial)) << "seed " << seed;
    }
  }
  EXPECT_GE(shapes, 2);
}

// Moves are kept in matrices up to Shape::kDensePlaces places and in a hash map beyond (issue 14:
// the map's nodes took milliseconds to free after a stop): both keep the first move between two
// places unless a later one is cheaper, and a move that stays in place on the side.
CompiledTask moves_task(std::int32_t places) {
  CompiledTask::Builder b;
  const VarId pos = b.add_variable(places, "position");
  const VarId done = b.add_variable(2, "done");
  b.add_action({{pos, 0}}, {{pos, 1}}, 500, "go 0->1");
  b.add_action({{pos, 0}}, {{pos, 1}}, 500, "go 0->1 again, no cheaper");
  b.add_action({{pos, 1}}, {{pos, 2}}, 900, "go 1->2");
  b.add_action({{pos, 1}}, {{pos, 2}}, 700, "go 1->2, cheaper");
  b.add_action({{pos, 2}}, {{pos, 2}}, 100, "stay at 2");
  b.add_action({{pos, 2}, {done, 0}}, {{done, 1}}, 300, "inspect at 2");
  b.add_action({{pos, 2}}, {{pos, 0}}, 1000, "go 2->0");
  b.set_initial(std::vector<std::int32_t>{0, 0});
  b.add_goal({done, 1});
  return std::move(b).build();
}

TEST(ReadShape, DenseAndSparseMovesAgree) {
  const CompiledTask dense_task = moves_task(3);
  const CompiledTask sparse_task = moves_task(Shape::kDensePlaces + 1);
  const std::optional<Shape> dense = read_shape(dense_task);
  const std::optional<Shape> sparse = read_shape(sparse_task);
  ASSERT_TRUE(dense.has_value());
  ASSERT_TRUE(sparse.has_value());
  EXPECT_EQ(dense->move_matrix.size(), 9U);
  EXPECT_TRUE(dense->moves.size() == 1 && dense->moves.contains(2 * 3 + 2));  // the stay
  EXPECT_TRUE(sparse->move_matrix.empty());
  EXPECT_EQ(sparse->moves.size(), 4U);
  for (const Shape* s : {&*dense, &*sparse}) {
    EXPECT_EQ(s->move_cost(0, 1), 500);
    EXPECT_EQ(s->move_action(0, 1), ActionId{0});
    EXPECT_EQ(s->move_cost(1, 2), 700);
    EXPECT_EQ(s->move_action(1, 2), ActionId{3});
    EXPECT_EQ(s->move_cost(2, 0), 1000);
    EXPECT_EQ(s->move_action(2, 0), ActionId{6});
    EXPECT_EQ(s->move_cost(2, 2), 0);
    EXPECT_EQ(s->move_cost(1, 0), kInfiniteCost);
    ASSERT_EQ(s->goals.size(), 1U);
    EXPECT_EQ(s->goals[0].options.size(), 1U);
  }
}

// The flat table beyond kDensePlaces (move_map.h): keys that share a home slot are all found, a
// key is added once, and a stop that has fired leaves it empty and unusable rather than half laid
// out.
TEST(MoveMap, FindsEveryKeyItHolds) {
  MoveMap map;
  ASSERT_TRUE(map.reserve(1000, nullptr));
  EXPECT_EQ(map.find(7), nullptr);
  for (std::int64_t k = 0; k < 1000; ++k) {
    const auto [move, added] =
        map.try_emplace(k * 4099, {k, ActionId{static_cast<std::uint32_t>(k)}});
    EXPECT_TRUE(added);
    EXPECT_EQ(move->cost, k);
  }
  const auto [again, added] = map.try_emplace(5 * 4099, {1, ActionId{1}});
  EXPECT_FALSE(added);
  EXPECT_EQ(again->cost, 5);  // the first one kept: the caller decides whether to replace it
  EXPECT_EQ(map.size(), 1000U);
  for (std::int64_t k = 0; k < 1000; ++k) {
    const MoveMap::Move* m = map.find(k * 4099);
    ASSERT_NE(m, nullptr) << k;
    EXPECT_EQ(m->action, ActionId{static_cast<std::uint32_t>(k)});
    EXPECT_FALSE(map.contains(k * 4099 + 1));
  }
}

TEST(MoveMap, AFiredStopLeavesItEmpty) {
  std::atomic<bool> cancel{true};
  StopCondition stop;
  stop.with_cancel(cancel);
  MoveMap map;
  EXPECT_FALSE(map.reserve(100'000, &stop));
  EXPECT_EQ(map.size(), 0U);
  EXPECT_FALSE(map.contains(0));
  // And the sparse shape is given up, not read with a table that has no room.
  const CompiledTask task = moves_task(Shape::kDensePlaces + 1);
  EXPECT_FALSE(read_shape(task, &stop).has_value());
}

}  // namespace
}  // namespace sewerplan::search::detail
