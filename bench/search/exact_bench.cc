// SPDX-License-Identifier: MIT
// Issue 16: the exact tour search's speed, and the default planner's gap to the proven optimum.
//
// BM_ExactGap plans each instance of a grid (meshed networks, uniform and clustered missions,
// three seeds each) with the default planner and with `exact`, both with goal selection, and
// reports `gap_mean_pct` and `gap_max_pct` (the default's cost over the optimum, on instances where
// both do the same number of tasks), `fewer_tasks` (instances where the default does fewer tasks
// than the optimum), `exact_ms_max` (the slowest exact run) and `default_ms_mean`.
// Arguments: manholes, tasks. Baseline: BM_ExactVsAstar, A* with h_max on the same task.
#include <algorithm>
#include <chrono>

#include <benchmark/benchmark.h>

#include "sewerplan/domain/mission_generator.h"
#include "sewerplan/search/planner.h"

#include "support/instances.h"

namespace sewerplan::search {
namespace {

double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

struct Instance {
  SewerMap map;
  Mission mission;
};

std::optional<Instance> make(std::size_t manholes, std::size_t tasks, std::uint64_t seed,
                             domain::MissionSpread spread) {
  auto map = generate_network({.manholes = manholes, .seed = seed, .topology = Topology::kMeshed});
  if (!map.has_value()) return std::nullopt;
  auto mission = domain::generate_mission(*map, {.tasks = tasks, .seed = seed, .spread = spread});
  if (!mission.has_value()) return std::nullopt;
  return Instance{std::move(*map), std::move(*mission)};
}

void BM_ExactGap(benchmark::State& state) {
  const auto manholes = static_cast<std::size_t>(state.range(0));
  const auto tasks = static_cast<std::size_t>(state.range(1));
  std::vector<Instance> grid;
  for (auto spread : {domain::MissionSpread::kUniform, domain::MissionSpread::kClustered}) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      if (auto i = make(manholes, tasks, seed, spread)) grid.push_back(std::move(*i));
    }
  }
  double gap_sum = 0, gap_max = 0, exact_max_ms = 0, default_ms = 0;
  std::size_t compared = 0, fewer = 0, proven = 0, runs = 0;
  for (auto _ : state) {
    for (const Instance& i : grid) {
      const auto progress = domain::initial_progress(i.mission, i.map);
      auto t = std::chrono::steady_clock::now();
      auto ours = plan_mission(i.map, i.mission, progress, {.select_goals = true});
      default_ms += ms_since(t);
      ++runs;
      t = std::chrono::steady_clock::now();
      auto best =
          plan_mission(i.map, i.mission, progress,
                       {.algorithm = Algorithm::kExact, .time_limit_s = 60, .select_goals = true});
      exact_max_ms = std::max(exact_max_ms, ms_since(t));
      if (!ours.has_value() || !best.has_value() || !best->optimal) continue;
      ++proven;
      if (ours->dropped.size() > best->dropped.size()) {
        ++fewer;
        continue;
      }
      const double gap = 100.0 * (ours->cost_s - best->cost_s) / best->cost_s;
      gap_sum += gap;
      gap_max = std::max(gap_max, gap);
      ++compared;
    }
  }
  state.counters["instances"] = static_cast<double>(grid.size());
  state.counters["proven"] = static_cast<double>(proven) / static_cast<double>(state.iterations());
  state.counters["gap_mean_pct"] = compared > 0 ? gap_sum / static_cast<double>(compared) : 0;
  state.counters["gap_max_pct"] = gap_max;
  state.counters["fewer_tasks"] = static_cast<double>(fewer);
  state.counters["exact_ms_max"] = exact_max_ms;
  state.counters["default_ms_mean"] = runs > 0 ? default_ms / static_cast<double>(runs) : 0;
}
BENCHMARK(BM_ExactGap)
    ->ArgNames({"manholes", "tasks"})
    ->ArgsProduct({{100, 1000, 10000}, {5, 10, 15}})
    ->Args({100000, 10})
    ->Args({100000, 15})
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// The baseline: A* with h_max proving the same optimum (10 tasks and fewer; beyond, it takes
// minutes).
void BM_ExactVsAstar(benchmark::State& state) {
  const bench::Instance& i = bench::spread_instance(1000, static_cast<std::size_t>(state.range(1)),
                                                    domain::MissionSpread::kUniform);
  const auto algorithm = static_cast<Algorithm>(state.range(0));
  const auto progress = domain::initial_progress(i.mission, i.map);
  for (auto _ : state) {
    auto outcome = plan_mission(i.map, i.mission, progress,
                                {.algorithm = algorithm, .time_limit_s = 60, .select_goals = true});
    if (!outcome.has_value()) {
      state.SkipWithError(outcome.error().message.c_str());
      return;
    }
    state.counters["cost_s"] = outcome->cost_s;
  }
}
BENCHMARK(BM_ExactVsAstar)
    ->ArgNames({"algorithm", "tasks"})
    ->ArgsProduct({{static_cast<int>(Algorithm::kExact), static_cast<int>(Algorithm::kAstar)},
                   {5, 8}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewerplan::search
