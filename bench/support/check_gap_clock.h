// SPDX-License-Identifier: MIT
// CheckGapClock: a Clock for a StopCondition that records how much work an algorithm does between
// two checks of its stop condition: the bound on how late a cancel from another thread is seen.
//
// A StopCondition with a clock reads it at every check (after the cancel flag), so the gaps
// between reads are the gaps between checks. It reads the calling thread's CPU time, not the wall
// time: on a loaded machine a wall-clock cancel latency is mostly the wait for a time slice
// (docs/benchmarks.md), while the CPU time between checks is the algorithm's own part, which a
// free core would add to the cancel latency.
//
//   CheckGapClock clock;
//   clock.now_s();                                  // the call's start
//   plan_mission(map, mission, progress, {.time_limit_s = 1e9, .clock = &clock});
//   clock.now_s();                                  // its end: the gap after the last check
//   clock.max_gap_s();
#pragma once

#include <algorithm>
#include <vector>

#include <benchmark/benchmark.h>

#include "sewerplan/core/clock.h"

#include <time.h>

namespace sewerplan::bench {

class CheckGapClock final : public Clock {
 public:
  double now_s() const override {
    const double t = thread_cpu_s();
    if (last_s_ < 0) {
      last_s_ = t;
      return t;
    }
    gaps_s_.push_back(t - last_s_);
    // The next gap starts after this bookkeeping: gaps_s_ doubling (at 2^k checks: 1.1, 2.9 and
    // 3.1 ms at 32,770 and 65,538 in traced GBFS runs) is the clock's work, not the algorithm's.
    last_s_ = thread_cpu_s();
    return t;
  }
  std::size_t checks() const { return gaps_s_.size(); }
  double max_gap_s() const {
    return gaps_s_.empty() ? 0 : *std::max_element(gaps_s_.begin(), gaps_s_.end());
  }
  // The p-quantile of the gaps (p in [0, 1]).
  double gap_quantile_s(double p) const {
    if (gaps_s_.empty()) return 0;
    std::vector<double> sorted = gaps_s_;
    std::sort(sorted.begin(), sorted.end());
    const auto i = static_cast<std::size_t>(p * static_cast<double>(sorted.size() - 1) + 0.5);
    return sorted[std::min(i, sorted.size() - 1)];
  }

 private:
  static double thread_cpu_s() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
  }

  mutable std::vector<double> gaps_s_;
  mutable double last_s_ = -1;
};

// The worst gaps over a benchmark's iterations, written as its counters: checks, and the p50, p99
// and largest gap in microseconds.
struct GapCounters {
  double max_s = 0;
  double p99_s = 0;
  double p50_s = 0;
  std::size_t checks = 0;

  void add(const CheckGapClock& clock) {
    max_s = std::max(max_s, clock.max_gap_s());
    p99_s = std::max(p99_s, clock.gap_quantile_s(0.99));
    p50_s = std::max(p50_s, clock.gap_quantile_s(0.5));
    checks = std::max(checks, clock.checks());
  }
  void write(benchmark::State& state) const {
    state.counters["checks"] = static_cast<double>(checks);
    state.counters["p50_gap_us"] = p50_s * 1e6;
    state.counters["p99_gap_us"] = p99_s * 1e6;
    state.counters["max_gap_us"] = max_s * 1e6;
  }
};

}  // namespace sewerplan::bench
