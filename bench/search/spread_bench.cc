// SPDX-License-Identifier: MIT
// Issue 16: compile + search against the limit any multi-goal planner pays, on missions of every
// shape.
//
// The naive baseline: K + 1 plain Dijkstra searches (a binary heap over a compressed-sparse-row
// copy of the same primitive graph the compiler searches, built outside the timing) from the
// start and from one end of each task's pipe. Two baselines are reported: `dijkstra_full_ms`
// settles the whole graph from every source (the yardstick), `dijkstra_ms` stops each
// search once it has settled every other source and an exit (the distances a planner must know,
// found as cheaply as plain Dijkstra finds them). The figure is `ratio` = plan_ms / dijkstra_ms
// (goal <= 3), and `ratio_full` against the full searches. Times are the thread's CPU time (on a
// shared machine wall time counts other processes, unevenly between the two sides);
// `plan_wall_ms` is the plan's wall time.
//
// Arguments: manholes, tasks, spread (MissionSpread: 0 uniform, 1 clustered, 2 near-exit).
#include <chrono>
#include <cstdint>
#include <ctime>
#include <functional>
#include <queue>
#include <vector>

#include <benchmark/benchmark.h>

#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"
#include "sewerplan/search/planner.h"

#include "position_graph.h"
#include "support/dijkstra_bound.h"
#include "support/instances.h"

namespace sewerplan::search {
namespace {

using domain::Cost;
using domain::MissionSpread;
using domain::detail::Node;
using domain::detail::PositionGraph;

using bench::cpu_ms;

void BM_PlanVsDijkstra(benchmark::State& state) {
  const auto spread = static_cast<MissionSpread>(state.range(2));
  const bench::Instance& instance = bench::spread_instance(
      static_cast<std::size_t>(state.range(0)), static_cast<std::size_t>(state.range(1)), spread);
  const auto progress = domain::initial_progress(instance.mission, instance.map);
  PositionGraph graph(instance.map, instance.mission);
  const bench::Csr csr = bench::to_csr(graph);
  std::vector<Node> sources{graph.in_manhole(std::get<ManholeId>(instance.mission.start))};
  for (const Task& t : instance.mission.tasks) {
    if (const auto* spot = std::get_if<PipeSpot>(&t.place)) {
      sources.push_back(graph.pipe_end(spot->pipe, 0));
    }
  }
  std::vector<bool> marked(graph.size(), false), exits(graph.size(), false);
  // The start ("in manhole") is entered by no move: the early stop waits for the task nodes.
  for (std::size_t i = 1; i < sources.size(); ++i) marked[sources[i]] = true;
  for (ManholeId e : instance.mission.exits) exits[graph.in_manhole(e)] = true;
  std::vector<Cost> dist(graph.size());
  double plan_ms = 0, plan_wall_ms = 0, dijkstra_ms = 0, full_ms = 0;
  std::size_t settled = 0;
  PlanOutcome last;
  for (auto _ : state) {
    const auto wall = std::chrono::steady_clock::now();
    double t = cpu_ms();
    auto outcome = plan_mission(instance.map, instance.mission, progress,
                                {.time_limit_s = 60, .select_goals = true});
    plan_ms += cpu_ms() - t;
    plan_wall_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall).count();
    if (!outcome.has_value()) {
      state.SkipWithError(outcome.error().message.c_str());
      return;
    }
    last = std::move(*outcome);
    t = cpu_ms();
    for (Node s : sources) {
      settled += bench::dijkstra(csr, s, dist, &marked, sources.size() - 1, &exits);
    }
    dijkstra_ms += cpu_ms() - t;
    t = cpu_ms();
    for (Node s : sources) bench::dijkstra(csr, s, dist);
    full_ms += cpu_ms() - t;
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["plan_ms"] = plan_ms / n;
  state.counters["plan_wall_ms"] = plan_wall_ms / n;
  state.counters["dijkstra_ms"] = dijkstra_ms / n;
  state.counters["dijkstra_full_ms"] = full_ms / n;
  state.counters["ratio"] = plan_ms / dijkstra_ms;
  state.counters["ratio_full"] = plan_ms / full_ms;
  state.counters["compile_ms"] = last.compile.time_s * 1e3;
  state.counters["improvements"] = static_cast<double>(last.improvements);
  state.counters["keys"] = static_cast<double>(last.compile.keys);
  state.counters["cost_s"] = last.cost_s;
  state.counters["dropped"] = static_cast<double>(last.dropped.size());
  state.counters["settled_plan"] = static_cast<double>(last.compile.settled_nodes);
  state.counters["settled_dijkstra"] = static_cast<double>(settled) / n;
}
BENCHMARK(BM_PlanVsDijkstra)
    ->ArgNames({"manholes", "tasks", "spread"})
    ->ArgsProduct({{1000, 10000, 100000}, {3, 10, 20, 50}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);

// 1,000,000 manholes: run with --benchmark_filter=BM_PlanVsDijkstraMillion (about a minute).
void BM_PlanVsDijkstraMillion(benchmark::State& state) { BM_PlanVsDijkstra(state); }
BENCHMARK(BM_PlanVsDijkstraMillion)
    ->ArgNames({"manholes", "tasks", "spread"})
    ->ArgsProduct({{1000000}, {3, 10, 20, 50}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace sewerplan::search
