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
#include "support/instances.h"

namespace sewerplan::search {
namespace {

using domain::Cost;
using domain::MissionSpread;
using domain::detail::Node;
using domain::detail::PositionGraph;

struct Csr {
  std::vector<std::uint32_t> begin;
  std::vector<Node> to;
  std::vector<Cost> cost;
};

Csr to_csr(const PositionGraph& graph) {
  Csr g;
  g.begin.reserve(graph.size() + 1);
  for (Node n = 0; n < graph.size(); ++n) {
    g.begin.push_back(static_cast<std::uint32_t>(g.to.size()));
    graph.for_each_successor(n, [&](Node to, Cost c) {
      g.to.push_back(to);
      g.cost.push_back(c);
    });
  }
  g.begin.push_back(static_cast<std::uint32_t>(g.to.size()));
  return g;
}

// Plain Dijkstra from `source`; with `stop_after` > 0 it stops once that many marked nodes (and
// an exit, with `exits`) are settled. Returns the nodes settled.
std::size_t dijkstra(const Csr& g, Node source, std::vector<Cost>& dist,
                     const std::vector<bool>& marked, std::size_t stop_after,
                     const std::vector<bool>& exits) {
  std::fill(dist.begin(), dist.end(), domain::kInfiniteCost);
  using Entry = std::pair<Cost, Node>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  dist[source] = 0;
  open.emplace(0, source);
  std::size_t settled = 0, found = 0;
  bool exit_found = false;
  while (!open.empty()) {
    const auto [d, n] = open.top();
    open.pop();
    if (d != dist[n]) continue;
    ++settled;
    if (stop_after > 0) {
      found += marked[n] ? 1U : 0U;
      exit_found = exit_found || exits[n];
      if (found >= stop_after && exit_found) break;
    }
    for (std::uint32_t e = g.begin[n]; e < g.begin[n + 1]; ++e) {
      const Cost nd = d + g.cost[e];
      if (nd < dist[g.to[e]]) {
        dist[g.to[e]] = nd;
        open.emplace(nd, g.to[e]);
      }
    }
  }
  return settled;
}

// The thread's CPU time in ms: on a machine shared with other work, wall time counts their time
// too, and the plan and the baseline, measured one after the other, would be stretched unevenly.
double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

void BM_PlanVsDijkstra(benchmark::State& state) {
  const auto spread = static_cast<MissionSpread>(state.range(2));
  const bench::Instance& instance = bench::spread_instance(
      static_cast<std::size_t>(state.range(0)), static_cast<std::size_t>(state.range(1)), spread);
  const auto progress = domain::initial_progress(instance.mission, instance.map);
  PositionGraph graph(instance.map, instance.mission);
  const Csr csr = to_csr(graph);
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
    for (Node s : sources) settled += dijkstra(csr, s, dist, marked, sources.size() - 1, exits);
    dijkstra_ms += cpu_ms() - t;
    t = cpu_ms();
    for (Node s : sources) dijkstra(csr, s, dist, marked, 0, exits);
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
