// SPDX-License-Identifier: MIT
// Cancelling a replan from another thread (issue 14: within 1 ms): a BackgroundReplan of a
// 20-task mission on a generated meshed network is let run for 2 ms, then cancelled; the time
// measured is from cancel() to get() returning. Counters: how many answers were kCancelled (the
// rest had finished first), and the p99 and maximum of the latency in ms. The baseline is the
// same replan let run to its end (BM_ReplanDeadline with limit_us:0 in deadline_bench.cc).
//
//   build/release/bench/sewerplan_executor_bench --benchmark_filter=Cancel
#include <algorithm>
#include <chrono>
#include <thread>
#include <vector>

#include <benchmark/benchmark.h>

#include "sewerplan/executor/background_replan.h"

#include "support/instances.h"

namespace sewerplan::bench {
namespace {

// Arguments: manholes, the algorithm (0: auto, whose compile and tour search do not yet ask the
// stop condition, issue 16; 1: greedy best-first).
void BM_BackgroundReplanCancel(benchmark::State& state) {
  const Instance& instance = generated_instance(static_cast<std::size_t>(state.range(0)), 20);
  std::vector<double> latency_ms;
  std::size_t cancelled = 0;
  for (auto _ : state) {
    executor::Replanner replanner(
        instance.map, instance.mission,
        {.planner = {
             .algorithm = state.range(1) == 0 ? search::Algorithm::kAuto : search::Algorithm::kGbfs,
             .improvement_expansions = 0}});
    executor::BackgroundReplan replan(replanner, std::nullopt);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    const auto start = std::chrono::steady_clock::now();
    replan.cancel();
    const Result<executor::PlanResponse> r = replan.get();
    const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
    state.SetIterationTime(took.count());
    latency_ms.push_back(took.count() * 1000);
    cancelled += r.has_value() ? 0U : 1U;
  }
  std::sort(latency_ms.begin(), latency_ms.end());
  state.counters["cancelled"] = static_cast<double>(cancelled);
  state.counters["p99_ms"] =
      latency_ms[std::min(latency_ms.size() - 1, latency_ms.size() * 99 / 100)];
  state.counters["max_ms"] = latency_ms.back();
}
BENCHMARK(BM_BackgroundReplanCancel)
    ->ArgNames({"manholes", "gbfs"})
    ->Args({10000, 1})
    ->Args({10000, 0})
    ->Args({100000, 1})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewerplan::bench
