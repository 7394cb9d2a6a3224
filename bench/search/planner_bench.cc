// SPDX-License-Identifier: MIT
// Planning speed: first plan on the paper's mission and on generated networks, heuristic
// evaluation rate, and the search's memory per state.
//
// Issue #3's figures: first plan on the AIS test environment (goal: under 100 microseconds) and
// on 100,000 manholes with 20 tasks (goal: under 50 ms), both compile and search, map loading
// excluded; heuristic evaluations per second; bytes per stored state. Baselines: uniform-cost
// search (A* with the blind heuristic) for planning, the blind heuristic for evaluation.
#include <cstdint>
#include <map>
#include <tuple>

#include <benchmark/benchmark.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"
#include "sewerplan/search/best_first_search.h"
#include "sewerplan/search/planner.h"

#include "support/instances.h"

namespace sewerplan::search {
namespace {

using bench::ais_instance;
using bench::generated_instance;
using bench::Instance;

void plan_once(benchmark::State& state, const Instance& instance, Algorithm algorithm,
               std::optional<HeuristicKind> heuristic = std::nullopt,
               std::uint64_t improvement = PlannerOptions{}.improvement_expansions,
               bool adaptive = true) {
  const auto progress = domain::initial_progress(instance.mission, instance.map);
  PlanOutcome last;
  for (auto _ : state) {
    auto outcome = plan_mission(instance.map, instance.mission, progress,
                                {.algorithm = algorithm,
                                 .heuristic = heuristic,
                                 .improvement_expansions = improvement,
                                 .adaptive_improvement = adaptive});
    if (!outcome.has_value()) {
      state.SkipWithError(outcome.error().message.c_str());
      return;
    }
    last = std::move(*outcome);
  }
  state.counters["cost_s"] = last.cost_s;
  state.counters["steps"] = static_cast<double>(last.plan.steps.size());
  state.counters["expanded"] = static_cast<double>(last.search.expanded);
  state.counters["keys"] = static_cast<double>(last.compile.keys);
  state.counters["compile_us"] = last.compile.time_s * 1e6;
}

void BM_PlanAisAuto(benchmark::State& state) { plan_once(state, ais_instance(), Algorithm::kAuto); }
void BM_PlanAisEhc(benchmark::State& state) { plan_once(state, ais_instance(), Algorithm::kEhc); }
void BM_PlanAisUniformCost(benchmark::State& state) {
  plan_once(state, ais_instance(), Algorithm::kAstar, HeuristicKind::kBlind);
}
BENCHMARK(BM_PlanAisAuto)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PlanAisEhc)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PlanAisUniformCost)->Unit(benchmark::kMicrosecond);

// Arguments: manholes, tasks, algorithm (Algorithm's value: 0 auto, 1 ehc, 2 gbfs, 3 wastar,
// 4 astar), improvement expansions (0: the first plan only).
void BM_PlanGenerated(benchmark::State& state) {
  const Instance& instance = generated_instance(static_cast<std::size_t>(state.range(0)),
                                                static_cast<std::size_t>(state.range(1)));
  plan_once(state, instance, static_cast<Algorithm>(state.range(2)), std::nullopt,
            static_cast<std::uint64_t>(state.range(3)));
}
BENCHMARK(BM_PlanGenerated)
    ->ArgNames({"manholes", "tasks", "algorithm", "improve"})
    ->Args({1000, 3, 0, 10000})
    ->Args({10000, 10, 0, 10000})
    ->Args({100000, 3, 0, 10000})
    ->Args({100000, 10, 0, 10000})
    ->Args({100000, 20, 0, 0})
    ->Args({100000, 20, 0, 10000})
    ->Args({100000, 20, 1, 0})
    ->Args({100000, 20, 2, 0})
    ->Unit(benchmark::kMillisecond);

// Issue 16's quality check: the same near-exit instances with the fixed budget of 10,000
// expansions that was the default before (no adaptive budget, no exact tour search): the default
// planner's cost_s must not exceed this one's.
void BM_PlanGeneratedFixedBudget(benchmark::State& state) {
  const Instance& instance = generated_instance(static_cast<std::size_t>(state.range(0)),
                                                static_cast<std::size_t>(state.range(1)));
  plan_once(state, instance, Algorithm::kAuto, std::nullopt, 10'000, false);
}
BENCHMARK(BM_PlanGeneratedFixedBudget)
    ->ArgNames({"manholes", "tasks"})
    ->Args({1000, 3})
    ->Args({10000, 10})
    ->Args({100000, 3})
    ->Args({100000, 10})
    ->Args({100000, 20})
    ->Unit(benchmark::kMillisecond);

// Every algorithm on every size: the first plan only, 10 tasks (A* only where its exhaustive
// search is affordable).
void BM_PlanPerAlgorithm(benchmark::State& state) {
  const Instance& instance = generated_instance(static_cast<std::size_t>(state.range(0)), 10);
  plan_once(state, instance, static_cast<Algorithm>(state.range(1)), std::nullopt, 0);
}
BENCHMARK(BM_PlanPerAlgorithm)
    ->ArgNames({"manholes", "algorithm"})
    ->ArgsProduct({{1000, 10000, 100000}, {0, 1, 2, 3}})
    ->Args({1000, 4})
    ->Unit(benchmark::kMillisecond);

void evaluate(benchmark::State& state, HeuristicKind kind) {
  const Instance& instance = generated_instance(100000, 20);
  auto compiled = domain::compile_sewer_task(
      instance.map, instance.mission, domain::initial_progress(instance.mission, instance.map));
  auto h = make_heuristic(kind, compiled->task());
  std::vector<ActionId> preferred;
  for (auto _ : state) {
    benchmark::DoNotOptimize(h->evaluate(compiled->task().initial_state(), &preferred));
  }
  state.counters["evaluations_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["facts"] = static_cast<double>(compiled->task().fact_count());
  state.counters["actions"] = static_cast<double>(compiled->task().action_count());
}
void BM_FfHeuristicEvaluate(benchmark::State& state) { evaluate(state, HeuristicKind::kFf); }
void BM_MaxHeuristicEvaluate(benchmark::State& state) { evaluate(state, HeuristicKind::kMax); }
void BM_BlindHeuristicEvaluate(benchmark::State& state) { evaluate(state, HeuristicKind::kBlind); }
BENCHMARK(BM_FfHeuristicEvaluate);
BENCHMARK(BM_MaxHeuristicEvaluate);
BENCHMARK(BM_BlindHeuristicEvaluate);

// Memory per stored state: an A* run that stores many states (10 tasks, blind heuristic).
void BM_AstarBytesPerState(benchmark::State& state) {
  const Instance& instance = generated_instance(10000, 10);
  auto compiled = domain::compile_sewer_task(
      instance.map, instance.mission, domain::initial_progress(instance.mission, instance.map));
  SearchResult last;
  for (auto _ : state) {
    auto h = make_heuristic(HeuristicKind::kBlind, compiled->task());
    BestFirstSearch astar(compiled->task(), *h, BestFirstSearch::astar());
    last = astar.search(StopCondition());
  }
  state.counters["states"] = static_cast<double>(last.statistics.stored);
  state.counters["bytes_per_state"] = static_cast<double>(last.statistics.peak_memory_bytes) /
                                      static_cast<double>(last.statistics.stored);
}
BENCHMARK(BM_AstarBytesPerState)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewerplan::search
