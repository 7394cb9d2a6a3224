// SPDX-License-Identifier: MIT
// The planner's portfolio (issue 33): chosen from the problem's size alone, never from the
// compile's work, and run as the data says.
#include "sewerplan/search/portfolio.h"

#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"
#include "sewerplan/search/tour_search.h"

#include "support/ais_testbed.h"

namespace sewerplan::search {
namespace {

std::vector<Engine> engines(const Portfolio& portfolio) {
  std::vector<Engine> out;
  for (const Stage& s : portfolio.stages) out.push_back(s.engine);
  return out;
}

const Stage* stage_of(const Portfolio& portfolio, Engine engine) {
  for (const Stage& s : portfolio.stages) {
    if (s.engine == engine) return &s;
  }
  return nullptr;
}
// The pointer is into `portfolio`: a temporary one would leave it dangling.
const Stage* stage_of(Portfolio&& portfolio, Engine engine) = delete;

// A problem of the tour's shape, with about the sizes the generator's meshed networks give
// (positions about 5.3 per manhole, keys about 2.2 per task, actions about 70 per task).
ProblemSize tour_problem(std::size_t manholes, std::size_t tasks) {
  return {.manholes = manholes,
          .pipes = manholes + manholes / 5,
          .positions = manholes * 53 / 10,
          .tasks = tasks,
          .keys = tasks * 22 / 10,
          .facts = tasks * 4,
          .actions = tasks * 70,
          .states = 1e30};
}

// The 10,000-manhole, 15-task instance on which a compile settling fewer nodes lost the optimum
// (docs/benchmarks.md, issue 16's fifth pass: 38,579 -> 33,040 settled, 9,231.6 -> 9,785.3 s):
// the portfolio, and so the plan, is the same whatever the compile's statistics say of its work.
TEST(Portfolio, DoesNotDependOnTheCompilesWork) {
  auto map = generate_network({.manholes = 10000, .seed = 2, .topology = Topology::kMeshed});
  ASSERT_TRUE(map.has_value());
  auto mission = domain::generate_mission(
      *map, {.tasks = 15, .seed = 2, .spread = domain::MissionSpread::kUniform});
  ASSERT_TRUE(mission.has_value());
  auto compiled = domain::compile_sewer_task(
      *map, *mission, domain::initial_progress(*mission, *map), {.select_goals = true});
  ASSERT_TRUE(compiled.has_value()) << compiled.error();
  const domain::CompileStatistics real = compiled->statistics();
  ASSERT_GT(real.settled_nodes, 0U);
  const PlannerOptions options{.select_goals = true};
  const ProblemSize size = problem_size(*map, compiled->task(), real);
  const Portfolio chosen = choose_portfolio(size, options);
  for (const std::size_t settled :
       {std::size_t{0}, real.settled_nodes / 7, real.settled_nodes * 1000}) {
    domain::CompileStatistics other = real;
    other.settled_nodes = settled;
    other.route_searches = settled / 100;
    other.time_s = 1e-6 * static_cast<double>(settled);
    other.adjacency = !real.adjacency;
    EXPECT_EQ(problem_size(*map, compiled->task(), other), size) << settled;
    EXPECT_EQ(choose_portfolio(problem_size(*map, compiled->task(), other), options), chosen)
        << settled;
  }
  // And it still ends in the exact search, which proves this instance's optimum.
  EXPECT_NE(stage_of(chosen, Engine::kExactImprovement), nullptr);
}

TEST(Portfolio, ProblemSizeReadsTheMapAndTheTask) {
  const auto ais = testing::load_ais_testbed();
  auto compiled = domain::compile_sewer_task(ais.map, ais.mission,
                                             domain::initial_progress(ais.mission, ais.map), {});
  ASSERT_TRUE(compiled.has_value()) << compiled.error();
  const ProblemSize size = problem_size(ais.map, compiled->task(), compiled->statistics());
  EXPECT_EQ(size.manholes, ais.map.manhole_count());
  EXPECT_EQ(size.pipes, ais.map.pipe_count());
  EXPECT_EQ(size.positions, compiled->statistics().graph_nodes);
  EXPECT_EQ(size.keys, compiled->statistics().keys);
  EXPECT_EQ(size.tasks, compiled->task().variable_count() - 1);
  EXPECT_EQ(size.actions, compiled->task().action_count());
  EXPECT_DOUBLE_EQ(size.states, state_count(compiled->task()));
}

// A handful of tasks: A* with h_max alone, optimal by construction, nothing after it.
TEST(ChoosePortfolio, SmallProblemIsAstarAlone) {
  const ProblemSize small{.manholes = 30,
                          .positions = 150,
                          .tasks = 3,
                          .keys = 7,
                          .facts = 40,
                          .actions = 90,
                          .states = 512};
  const Portfolio p = choose_portfolio(small, {});
  ASSERT_EQ(p.stages.size(), 1U);
  EXPECT_EQ(p.stages[0].engine, Engine::kSearch);
  EXPECT_EQ(p.stages[0].algorithm, Algorithm::kAstar);
  EXPECT_EQ(p.stages[0].heuristic, HeuristicKind::kMax);
  // An inadmissible heuristic asked for: the improvement follows.
  const Portfolio ff = choose_portfolio(small, {.heuristic = HeuristicKind::kFf});
  EXPECT_EQ(engines(ff), (std::vector<Engine>{Engine::kSearch, Engine::kImprovement}));
}

// Fifteen tasks: the tour search, weighted A* where the task is not of its shape, then the exact
// search with a table of 512 bytes per unit of estimated route work.
TEST(ChoosePortfolio, FifteenTasksEndInTheExactSearch) {
  const ProblemSize size = tour_problem(10000, 15);
  const Portfolio p = choose_portfolio(size, {.weight = 2.5});
  ASSERT_GE(p.stages.size(), 3U);
  EXPECT_EQ(p.stages[0].engine, Engine::kTourSearch);
  EXPECT_EQ(p.stages[1].engine, Engine::kSearch);
  EXPECT_EQ(p.stages[1].algorithm, Algorithm::kWeightedAstar);
  EXPECT_EQ(p.stages[1].heuristic, HeuristicKind::kFf);
  EXPECT_DOUBLE_EQ(p.stages[1].weight, 2.5);
  EXPECT_EQ(p.stages[2].engine, Engine::kExactImprovement);
  EXPECT_EQ(p.stages[2].budget, kExactBytesPerReach * size.keys * kReachPositions);
}

// The budgets grow with the keys and with the positions up to the battery's reach, not beyond:
// a network ten times larger with the same tasks gets the same portfolio.
TEST(ChoosePortfolio, BudgetsFollowTheSizeUpToTheReach) {
  EXPECT_EQ(choose_portfolio(tour_problem(10000, 15), {}),
            choose_portfolio(tour_problem(100000, 15), {}));
  // On a network smaller than the reach, the table's budget follows its positions.
  ProblemSize tiny = tour_problem(100, 15);
  ASSERT_LT(tiny.positions, kReachPositions);
  const Portfolio tiny_portfolio = choose_portfolio(tiny, {});
  const Stage* exact = stage_of(tiny_portfolio, Engine::kExactImprovement);
  ASSERT_NE(exact, nullptr);
  EXPECT_EQ(exact->budget, kExactBytesPerReach * tiny.keys * tiny.positions);
  // Eight tasks: the exact search fits the improvement's work outright (2^K x 9K^2 units).
  const Portfolio eight = choose_portfolio(tour_problem(10000, 8), {});
  const Stage* ten = stage_of(eight, Engine::kExactImprovement);
  ASSERT_NE(ten, nullptr);
  EXPECT_EQ(ten->budget, kExactDefaultBytes);
}

// Many tasks: no exact search (beyond kMaxExactGoals), and an improvement of no more expansions
// than there are tasks is left out.
TEST(ChoosePortfolio, FiftyTasksKeepTheTourSearchsPlan) {
  const Portfolio p = choose_portfolio(tour_problem(100000, 50), {});
  EXPECT_EQ(engines(p), (std::vector<Engine>{Engine::kTourSearch, Engine::kSearch}));
  // Without the adaptive budget, the improvement gets what the options give.
  const Portfolio fixed =
      choose_portfolio(tour_problem(100000, 50), {.adaptive_improvement = false});
  EXPECT_EQ(engines(fixed),
            (std::vector<Engine>{Engine::kTourSearch, Engine::kSearch, Engine::kImprovement}));
  EXPECT_EQ(fixed.stages.back().budget, PlannerOptions{}.improvement_expansions);
}

TEST(ChoosePortfolio, ExactAndExplicitAlgorithms) {
  const ProblemSize size = tour_problem(1000, 12);
  EXPECT_EQ(engines(choose_portfolio(size, {.algorithm = Algorithm::kExact})),
            (std::vector<Engine>{Engine::kExactTour, Engine::kSearch}));
  const Portfolio gbfs = choose_portfolio(size, {.algorithm = Algorithm::kGbfs});
  EXPECT_EQ(engines(gbfs), (std::vector<Engine>{Engine::kSearch, Engine::kImprovement}));
  EXPECT_EQ(gbfs.stages[0].algorithm, Algorithm::kGbfs);
  EXPECT_EQ(engines(choose_portfolio(size, {.improvement_expansions = 0})),
            (std::vector<Engine>{Engine::kTourSearch, Engine::kSearch}));
}

// run_portfolio runs what the value says: a greedy first plan improved to the optimum, or that
// plan alone.
TEST(RunPortfolio, RunsTheStagesItIsGiven) {
  const auto ais = testing::load_ais_testbed();
  auto compiled = domain::compile_sewer_task(ais.map, ais.mission,
                                             domain::initial_progress(ais.mission, ais.map), {});
  ASSERT_TRUE(compiled.has_value()) << compiled.error();
  const domain::CompiledTask& task = compiled->task();
  const SteadyClock clock;
  const PortfolioFailure failure{.status =
                                     [](SearchStatus) {
                                       return Error{ErrorCode::kNoPlan, "no plan"};
                                     },
                                 .battery_exceeded =
                                     [](Cost) {
                                       return Error{ErrorCode::kSearchLimit, "battery"};
                                     }};
  const Stage greedy{.engine = Engine::kSearch, .algorithm = Algorithm::kGbfs};
  auto alone = run_portfolio({.stages = {greedy}}, task, {}, clock, failure);
  ASSERT_TRUE(alone.has_value()) << alone.error();
  EXPECT_FALSE(alone->optimal);
  EXPECT_EQ(alone->algorithm, "greedy best-first search + ff");
  auto improved =
      run_portfolio({.stages = {greedy, {.engine = Engine::kImprovement, .budget = 100'000}}}, task,
                    {}, clock, failure);
  ASSERT_TRUE(improved.has_value()) << improved.error();
  EXPECT_TRUE(improved->optimal);
  auto optimum =
      run_portfolio({.stages = {{.engine = Engine::kExactTour}}}, task, {}, clock, failure);
  ASSERT_TRUE(optimum.has_value()) << optimum.error();
  EXPECT_EQ(improved->result.cost, optimum->result.cost);
  EXPECT_LE(improved->result.cost, alone->result.cost);
  // A portfolio whose only stage does not apply finds nothing, and says so.
  auto none = run_portfolio({}, task, {}, clock, failure);
  EXPECT_FALSE(none.has_value());
}

}  // namespace
}  // namespace sewerplan::search
