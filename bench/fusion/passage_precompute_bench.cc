// SPDX-License-Identifier: MIT
// Manhole motion planning speed: precomputing every passage of the AIS test environment and of a
// generated 1,000-manhole network, and planning one right-angle turn.
//
// Baseline: the angle-and-step rules (judge_passage without a table) over the same passages,
// which is what planning costs without motion results. Counters: passages, distinct geometries
// (each planned once), and the share of passages the planner rejects that the rules accept
// (motion_rejects_rules_allow) and the reverse (motion_allows_rules_reject), per passage.
//
// BM_PrecomputeStopCheckGap (issue 14: a cancel within 1 ms): the CPU time between two checks of
// the stop condition during a precompute (bench/support/check_gap_clock.h): before each passage,
// at every RRT iteration, and in the table's assembly. Counters: checks, p50, p99 and the largest
// gap in microseconds.
#include <algorithm>
#include <cstddef>

#include <benchmark/benchmark.h>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/passage_motion.h"
#include "sewerplan/fusion/manhole_turn_planner.h"
#include "sewerplan/fusion/passage_precompute.h"
#include "sewerplan/modules/ompl.h"

#include "support/check_gap_clock.h"
#include "support/instances.h"

namespace sewerplan::fusion {
namespace {

// OMPL's planner as the command gets it: from the OMPL module (sewerplan/modules/ompl.h).
const HeadPathPlanner* ompl() {
  const Result<const HeadPathPlanner*>& planner = modules::ompl_head_path_planner();
  return planner.has_value() ? *planner : nullptr;
}

const SewerMap& map_for(std::int64_t manholes) {
  return manholes == 0 ? bench::ais_instance().map
                       : bench::generated_instance(static_cast<std::size_t>(manholes), 1).map;
}

// Argument: manholes (0: the AIS test environment).
void BM_PassagePrecompute(benchmark::State& state) {
  if (ompl() == nullptr) {
    state.SkipWithError("no motion planning: built without OMPL, or its module does not load");
    return;
  }
  const SewerMap& map = map_for(state.range(0));
  const RobotProfile profile = *builtin_profile("makro-1.1");
  SteadyClock clock;
  PrecomputeStatistics stats;
  for (auto _ : state) {
    Result<PrecomputeResult> r =
        precompute_passage_motion(map, profile, {.head_paths = ompl()}, clock);
    if (!r.has_value()) {
      state.SkipWithError(r.error().message.c_str());
      return;
    }
    stats = r->statistics;
    benchmark::DoNotOptimize(r->table);
  }
  const auto passages = static_cast<double>(stats.passages);
  state.counters["manholes"] = static_cast<double>(map.manhole_count());
  state.counters["passages"] = passages;
  state.counters["geometries"] = static_cast<double>(stats.distinct_geometries);
  state.counters["feasible"] = static_cast<double>(stats.feasible);
  state.counters["rules_allow"] = static_cast<double>(stats.rules_allow);
  state.counters["motion_rejects_rules_allow"] =
      static_cast<double>(stats.rejected_by_motion_rules_allow) / passages;
  state.counters["motion_allows_rules_reject"] =
      static_cast<double>(stats.allowed_by_motion_rules_reject) / passages;
}
BENCHMARK(BM_PassagePrecompute)->Arg(0)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_PrecomputeStopCheckGap(benchmark::State& state) {
  if (ompl() == nullptr) {
    state.SkipWithError("no motion planning: built without OMPL, or its module does not load");
    return;
  }
  const SewerMap& map = map_for(state.range(0));
  const RobotProfile profile = *builtin_profile("makro-1.1");
  SteadyClock steady;
  bench::GapCounters gaps;
  for (auto _ : state) {
    const bench::CheckGapClock clock;
    clock.now_s();
    Result<PrecomputeResult> r = precompute_passage_motion(
        map, profile, {.head_paths = ompl(), .stop = StopCondition::at_deadline(clock, 1e12)},
        steady);
    clock.now_s();
    if (!r.has_value()) {
      state.SkipWithError(r.error().message.c_str());
      return;
    }
    gaps.add(clock);
  }
  gaps.write(state);
}
BENCHMARK(BM_PrecomputeStopCheckGap)
    ->Arg(0)
    ->Arg(1000)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

// The baseline: the rules over every ordered slot pair.
void BM_PassageRules(benchmark::State& state) {
  const SewerMap& map = map_for(state.range(0));
  const RobotProfile profile = *builtin_profile("makro-1.1");
  for (auto _ : state) {
    std::size_t allowed = 0;
    for (ManholeId m : map.manhole_ids()) {
      const auto n = static_cast<std::uint16_t>(map.slots(m).size());
      for (std::uint16_t i = 0; i < n; ++i) {
        for (std::uint16_t j = 0; j < n; ++j) {
          if (i == j) continue;
          allowed += judge_passage(map, profile, nullptr, m, SlotIndex{i}, SlotIndex{j}).allowed;
        }
      }
    }
    benchmark::DoNotOptimize(allowed);
  }
}
BENCHMARK(BM_PassageRules)->Arg(0)->Arg(1000)->Unit(benchmark::kMillisecond);

// One feasible right angle in a 1 m manhole between 0.60 m pipes, and one infeasible U-turn (the
// planner's full iteration budget).
void BM_ManholeTurnPlan(benchmark::State& state) {
  if (ompl() == nullptr) {
    state.SkipWithError("no motion planning: built without OMPL, or its module does not load");
    return;
  }
  const RobotProfile profile = *builtin_profile("makro-1.1");
  const ManholeTurnPlanner planner(ompl(), robot_body(profile), profile);
  const PassageGeometry g{.turn_deg = static_cast<double>(state.range(0))};
  for (auto _ : state) {
    Result<TurnPlan> p = planner.plan(g);
    benchmark::DoNotOptimize(p);
  }
}
BENCHMARK(BM_ManholeTurnPlan)->Arg(90)->Arg(170)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewerplan::fusion
