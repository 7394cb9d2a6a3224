// SPDX-License-Identifier: MIT
// Issue 14: a cancel from another thread stops every algorithm within 1 ms.
//
// Each iteration starts the search on a thread of its own, lets it run for 20 ms, sets the cancel
// flag and measures how long the search takes to return (`latency_us`: mean, `max_latency_us`:
// the worst iteration; `cancelled_runs`: the iterations still running at the cancel, the only
// ones counted). The task: a 50-task uniform mission on 10,000 manholes, large enough that no
// engine finishes within the 20 ms; the tour search, which solves that in a few milliseconds, gets
// 200 tasks, and goal selection 100,000 manholes. Argument: 0 EHC, 1 GBFS, 2 weighted A*, 3 A*
// (h_max), 4 the tour search, 5 plan_mission (the whole planner: compile, tour search,
// improvement), 8 goal selection (the compile with select_goals: the route searches, then the
// tasks that cannot be done left out).
//
// BM_StopCheckGap measures what a loaded machine hides (docs/benchmarks.md): the CPU time each
// algorithm spends between two checks of its stop condition (bench/support/check_gap_clock.h),
// which a free core adds to a cancel's latency. Counters: checks, p50, p99 and the largest gap
// (max_gap_us: the acceptance is under 1,000). Each run is cut at 0.5 s of CPU time. Arguments: the
// algorithm as above plus 6 the exact tour search (on 12 tasks), 7 plan_mission with --algorithm
// exact, 9 the tour search on 200 tasks (cut by the stop: the gap from it to the return), and the
// manholes (10,000 and 100,000 for every algorithm).
//
//   build/release/bench/sewerplan_search_bench --benchmark_filter='StopCheckGap|CancelLatency'

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>

#include <benchmark/benchmark.h>

#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"
#include "sewerplan/search/best_first_search.h"
#include "sewerplan/search/enforced_hill_climbing.h"
#include "sewerplan/search/planner.h"
#include "sewerplan/search/tour_search.h"

#include "support/check_gap_clock.h"
#include "support/instances.h"

namespace sewerplan::search {
namespace {

using Clock = std::chrono::steady_clock;

void BM_CancelLatency(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  const bench::Instance& instance = bench::spread_instance(
      which == 8 ? 100000 : 10000, which == 4 ? 200 : 50, domain::MissionSpread::kUniform);
  const auto progress = domain::initial_progress(instance.mission, instance.map);
  auto compiled =
      domain::compile_sewer_task(instance.map, instance.mission, progress, {.select_goals = true});
  if (!compiled.has_value()) {
    state.SkipWithError(compiled.error().message.c_str());
    return;
  }
  const domain::CompiledTask& task = compiled->task();
  double total_us = 0, max_us = 0;
  std::size_t counted = 0;
  for (auto _ : state) {
    std::atomic<bool> cancel{false};
    std::atomic<bool> finished{false};
    Clock::time_point returned;
    std::thread worker([&] {
      StopCondition stop;
      stop.with_cancel(cancel);
      auto h = make_heuristic(which == 3 ? HeuristicKind::kMax : HeuristicKind::kFf, task);
      switch (which) {
        case 0:
          EnforcedHillClimbing(task, *h).search(stop);
          break;
        case 1:
          BestFirstSearch(task, *h, BestFirstSearch::greedy()).search(stop);
          break;
        case 2:
          BestFirstSearch(task, *h, BestFirstSearch::weighted_astar(2)).search(stop);
          break;
        case 3:
          BestFirstSearch(task, *h, BestFirstSearch::astar()).search(stop);
          break;
        case 4:
          tour_search(task, stop);
          break;
        case 8:
          (void)domain::compile_sewer_task(instance.map, instance.mission, progress,
                                           {.select_goals = true, .stop = stop});
          break;
        default:
          (void)plan_mission(instance.map, instance.mission, progress,
                             {.cancel = &cancel, .select_goals = true});
          break;
      }
      returned = Clock::now();
      finished = true;
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const bool was_running = !finished;
    const auto cancelled = Clock::now();
    cancel = true;
    worker.join();
    if (was_running) {
      const double us = std::chrono::duration<double, std::micro>(returned - cancelled).count();
      total_us += us;
      max_us = std::max(max_us, us);
      ++counted;
    }
  }
  state.counters["latency_us"] = counted > 0 ? total_us / static_cast<double>(counted) : 0;
  state.counters["max_latency_us"] = max_us;
  state.counters["cancelled_runs"] = static_cast<double>(counted);
}
BENCHMARK(BM_CancelLatency)
    ->ArgName("algorithm")
    ->DenseRange(0, 5)
    ->Arg(8)
    ->Iterations(10)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_StopCheckGap(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  const bool exact = which == 6 || which == 7;
  const bench::Instance& instance =
      bench::spread_instance(static_cast<std::size_t>(state.range(1)),
                             exact ? 12 : (which == 9 ? 200 : 50), domain::MissionSpread::kUniform);
  const auto progress = domain::initial_progress(instance.mission, instance.map);
  auto compiled =
      domain::compile_sewer_task(instance.map, instance.mission, progress, {.select_goals = true});
  if (!compiled.has_value()) {
    state.SkipWithError(compiled.error().message.c_str());
    return;
  }
  const domain::CompiledTask& task = compiled->task();
  bench::GapCounters gaps;
  for (auto _ : state) {
    const bench::CheckGapClock clock;
    // Each run is cut at 0.5 s of CPU time: the gaps, not the runs, are measured.
    const StopCondition stop = StopCondition::after_seconds(clock, 0.5);
    auto h = make_heuristic(which == 3 ? HeuristicKind::kMax : HeuristicKind::kFf, task);
    switch (which) {
      case 8:
        (void)domain::compile_sewer_task(instance.map, instance.mission, progress,
                                         {.select_goals = true, .stop = stop});
        break;
      case 0:
        EnforcedHillClimbing(task, *h).search(stop, clock);
        break;
      case 1:
        BestFirstSearch(task, *h, BestFirstSearch::greedy()).search(stop, clock);
        break;
      case 2:
        BestFirstSearch(task, *h, BestFirstSearch::weighted_astar(2)).search(stop, clock);
        break;
      case 3:
        BestFirstSearch(task, *h, BestFirstSearch::astar())
            .search(StopCondition(stop).with_max_expansions(200'000), clock);
        break;
      case 4:
      case 9:
        tour_search(task, stop, &clock);
        break;
      case 6:
        exact_tour_search(task, stop, &clock);
        break;
      default:
        (void)plan_mission(instance.map, instance.mission, progress,
                           {.algorithm = which == 7 ? Algorithm::kExact : Algorithm::kAuto,
                            .time_limit_s = 0.5,
                            .clock = &clock,
                            .select_goals = true});
        break;
    }
    clock.now_s();
    gaps.add(clock);
  }
  gaps.write(state);
}
BENCHMARK(BM_StopCheckGap)
    ->ArgNames({"algorithm", "manholes"})
    ->ArgsProduct({{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}, {10000, 100000}})
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewerplan::search
