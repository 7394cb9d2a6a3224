// SPDX-License-Identifier: MIT
// Tour search: valid plans, near the optimum, goals forgone for the battery, and only for tasks of
// its shape.
#include "sewerplan/search/tour_search.h"

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/search/planner.h"

#include "support/ais_testbed.h"

namespace sewerplan::search {
namespace {

TEST(TourSearch, FindsThePapersOptimalPlan) {
  const auto ais = testing::load_ais_testbed();
  const auto progress = domain::initial_progress(ais.mission, ais.map);
  auto compiled = domain::compile_sewer_task(ais.map, ais.mission, progress);
  ASSERT_TRUE(compiled.has_value());
  auto tour = tour_search(compiled->task());
  ASSERT_TRUE(tour.has_value());
  const domain::Plan plan = compiled->expand(tour->plan);
  const auto report = domain::validate_plan(plan, ais.map, ais.mission);
  EXPECT_TRUE(report.valid) << report.error;
  EXPECT_NEAR(report.total_cost_s, 585.38, 0.01);
}

// On generated missions small enough for A* to prove the optimum, the tour's plan is valid and
// within 10% of it (in practice, mostly equal).
TEST(TourSearch, PlansAreValidAndNearTheOptimum) {
  int compared = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    auto map = generate_network({.manholes = 300, .seed = seed, .topology = Topology::kMeshed});
    ASSERT_TRUE(map.has_value());
    auto mission = domain::generate_mission(*map, {.tasks = 7, .seed = seed});
    if (!mission.has_value()) continue;
    const auto progress = domain::initial_progress(*mission, *map);
    auto compiled = domain::compile_sewer_task(*map, *mission, progress);
    if (!compiled.has_value()) continue;
    auto optimal = plan_mission(*map, *mission, progress, {.algorithm = Algorithm::kAstar});
    auto tour = tour_search(compiled->task());
    if (!optimal.has_value()) {
      continue;  // no plan within the battery (the tour may still be over the bound: empty)
    }
    ASSERT_TRUE(tour.has_value()) << "seed " << seed;
    const domain::Plan plan = compiled->expand(tour->plan);
    const auto report = domain::validate_plan(plan, *map, *mission);
    ASSERT_TRUE(report.valid) << "seed " << seed << ": " << report.error;
    EXPECT_LE(report.total_cost_s, optimal->cost_s * 1.10 + 1e-6) << "seed " << seed;
    EXPECT_GE(report.total_cost_s, optimal->cost_s - 0.01) << "seed " << seed;
    ++compared;
  }
  EXPECT_GE(compared, 4);
}

TEST(TourSearch, OtherTasksAreNotItsShape) {
  domain::CompiledTask::Builder b;
  const auto x = b.add_variable(3, "x");
  const auto y = b.add_variable(3, "y");  // not a binary goal
  b.add_action({{x, 0}}, {{x, 1}, {y, 2}}, 1, "a");
  b.set_initial({0, 0});
  b.add_goal({y, 2});
  const domain::CompiledTask task = std::move(b).build();
  EXPECT_FALSE(tour_search(task).has_value());
}

}  // namespace
}  // namespace sewerplan::search
