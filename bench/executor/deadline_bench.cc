// SPDX-License-Identifier: MIT
// Deadline overshoot of the anytime Replanner (issue 14): a replan with a tight time limit
// (ReplannerOptions::planner.time_limit_s) on generated meshed networks, the first plan of a
// 20-task mission. Each iteration is one plan() on a fresh Replanner; the counters give how far
// past its limit the answer came (p50, p99, p99.9 in ms), how many answers were degraded (the
// safe one, the nearest exit) and how many called the beacon (must be 0: a limit never does).
// The baseline is the same replan without a limit.
//
//   build/release/bench/sewerplan_executor_bench --benchmark_filter=Deadline
#include <algorithm>
#include <vector>

#include <benchmark/benchmark.h>

#include "sewerplan/core/clock.h"
#include "sewerplan/executor/replanner.h"

#include "support/instances.h"

namespace sewerplan::bench {
namespace {

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5);
  return v[std::min(i, v.size() - 1)];
}

// Arguments: manholes, the limit in microseconds (0: none, the baseline), the algorithm (0: auto,
// whose tour search ignores the limit until issue 16's change; 1: greedy best-first, which asks
// its stop condition at every expansion).
void BM_ReplanDeadline(benchmark::State& state) {
  const Instance& instance = generated_instance(static_cast<std::size_t>(state.range(0)), 20);
  const double limit_s = static_cast<double>(state.range(1)) * 1e-6;
  const SteadyClock clock;
  std::vector<double> overshoot_ms;
  std::size_t degraded = 0;
  std::size_t beacons = 0;
  for (auto _ : state) {
    state.PauseTiming();
    executor::Replanner replanner(
        instance.map, instance.mission,
        {.planner = {.algorithm =
                         state.range(2) == 0 ? search::Algorithm::kAuto : search::Algorithm::kGbfs,
                     .time_limit_s = limit_s,
                     .improvement_expansions = 0},
         .clock = &clock});
    state.ResumeTiming();
    const double start_s = clock.now_s();
    const executor::PlanResponse r = replanner.plan();
    overshoot_ms.push_back(std::max(0.0, clock.now_s() - start_s - limit_s) * 1000);
    degraded += r.decision == executor::PlanResponse::Decision::kDegraded ? 1U : 0U;
    beacons += executor::calls_beacon(r.decision) ? 1U : 0U;
    benchmark::DoNotOptimize(r);
  }
  state.counters["overshoot_p50_ms"] = percentile(overshoot_ms, 0.5);
  state.counters["overshoot_p99_ms"] = percentile(overshoot_ms, 0.99);
  state.counters["overshoot_p999_ms"] = percentile(overshoot_ms, 0.999);
  state.counters["degraded"] = static_cast<double>(degraded);
  state.counters["beacons"] = static_cast<double>(beacons);
}
BENCHMARK(BM_ReplanDeadline)
    ->ArgNames({"manholes", "limit_us", "gbfs"})
    ->Args({1000, 0, 0})
    ->Args({1000, 1, 0})
    ->Args({1000, 1, 1})
    ->Args({1000, 1000, 1})
    ->Args({10000, 1, 1})
    ->Args({100000, 0, 0})
    ->Args({100000, 1, 0})
    ->Args({100000, 1, 1})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewerplan::bench
