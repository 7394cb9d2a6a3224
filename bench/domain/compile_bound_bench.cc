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
#include <ctime>
#include <functional>
#include <map>
#include <queue>
#include <string>
#include <tuple>
#include <vector>

#include <benchmark/benchmark.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"

#include "position_graph.h"
#include "support/instances.h"
#include "support/scrambled_network.h"

namespace sewerplan::domain {
namespace {

using bench::Instance;
using detail::Node;
using detail::PositionGraph;

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

// Plain Dijkstra from `source` over the whole graph; returns the nodes settled.
std::size_t dijkstra(const Csr& g, Node source, std::vector<Cost>& dist) {
  std::fill(dist.begin(), dist.end(), kInfiniteCost);
  using Entry = std::pair<Cost, Node>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  dist[source] = 0;
  open.emplace(0, source);
  std::size_t settled = 0;
  while (!open.empty()) {
    const auto [d, n] = open.top();
    open.pop();
    if (d != dist[n]) continue;
    ++settled;
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

double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

const Instance& generated(int generator, std::size_t manholes, std::size_t tasks) {
  static std::map<std::tuple<int, std::size_t, std::size_t>, Instance> cache;
  const auto key = std::make_tuple(generator, manholes, tasks);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  Instance i;
  if (generator == 0) {
    i.map = *generate_network({.manholes = manholes, .seed = 1, .topology = Topology::kMeshed});
    i.mission =
        *generate_mission(i.map, {.tasks = tasks, .seed = 1, .spread = MissionSpread::kUniform});
  } else {
    i.map = *bench::generate_scrambled_network({.manholes = manholes, .seed = 1});
    i.mission = *bench::scrambled_mission(i.map, tasks, 1);
  }
  return cache.emplace(key, std::move(i)).first->second;
}

// A real network and a mission on it: the paper's on the AIS test bed; else the most tasks, up to
// 20, the uniform spread finds room for, with a battery that bounds nothing.
const Instance& real(int network) {
  static std::map<int, Instance> cache;
  auto it = cache.find(network);
  if (it != cache.end()) return it->second;
  const std::string dir = std::string(SEWERPLAN_SOURCE_DIR) + "/datasets/";
  static const char* const kFiles[] = {"ais-testbed/map.json", "swmm/epa-example1.inp",
                                       "swmm/swmmio-state-plane.inp", "swmm/bellinge-small.inp",
                                       "isybau/street-2017.xml"};
  if (network == 0) return bench::ais_instance();
  Diagnostics d;
  Instance i;
  i.map = *read_map(dir + kFiles[network], d);
  for (std::size_t tasks = 20; tasks > 0; --tasks) {
    auto mission = generate_mission(
        i.map, {.tasks = tasks, .seed = 1, .spread = MissionSpread::kUniform, .battery_wh = 1e6});
    if (mission.has_value()) {
      i.mission = std::move(*mission);
      break;
    }
  }
  return cache.emplace(network, std::move(i)).first->second;
}

void measure(benchmark::State& state, const Instance& instance) {
  if (instance.mission.tasks.empty()) {
    state.SkipWithError("no mission fits this network");
    return;
  }
  const MissionProgress progress = initial_progress(instance.mission, instance.map);
  PositionGraph graph(instance.map, instance.mission);
  // The start first: in a pipe it is a node of its own, which the CSR copy must hold.
  std::vector<Node> sources{graph.node(progress.position)};
  for (const Task& t : instance.mission.tasks) {
    if (const auto* spot = std::get_if<PipeSpot>(&t.place)) {
      sources.push_back(graph.pipe_end(spot->pipe, 0));
    } else {
      sources.push_back(graph.in_manhole(std::get<ManholeId>(t.place)));
    }
  }
  const Csr csr = to_csr(graph);
  std::vector<Cost> dist(graph.size());
  CompileCache cache;
  double compile_ms = 0, cached_ms = 0, dijkstra_ms = 0;
  std::size_t settled = 0;
  CompileStatistics stats;
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
    t = cpu_ms();
    settled = 0;
    for (Node s : sources) settled += dijkstra(csr, s, dist);
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
  state.counters["graph_nodes"] = static_cast<double>(graph.size());
  state.counters["keys"] = static_cast<double>(stats.keys);
  state.counters["searches"] = static_cast<double>(stats.route_searches);
  state.counters["settled_compile"] = static_cast<double>(stats.settled_nodes);
  state.counters["settled_dijkstra"] = static_cast<double>(settled);
}

void BM_CompileVsDijkstra(benchmark::State& state) {
  measure(state,
          generated(static_cast<int>(state.range(0)), static_cast<std::size_t>(state.range(1)),
                    static_cast<std::size_t>(state.range(2))));
}
BENCHMARK(BM_CompileVsDijkstra)
    ->ArgNames({"generator", "manholes", "tasks"})
    ->ArgsProduct({{0, 1}, {1000, 10000, 100000}, {20}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

void BM_CompileVsDijkstraReal(benchmark::State& state) {
  measure(state, real(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_CompileVsDijkstraReal)
    ->ArgNames({"network"})
    ->DenseRange(0, 4)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(20);

}  // namespace
}  // namespace sewerplan::domain
