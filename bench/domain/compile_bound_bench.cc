// SPDX-License-Identifier: MIT
// Issue 35: the compile against the K+1 Dijkstra bound, on more than one generator.
//
// For each network (ours, generate_network, at several sizes; the scrambled generator of
// bench/support/scrambled_network.h at the same sizes; the real networks in datasets/), in one
// process: the compile of a mission of K tasks (compile_sewer_task with goal selection, as
// plan_mission calls it), and the naive baseline: K + 1 plain Dijkstra searches, each settling
// the whole graph (a binary heap over a compressed-sparse-row copy of the same primitive graph
// the compiler searches, built outside the timing), from the start and from one end of each
// task's pipe. The figure is `ratio` = compile_ms / dijkstra_ms; `ratio_cached` is the same with
// the compile's per-map core kept between compiles (CompileCache, as the Replanner keeps it).
// With the routing index (CompileCache::RoutingIndex::kAlways): `first_with_index_ms`, a first
// compile that builds it, and `indexed_ms` (`ratio_indexed`), the mission compiled on it with no
// row from the memo (issue 35's "first plan after the index is built"), with the rows it took
// from the index (`indexed_rows`) and the searches it still ran (`indexed_searches`).
// Times are the thread's CPU time (spread_bench.cc says why).
//
// Missions: on ours, generate_mission's uniform spread (MAKRO PLUS, whose battery bounds the
// searches: the tasks within a few kilometres of the start); on the scrambled networks and the
// real ones, the uniform spread with a battery of 1,000,000 Wh, which bounds nothing (the tasks
// over the whole network). The real networks are small (14 to 45 manholes): their rows measure
// the compile's fixed costs, not its searches.
//
// Arguments of BM_CompileVsDijkstra: generator (0 ours, 1 scrambled), manholes, tasks.
// Of BM_CompileVsDijkstraReal: the network (0 AIS test bed and its paper mission, 1 EPA example
// 1, 2 the swmmio state-plane model, 3 Bellinge small, 4 the ISYBAU street of 2017).
//
//   build/release/bench/sewerplan_domain_bench --benchmark_filter=CompileVsDijkstra
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "sewerplan/domain/compile.h"

#include "position_graph.h"
#include "support/dijkstra_bound.h"

namespace sewerplan::domain {
namespace {

using bench::cpu_ms;
using bench::Instance;
using detail::Node;
using detail::PositionGraph;

void measure(benchmark::State& state, const Instance& instance) {
  if (instance.mission.tasks.empty()) {
    state.SkipWithError("no mission fits this network");
    return;
  }
  const MissionProgress progress = initial_progress(instance.mission, instance.map);
  PositionGraph graph(instance.map, instance.mission);
  const std::vector<Node> sources = bench::bound_sources(graph, instance.mission, progress);
  const bench::Csr csr = bench::to_csr(graph);
  std::vector<Cost> dist(graph.size());
  CompileCache cache;
  double compile_ms = 0, cached_ms = 0, dijkstra_ms = 0, built_ms = 0, indexed_ms = 0;
  std::size_t settled = 0;
  CompileStatistics stats;
  CompileStatistics indexed_stats;
  for (auto _ : state) {
    double t = cpu_ms();
    auto task =
        compile_sewer_task(instance.map, instance.mission, progress, {.select_goals = true});
    compile_ms += cpu_ms() - t;
    if (!task.has_value()) {
      state.SkipWithError(task.error().message.c_str());
      return;
    }
    stats = task->statistics();
    (void)compile_sewer_task(instance.map, instance.mission, progress,
                             {.select_goals = true, .cache = &cache});  // warms the cache
    t = cpu_ms();
    auto again = compile_sewer_task(instance.map, instance.mission, progress,
                                    {.select_goals = true, .cache = &cache});
    cached_ms += cpu_ms() - t;
    benchmark::DoNotOptimize(again);
    // Issue 35, the routing index: a cache that builds it on its first compile (of the mission
    // with 1 Wh more used: its memo has rows for smaller bounds only, so that the compile
    // measured takes nothing from it), then the mission compiled on it.
    {
      CompileCache indexed(CompileCache::RoutingIndex::kAlways);
      MissionProgress before = progress;
      before.energy_used_wh += 1;
      t = cpu_ms();
      (void)compile_sewer_task(instance.map, instance.mission, before,
                               {.select_goals = true, .cache = &indexed});
      built_ms += cpu_ms() - t;
      t = cpu_ms();
      auto from_index = compile_sewer_task(instance.map, instance.mission, progress,
                                           {.select_goals = true, .cache = &indexed});
      indexed_ms += cpu_ms() - t;
      if (from_index.has_value()) indexed_stats = from_index->statistics();
    }
    t = cpu_ms();
    settled = 0;
    for (Node s : sources) settled += bench::dijkstra(csr, s, dist);
    dijkstra_ms += cpu_ms() - t;
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["manholes_n"] = static_cast<double>(instance.map.manhole_count());
  state.counters["tasks_n"] = static_cast<double>(instance.mission.tasks.size());
  state.counters["compile_ms"] = compile_ms / n;
  state.counters["compile_cached_ms"] = cached_ms / n;
  state.counters["dijkstra_ms"] = dijkstra_ms / n;
  state.counters["ratio"] = compile_ms / dijkstra_ms;
  state.counters["ratio_cached"] = cached_ms / dijkstra_ms;
  state.counters["first_with_index_ms"] = built_ms / n;
  state.counters["indexed_ms"] = indexed_ms / n;
  state.counters["ratio_indexed"] = indexed_ms / dijkstra_ms;
  state.counters["indexed_rows"] = static_cast<double>(indexed_stats.index_rows);
  state.counters["indexed_searches"] = static_cast<double>(indexed_stats.route_searches);
  state.counters["indexed_settled"] = static_cast<double>(indexed_stats.settled_nodes);
  state.counters["graph_nodes"] = static_cast<double>(graph.size());
  state.counters["keys"] = static_cast<double>(stats.keys);
  state.counters["searches"] = static_cast<double>(stats.route_searches);
  state.counters["settled_compile"] = static_cast<double>(stats.settled_nodes);
  state.counters["settled_dijkstra"] = static_cast<double>(settled);
}

void BM_CompileVsDijkstra(benchmark::State& state) {
  measure(state, bench::bound_instance(static_cast<int>(state.range(0)),
                                       static_cast<std::size_t>(state.range(1)),
                                       static_cast<std::size_t>(state.range(2))));
}
BENCHMARK(BM_CompileVsDijkstra)
    ->ArgNames({"generator", "manholes", "tasks"})
    ->ArgsProduct({{0, 1}, {1000, 10000, 100000}, {20}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

void BM_CompileVsDijkstraReal(benchmark::State& state) {
  measure(state, bench::real_instance(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_CompileVsDijkstraReal)
    ->ArgNames({"network"})
    ->DenseRange(0, bench::kRealNetworks - 1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(20);

}  // namespace
}  // namespace sewerplan::domain
