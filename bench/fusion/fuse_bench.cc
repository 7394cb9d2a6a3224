// SPDX-License-Identifier: MIT
// Plan fusion speed: fusing the paper's plan, and a long planned route on generated networks, and
// expanding a fused plan into jobs.
//
// Baseline: validate_plan, the replay alone, which fusion runs step by step; the difference is
// the cost of resolving the parameters. Plans come from the planner once per instance (the
// instance cache of bench/support/instances.h), outside the timed loop.
#include <cstddef>
#include <map>
#include <utility>

#include <benchmark/benchmark.h>

#include "sewerplan/domain/validator.h"
#include "sewerplan/fusion/fuse.h"
#include "sewerplan/fusion/jobs.h"
#include "sewerplan/search/planner.h"

#include "support/instances.h"

namespace sewerplan::fusion {
namespace {

using bench::Instance;

struct PlannedInstance {
  const Instance* instance = nullptr;
  domain::Plan plan;
};

// The planner's plan for the paper's mission on the AIS test environment (manholes 0), or for a
// `tasks`-task mission on a generated network of `manholes`. An empty plan if planning fails.
const PlannedInstance& planned(std::size_t manholes, std::size_t tasks) {
  static std::map<std::pair<std::size_t, std::size_t>, PlannedInstance> cache;
  const auto key = std::make_pair(manholes, tasks);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  PlannedInstance p;
  p.instance = manholes == 0 ? &bench::ais_instance() : &bench::generated_instance(manholes, tasks);
  const Instance& i = *p.instance;
  auto outcome =
      search::plan_mission(i.map, i.mission, domain::initial_progress(i.mission, i.map), {});
  if (outcome.has_value()) p.plan = std::move(outcome->plan);
  return cache.emplace(key, std::move(p)).first->second;
}

void set_counters(benchmark::State& state, const PlannedInstance& p) {
  state.counters["steps"] = static_cast<double>(p.plan.steps.size());
  state.counters["steps_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * static_cast<double>(p.plan.steps.size()),
      benchmark::Counter::kIsRate);
}

// Arguments: manholes (0: the AIS test environment), tasks.
void BM_FusePlan(benchmark::State& state) {
  const PlannedInstance& p =
      planned(static_cast<std::size_t>(state.range(0)), static_cast<std::size_t>(state.range(1)));
  const Instance& i = *p.instance;
  const auto start = domain::initial_progress(i.mission, i.map);
  for (auto _ : state) {
    Result<FusedPlan> fused = fuse(p.plan, i.map, i.mission, start);
    if (!fused.has_value()) {
      state.SkipWithError(fused.error().message.c_str());
      return;
    }
    benchmark::DoNotOptimize(fused->actions.data());
  }
  set_counters(state, p);
}

// The naive baseline: the validator's replay of the same plan, without resolving anything.
void BM_ValidatePlanBaseline(benchmark::State& state) {
  const PlannedInstance& p =
      planned(static_cast<std::size_t>(state.range(0)), static_cast<std::size_t>(state.range(1)));
  const Instance& i = *p.instance;
  const auto start = domain::initial_progress(i.mission, i.map);
  for (auto _ : state) {
    domain::ValidationReport report = domain::validate_plan(p.plan, i.map, i.mission, start);
    benchmark::DoNotOptimize(report.total_cost_s);
  }
  set_counters(state, p);
}

void BM_ExpandPlan(benchmark::State& state) {
  const PlannedInstance& p =
      planned(static_cast<std::size_t>(state.range(0)), static_cast<std::size_t>(state.range(1)));
  const Instance& i = *p.instance;
  Result<FusedPlan> fused =
      fuse(p.plan, i.map, i.mission, domain::initial_progress(i.mission, i.map));
  if (!fused.has_value()) {
    state.SkipWithError(fused.error().message.c_str());
    return;
  }
  for (auto _ : state) {
    auto jobs = expand_plan(*fused, i.mission.profile);
    benchmark::DoNotOptimize(jobs.data());
  }
  set_counters(state, p);
}

BENCHMARK(BM_FusePlan)
    ->ArgNames({"manholes", "tasks"})
    ->Args({0, 0})
    ->Args({10000, 20})
    ->Args({100000, 20})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ValidatePlanBaseline)
    ->ArgNames({"manholes", "tasks"})
    ->Args({0, 0})
    ->Args({10000, 20})
    ->Args({100000, 20})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ExpandPlan)
    ->ArgNames({"manholes", "tasks"})
    ->Args({0, 0})
    ->Args({100000, 20})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace sewerplan::fusion
