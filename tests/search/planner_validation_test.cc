// SPDX-License-Identifier: MIT
// The planner checked by independent means: every plan replayed by the validator, the optimal
// mode against the brute-force oracle, and generated networks from ten to 100,000 manholes.
#include <map>

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/domain/mission_generator.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/search/planner.h"

#include "support/ais_testbed.h"
#include "support/brute_force.h"

namespace sewerplan::search {
namespace {

// The planner adds costs rounded to milliseconds per action; the validator adds exact seconds.
double tolerance_s(const domain::Plan& plan) {
  return 0.0005 * static_cast<double>(plan.steps.size()) + 1e-9;
}

void expect_valid(const SewerMap& map, const Mission& mission, const PlanOutcome& outcome) {
  const domain::ValidationReport report = domain::validate_plan(outcome.plan, map, mission);
  EXPECT_TRUE(report.valid) << report << "\n" << domain::format_plan(outcome.plan, map, mission);
  EXPECT_NEAR(report.total_cost_s, outcome.cost_s, tolerance_s(outcome.plan));
}

const SewerMap& network(std::size_t manholes, std::uint64_t seed) {
  static std::map<std::pair<std::size_t, std::uint64_t>, SewerMap> cache;
  auto key = std::make_pair(manholes, seed);
  auto it = cache.find(key);
  if (it == cache.end()) {
    auto map =
        generate_network({.manholes = manholes, .seed = seed, .topology = Topology::kMeshed});
    it = cache.emplace(key, std::move(*map)).first;
  }
  return it->second;
}

TEST(PlannerValidation, ThePapersPlanIsValidAndAsCheapAsTheOracle) {
  const testing::AisTestbed ais = testing::load_ais_testbed();
  auto outcome = plan_mission(ais.map, ais.mission, domain::initial_progress(ais.mission, ais.map),
                              {.algorithm = Algorithm::kAstar});
  ASSERT_TRUE(outcome.has_value()) << outcome.error();
  expect_valid(ais.map, ais.mission, *outcome);
  const testing::BruteForceOutcome best = testing::brute_force_optimal_plan(ais.map, ais.mission);
  ASSERT_TRUE(best.has_value());
  EXPECT_NEAR(outcome->cost_s, best->cost_s, tolerance_s(outcome->plan));
}

struct Size {
  std::size_t manholes;
  std::size_t tasks;
};

class GeneratedNetworks : public ::testing::TestWithParam<Size> {};

// Generated missions are random: some have no plan (the robot's limits can make a route one-way;
// the optimal-mode test checks such verdicts against the oracle). Seeds are drawn until two
// missions have plans, and every algorithm's plan for them must be valid.
TEST_P(GeneratedNetworks, EveryAlgorithmPlansValidly) {
  const auto [manholes, tasks] = GetParam();
  std::size_t solved = 0;
  for (std::uint64_t seed = 1; seed <= 8 && solved < 2; ++seed) {
    const SewerMap& map = network(manholes, seed);
    auto mission = domain::generate_mission(map, {.tasks = tasks, .seed = seed});
    ASSERT_TRUE(mission.has_value()) << mission.error();
    const auto progress = domain::initial_progress(*mission, map);
    auto first = plan_mission(map, *mission, progress, {.time_limit_s = 120});
    if (!first.has_value() && first.error().code == ErrorCode::kNoPlan) continue;
    ++solved;
    std::vector<Algorithm> algorithms{Algorithm::kAuto};
    if (manholes <= 10000) algorithms.insert(algorithms.end(), {Algorithm::kEhc, Algorithm::kGbfs});
    for (Algorithm a : algorithms) {
      // The limit only keeps a broken search from hanging the suite; plans come in well under it.
      auto outcome = plan_mission(map, *mission, progress, {.algorithm = a, .time_limit_s = 120});
      ASSERT_TRUE(outcome.has_value()) << manholes << " manholes, " << tasks << " tasks, seed "
                                       << seed << ", " << to_string(a) << ": " << outcome.error();
      expect_valid(map, *mission, *outcome);
    }
  }
  EXPECT_EQ(solved, 2U) << "fewer than two of eight generated missions have a plan";
}

INSTANTIATE_TEST_SUITE_P(TenTo100000Manholes, GeneratedNetworks,
                         ::testing::Values(Size{10, 3}, Size{100, 3}, Size{100, 10}, Size{1000, 10},
                                           Size{1000, 20}, Size{10000, 20}, Size{100000, 3},
                                           Size{100000, 20}),
                         [](const auto& param_info) {
                           return std::to_string(param_info.param.manholes) + "_manholes_" +
                                  std::to_string(param_info.param.tasks) + "_tasks";
                         });

class OptimalMode : public ::testing::TestWithParam<std::size_t> {};

TEST_P(OptimalMode, MatchesTheBruteForceOptimum) {
  const std::size_t tasks = GetParam();
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const SewerMap& map = network(40, seed);
    auto mission = domain::generate_mission(map, {.tasks = tasks, .seed = seed});
    ASSERT_TRUE(mission.has_value()) << mission.error();
    auto outcome = plan_mission(map, *mission, domain::initial_progress(*mission, map),
                                {.algorithm = Algorithm::kAstar});
    const testing::BruteForceOutcome best = testing::brute_force_optimal_plan(map, *mission);
    ASSERT_NE(best.status(), testing::BruteForceStatus::kStateLimit);
    ASSERT_EQ(outcome.has_value(), best.has_value())
        << "seed " << seed << ": " << (outcome.has_value() ? "" : outcome.error().message);
    if (!best.has_value()) continue;
    expect_valid(map, *mission, *outcome);
    EXPECT_NEAR(outcome->cost_s, best->cost_s, tolerance_s(outcome->plan)) << "seed " << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(UpToEightTasks, OptimalMode, ::testing::Values(1, 3, 5, 8));

}  // namespace
}  // namespace sewerplan::search
