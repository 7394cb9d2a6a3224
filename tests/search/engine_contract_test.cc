// SPDX-License-Identifier: MIT
// The contract every search engine keeps, run against each engine and heuristic pairing.
#include <atomic>

#include <gtest/gtest.h>

#include "sewerplan/search/best_first_search.h"
#include "sewerplan/search/enforced_hill_climbing.h"
#include "sewerplan/search/planner.h"

namespace sewerplan::search {
namespace {

using domain::CompiledTask;
using domain::Fact;
using domain::VarId;

// Positions 0..4 and a bit to collect at position 1. From 0: 0->1 costs 10; 0->2->3->1 costs 3.
// 1->3 costs 10. Goal: at 3 with the bit collected. Optimal: 0,2,3,1,collect,3 = 13.
// Position 4 is unreachable.
CompiledTask collect_task(domain::Cost bound = domain::kInfiniteCost, bool reachable_goal = true) {
  CompiledTask::Builder b;
  const VarId pos = b.add_variable(5, "pos");
  const VarId bit = b.add_variable(2, "bit");
  b.add_action({{pos, 0}}, {{pos, 1}}, 10, "0->1");
  b.add_action({{pos, 0}}, {{pos, 2}}, 1, "0->2");
  b.add_action({{pos, 2}}, {{pos, 3}}, 1, "2->3");
  b.add_action({{pos, 3}}, {{pos, 1}}, 1, "3->1");
  b.add_action({{pos, 1}}, {{pos, 3}}, 10, "1->3");
  b.add_action({{pos, 1}, {bit, 0}}, {{bit, 1}}, 0, "collect");
  b.set_initial({0, 0});
  b.add_goal({pos, reachable_goal ? 3 : 4});
  b.add_goal({bit, 1});
  b.set_cost_bound(bound);
  return std::move(b).build();
}

// Positions 0 and 1, the robot already at the goal position 1.
CompiledTask at_goal_task() {
  CompiledTask::Builder b;
  const VarId pos = b.add_variable(2, "pos");
  b.add_action({{pos, 0}}, {{pos, 1}}, 1, "0->1");
  b.add_action({{pos, 1}}, {{pos, 0}}, 1, "1->0");
  b.set_initial({1});
  b.add_goal({pos, 1});
  return std::move(b).build();
}

struct EngineConfig {
  Algorithm algorithm;
  HeuristicKind heuristic;
  bool optimal;
};

std::string config_name(const ::testing::TestParamInfo<EngineConfig>& info) {
  return std::string(to_string(info.param.algorithm)) + "_" +
         std::string(to_string(info.param.heuristic));
}

class SearchEngineContract : public ::testing::TestWithParam<EngineConfig> {
 protected:
  SearchResult run(const CompiledTask& task, const StopCondition& stop = StopCondition()) {
    heuristic_ = make_heuristic(GetParam().heuristic, task);
    engine_ = make_engine(GetParam().algorithm, task, *heuristic_, 2.0);
    return engine_->search(stop);
  }
  // Replays the plan and returns its cost; fails the test if it is not a plan.
  domain::Cost replay(const CompiledTask& task, const SearchResult& r) {
    std::vector<std::int32_t> state(task.initial_state().begin(), task.initial_state().end());
    domain::Cost cost = 0;
    for (domain::ActionId a : r.plan) {
      EXPECT_TRUE(task.is_applicable(a, state)) << task.action_name(a);
      task.apply(a, state);
      cost += task.cost(a);
    }
    EXPECT_TRUE(task.is_goal(state));
    return cost;
  }
  std::unique_ptr<Heuristic> heuristic_;
  std::unique_ptr<SearchEngine> engine_;
};

TEST_P(SearchEngineContract, FindsAPlanThatReachesTheGoal) {
  const CompiledTask task = collect_task();
  SearchResult r = run(task);
  ASSERT_EQ(r.status, SearchStatus::kSolved);
  EXPECT_EQ(replay(task, r), r.cost);
  if (GetParam().optimal) {
    EXPECT_EQ(r.cost, 13);
  }
  EXPECT_GT(r.statistics.expanded, 0U);
  EXPECT_GE(r.statistics.generated, r.statistics.expanded);
  EXPECT_GT(r.statistics.peak_memory_bytes, 0U);
}

TEST_P(SearchEngineContract, ReportsUnsolvableWhenTheGoalIsUnreachable) {
  EXPECT_EQ(run(collect_task(domain::kInfiniteCost, false)).status, SearchStatus::kUnsolvable);
}

TEST_P(SearchEngineContract, NeverReturnsAPlanAboveTheCostBound) {
  const CompiledTask tight = collect_task(12);
  EXPECT_EQ(run(tight).status, SearchStatus::kUnsolvable) << "the cheapest plan costs 13";
  const CompiledTask exact = collect_task(13);
  SearchResult r = run(exact);
  ASSERT_EQ(r.status, SearchStatus::kSolved);
  EXPECT_LE(replay(exact, r), 13);
}

TEST_P(SearchEngineContract, StopsAtTheExpansionLimit) {
  SearchResult r = run(collect_task(), StopCondition().with_max_expansions(1));
  EXPECT_EQ(r.status, SearchStatus::kExpansionLimit);
  EXPECT_TRUE(r.plan.empty());
}

TEST_P(SearchEngineContract, ReturnsCancelledWhenStopConditionFires) {
  std::atomic<bool> cancel{true};
  EXPECT_EQ(run(collect_task(), StopCondition().with_cancel(cancel)).status,
            SearchStatus::kCancelled);
}

TEST_P(SearchEngineContract, StopsAtTheTimeLimitOfTheInjectedClock) {
  ManualClock clock;
  EXPECT_EQ(run(collect_task(), StopCondition::after_seconds(clock, 0)).status,
            SearchStatus::kTimeLimit);
}

// A heuristic that sets the cancel flag on its n-th evaluation (a cancel arriving from another
// thread in the middle of an expansion).
class CancellingHeuristic final : public Heuristic {
 public:
  CancellingHeuristic(std::unique_ptr<Heuristic> inner, std::atomic<bool>& cancel, int at)
      : inner_(std::move(inner)), cancel_(cancel), at_(at) {}
  Cost evaluate(std::span<const std::int32_t> state, std::vector<ActionId>* preferred) override {
    if (++evaluations_ == at_) cancel_ = true;
    return inner_->evaluate(state, preferred);
  }
  bool admissible() const override { return inner_->admissible(); }
  std::string_view name() const override { return inner_->name(); }
  int evaluations() const { return evaluations_; }

 private:
  std::unique_ptr<Heuristic> inner_;
  std::atomic<bool>& cancel_;
  int at_;
  int evaluations_ = 0;
};

// Issue 14: the initial state of collect_task() has two successors; a cancel during the first
// one's evaluation stops the search before the second is evaluated.
TEST_P(SearchEngineContract, StopsWithinAnExpansionWhenCancelledBetweenEvaluations) {
  const CompiledTask task = collect_task();
  std::atomic<bool> cancel{false};
  CancellingHeuristic h(make_heuristic(GetParam().heuristic, task), cancel, 2);
  auto engine = make_engine(GetParam().algorithm, task, h, 2.0);
  StopCondition stop;
  stop.with_cancel(cancel);
  EXPECT_EQ(engine->search(stop).status, SearchStatus::kCancelled);
  EXPECT_EQ(h.evaluations(), 2);
}

// Issue 14: a result that the initial state decides (a goal, a dead end) is the answer even when
// the stop fires as initialize() finishes it: here the initial state's evaluation sets the cancel
// flag (and completes). The stop used to replace the result.
TEST_P(SearchEngineContract, AStopAsTheInitialStateDecidesTheSearchLeavesItsResult) {
  const CompiledTask at_goal = at_goal_task();
  const CompiledTask dead_end = collect_task(domain::kInfiniteCost, false);
  for (const CompiledTask* task : {&at_goal, &dead_end}) {
    const bool goal = task == &at_goal;
    if (!goal &&
        make_heuristic(GetParam().heuristic, *task)->evaluate(task->initial_state(), nullptr) !=
            Heuristic::kDeadEnd) {
      continue;  // a heuristic that does not see the dead end (blind)
    }
    std::atomic<bool> cancel{false};
    CancellingHeuristic h(make_heuristic(GetParam().heuristic, *task), cancel, 1);
    auto engine = make_engine(GetParam().algorithm, *task, h, 2.0);
    StopCondition stop;
    stop.with_cancel(cancel);
    const SearchResult r = engine->search(stop);
    if (goal) {
      EXPECT_EQ(r.status, SearchStatus::kSolved);
      EXPECT_TRUE(r.plan.empty());
      EXPECT_EQ(r.cost, 0);
      EXPECT_EQ(r.statistics.expanded, 0U);
    } else {
      EXPECT_EQ(h.evaluations(), 1);
      EXPECT_TRUE(cancel);
      EXPECT_EQ(r.status, SearchStatus::kUnsolvable);
    }
  }
}

TEST_P(SearchEngineContract, IsDeterministic) {
  const CompiledTask task = collect_task();
  SearchResult a = run(task);
  SearchResult b = run(task);
  EXPECT_EQ(a.plan, b.plan);
  EXPECT_EQ(a.statistics.expanded, b.statistics.expanded);
}

INSTANTIATE_TEST_SUITE_P(
    EveryEngine, SearchEngineContract,
    ::testing::Values(EngineConfig{Algorithm::kEhc, HeuristicKind::kFf, false},
                      EngineConfig{Algorithm::kGbfs, HeuristicKind::kFf, false},
                      EngineConfig{Algorithm::kGbfs, HeuristicKind::kAdd, false},
                      EngineConfig{Algorithm::kWeightedAstar, HeuristicKind::kFf, false},
                      EngineConfig{Algorithm::kAstar, HeuristicKind::kMax, true},
                      EngineConfig{Algorithm::kAstar, HeuristicKind::kBlind, true}),
    config_name);

TEST(Heuristics, EstimateTheCollectTaskAsTheRelaxationSays) {
  const CompiledTask task = collect_task();
  std::vector<ActionId> preferred;
  // h_max: the dearer goal fact; reaching bit=1 needs position 1, 3 away (0->2->3->1).
  EXPECT_EQ(make_heuristic(HeuristicKind::kMax, task)->evaluate(task.initial_state(), nullptr), 3);
  // h_add: pos=3 costs 2, bit=1 costs 3: 5.
  EXPECT_EQ(make_heuristic(HeuristicKind::kAdd, task)->evaluate(task.initial_state(), nullptr), 5);
  // FF: relaxed plan {0->2, 2->3, 3->1, collect}: 3 + 4 actions x 1 ms.
  auto ff = make_heuristic(HeuristicKind::kFf, task);
  EXPECT_EQ(ff->evaluate(task.initial_state(), &preferred), 7);
  ASSERT_EQ(preferred.size(), 1U);
  EXPECT_EQ(task.action_name(preferred[0]), "0->2") << "the helpful action";
  EXPECT_EQ(make_heuristic(HeuristicKind::kBlind, task)->evaluate(task.initial_state(), nullptr),
            0);
}

TEST(Heuristics, ReportADeadEndWhenTheRelaxationCannotReachTheGoal) {
  const CompiledTask task = collect_task(domain::kInfiniteCost, false);
  for (HeuristicKind k : {HeuristicKind::kFf, HeuristicKind::kAdd, HeuristicKind::kMax}) {
    EXPECT_EQ(make_heuristic(k, task)->evaluate(task.initial_state(), nullptr), Heuristic::kDeadEnd)
        << to_string(k);
  }
}

}  // namespace
}  // namespace sewerplan::search
