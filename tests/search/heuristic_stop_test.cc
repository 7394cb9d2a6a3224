// SPDX-License-Identifier: MIT
// Issue 14: a heuristic watching a stop condition honours it inside its own work (the relaxed
// task's construction and the relaxed exploration), and a search whose first evaluation is
// interrupted reports the stop. An interrupted evaluation leaves nothing wrong behind: the next
// one, unwatched, gives what a heuristic never interrupted gives.
#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"
#include "sewerplan/search/best_first_search.h"
#include "sewerplan/search/enforced_hill_climbing.h"
#include "sewerplan/search/heuristic.h"

#include "support/ticking_clock.h"

namespace sewerplan::search {
namespace {

struct Compiled {
  SewerMap map = *generate_network({.manholes = 1000, .seed = 3, .topology = Topology::kMeshed});
  Mission mission = *domain::generate_mission(map, {.tasks = 30, .seed = 3});
  domain::SewerTask task = *domain::compile_sewer_task(
      map, mission, domain::initial_progress(mission, map), {.select_goals = true});
};

// A 30-task mission on 1,000 manholes: a relaxed task of thousands of actions.
const Compiled& compiled() {
  static const Compiled c;
  return c;
}

class HeuristicStop : public ::testing::TestWithParam<HeuristicKind> {};

TEST_P(HeuristicStop, AnInterruptedEvaluationLeavesTheNextOneExact) {
  const domain::CompiledTask& task = compiled().task.task();
  std::vector<ActionId> expected_helpful;
  const Cost expected =
      make_heuristic(GetParam(), task)->evaluate(task.initial_state(), &expected_helpful);
  ASSERT_GE(expected, 0);

  // Interrupted at the n-th check, for every n until an evaluation completes: each gives no
  // estimate, and resuming after each (unwatched) gives the uninterrupted estimate.
  int interrupted = 0;
  for (double n = 1;; ++n) {
    auto h = make_heuristic(GetParam(), task);
    testing::TickingClock clock(1.0);
    const StopCondition stop = StopCondition::at_deadline(clock, n);
    h->watch(&stop);
    std::vector<ActionId> helpful;
    const Cost watched = h->evaluate(task.initial_state(), &helpful);
    h->watch(nullptr);
    if (watched != Heuristic::kInterrupted) {
      EXPECT_EQ(watched, expected);
      break;
    }
    ++interrupted;
    EXPECT_EQ(h->evaluate(task.initial_state(), &helpful), expected) << "interrupted at " << n;
    EXPECT_EQ(helpful, expected_helpful) << "interrupted at " << n;
    ASSERT_LT(n, 1e5) << "the evaluation never completes";
  }
  // The construction and the exploration each ask more than once on this task.
  EXPECT_GT(interrupted, 2);
}

INSTANTIATE_TEST_SUITE_P(DeleteRelaxations, HeuristicStop,
                         ::testing::Values(HeuristicKind::kFf, HeuristicKind::kAdd,
                                           HeuristicKind::kMax));

// A stop that fires inside the first evaluation: the engines report it, with no plan and no
// state evaluated, rather than going on with the next expansion.
TEST(EngineStop, AStopDuringTheFirstEvaluationIsReported) {
  const domain::CompiledTask& task = compiled().task.task();
  for (int engine = 0; engine < 3; ++engine) {
    testing::TickingClock clock(1.0);
    const StopCondition stop = StopCondition::at_deadline(clock, 3);
    auto h = make_heuristic(engine == 2 ? HeuristicKind::kMax : HeuristicKind::kFf, task);
    SearchResult r;
    if (engine == 0) {
      r = EnforcedHillClimbing(task, *h).search(stop);
    } else {
      r = BestFirstSearch(task, *h,
                          engine == 1 ? BestFirstSearch::greedy() : BestFirstSearch::astar())
              .search(stop);
    }
    EXPECT_EQ(r.status, SearchStatus::kTimeLimit) << "engine " << engine;
    EXPECT_TRUE(r.plan.empty());
    EXPECT_EQ(r.statistics.evaluated, 0U) << "engine " << engine;
    EXPECT_EQ(r.statistics.expanded, 0U) << "engine " << engine;
    // The engine no longer watches: the heuristic's own evaluations are unbounded again.
    EXPECT_EQ(h->watched(), nullptr);
    EXPECT_GE(h->evaluate(task.initial_state(), nullptr), 0);
  }
}

}  // namespace
}  // namespace sewerplan::search
