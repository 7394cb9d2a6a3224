// SPDX-License-Identifier: MIT
// The tour search's incremental costs (search/src/tour_costs.h): a trial order priced from the
// current order's costs costs exactly what the trial order costs when read whole, so the tour
// search takes the same steps as when it evaluated every trial whole.
#include "tour_costs.h"

#include <algorithm>
#include <random>

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"

#include "tour_shape.h"

namespace sewerplan::search::detail {
namespace {

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

}  // namespace
}  // namespace sewerplan::search::detail
