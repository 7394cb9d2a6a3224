// SPDX-License-Identifier: MIT
// Issue 35: a contraction hierarchy over the position graph (domain/src/contraction_hierarchy.h),
// built and queried, against plain Dijkstra searches over the same graph.
//
// On the issue-35 instances (bench/support/dijkstra_bound.h: ours, generate_network, and the
// scrambled generator, at 1k, 10k and 100k manholes, 20 tasks), in one process and in the
// thread's CPU time:
//   - build_ms: the hierarchy built from the GraphCore's adjacency (the adjacency itself built
//     outside the timing), against dijkstra_ms, one full Dijkstra over the same adjacency (the
//     mean over the K + 1 bound's sources): `build_ratio` (the goal: <= 10);
//   - bytes_per_element: the hierarchy's arrays per manhole + pipe of the map (goal: < 200);
//   - table_ms: the many-to-many table between the compile's keys that are nodes of the map (the
//     start, or the ends of its pipe when it starts inside one; each manhole task's slots; each
//     pipe task's ends), every key to every key, against bound_ms, the K + 1 Dijkstra bound
//     (dijkstra_bound.h, as BM_CompileVsDijkstra): `table_ratio` (the goal for the whole
//     plan: <= 1); p2p_us: one point-to-point distance between keys, the mean;
//   - shortcuts, up_edges, down_edges against moves (the graph's).
// BM_ContractionHierarchyTies counts, for the same keys, the routes (key to key) whose unpacked
// hierarchy path is not the route search's (graph_search.h, the compile's tie rule) though both
// cost the same: what wiring the index into the compile must resolve (docs/benchmarks.md).
//
// Arguments: generator (0 ours, 1 scrambled), manholes, tasks; of BM_ContractionHierarchy also
// keep_ties (ChOptions: 1 keeps every shortest way, for the unique flags).
//
//   build/release/bench/sewerplan_domain_bench --benchmark_filter=ContractionHierarchy
//       --benchmark_counters_tabular=true
#include <algorithm>
#include <span>
#include <vector>

#include <benchmark/benchmark.h>

#include "contraction_hierarchy.h"
#include "graph_search.h"
#include "position_graph.h"
#include "support/dijkstra_bound.h"

namespace sewerplan::domain {
namespace {

using bench::cpu_ms;
using bench::Instance;
using detail::ChQuery;
using detail::ContractionHierarchy;
using detail::Node;
using detail::PositionGraph;

// The compile's keys (compile_routes.cc, collect_keys) that are nodes of the map: a start or a
// task spot inside a pipe is an extra node the hierarchy does not have; the start is replaced by
// its pipe's ends, the spots are left out.
std::vector<Node> map_keys(PositionGraph& graph, const Instance& instance,
                           const MissionProgress& progress) {
  std::vector<Node> keys;
  const Node start = graph.node(progress.position);
  if (graph.is_extra_spot(start)) {
    const PipeId pipe = *graph.pipe_of(start);
    keys.push_back(graph.pipe_end(pipe, 0));
    keys.push_back(graph.pipe_end(pipe, 1));
  } else {
    keys.push_back(start);
  }
  for (const Task& task : instance.mission.tasks) {
    if (const auto* m = std::get_if<ManholeId>(&task.place)) {
      for (std::uint16_t s = 0; s < instance.map.manhole(*m).slot_count; ++s) {
        keys.push_back(graph.at_slot(*m, SlotIndex{s}));
      }
      continue;
    }
    const PipeId pipe = std::get<PipeSpot>(task.place).pipe;
    for (std::size_t e = 0; e < 2; ++e) keys.push_back(graph.pipe_end(pipe, e));
  }
  std::vector<Node> unique;
  for (Node k : keys) {
    if (std::find(unique.begin(), unique.end(), k) == unique.end()) unique.push_back(k);
  }
  return unique;
}

bench::Csr adjacency_of(const detail::GraphCore& core) {
  return {core.adjacency_begin, core.adjacency_to, core.adjacency_cost};
}

void BM_ContractionHierarchy(benchmark::State& state) {
  const Instance& instance = bench::bound_instance(static_cast<int>(state.range(0)),
                                                   static_cast<std::size_t>(state.range(1)),
                                                   static_cast<std::size_t>(state.range(2)));
  const MissionProgress progress = initial_progress(instance.mission, instance.map);
  PositionGraph graph(instance.map, instance.mission);
  const std::vector<Node> sources = bench::bound_sources(graph, instance.mission, progress);
  const bench::Csr csr = bench::to_csr(graph);
  const std::vector<Node> keys = map_keys(graph, instance, progress);
  if (!graph.build_adjacency(nullptr)) {
    state.SkipWithError("no adjacency");
    return;
  }
  const bench::Csr adjacency = adjacency_of(graph.core());
  std::vector<Cost> dist(csr.begin.size());
  std::vector<Cost> table;
  double build_ms = 0, dijkstra_ms = 0, bound_ms = 0, table_ms = 0, p2p_ms = 0;
  std::size_t p2p_queries = 0, table_settled = 0;
  Cost longest_ms = 0;  // the table's longest finite entry: how far 32-bit edge costs are safe
  detail::ChStatistics stats;
  for (auto _ : state) {
    double t = cpu_ms();
    auto ch = ContractionHierarchy::build(adjacency.begin, adjacency.to, adjacency.cost,
                                          {.keep_ties = state.range(3) != 0});
    build_ms += cpu_ms() - t;
    if (!ch.has_value()) {
      state.SkipWithError(ch.error().message.c_str());
      return;
    }
    stats = ch->statistics();
    std::size_t searched = 0;
    t = cpu_ms();
    for (Node s : sources) {
      if (s + 1 >= adjacency.begin.size()) continue;  // the start inside a pipe: not in the map
      bench::dijkstra(adjacency, s, dist);
      ++searched;
    }
    dijkstra_ms += (cpu_ms() - t) / static_cast<double>(std::max<std::size_t>(searched, 1));
    t = cpu_ms();
    for (Node s : sources) bench::dijkstra(csr, s, dist);
    bound_ms += cpu_ms() - t;
    ChQuery query(*ch);
    t = cpu_ms();
    query.table(keys, keys, table);
    table_ms += cpu_ms() - t;
    table_settled = query.settled_total();
    for (Cost c : table) {
      if (c != kInfiniteCost) longest_ms = std::max(longest_ms, c);
    }
    benchmark::DoNotOptimize(table);
    t = cpu_ms();
    for (std::size_t i = 0; i < keys.size(); ++i) {
      benchmark::DoNotOptimize(query.distance(keys[i], keys[(i * 7 + 3) % keys.size()]));
      ++p2p_queries;
    }
    p2p_ms += cpu_ms() - t;
  }
  const auto n = static_cast<double>(state.iterations());
  const double elements =
      static_cast<double>(instance.map.manhole_count() + instance.map.pipe_count());
  state.counters["manholes_n"] = static_cast<double>(instance.map.manhole_count());
  state.counters["pipes_n"] = static_cast<double>(instance.map.pipe_count());
  state.counters["nodes"] = static_cast<double>(stats.nodes);
  state.counters["moves"] = static_cast<double>(stats.moves);
  state.counters["shortcuts"] = static_cast<double>(stats.shortcuts);
  state.counters["up_edges"] = static_cast<double>(stats.up_edges);
  state.counters["down_edges"] = static_cast<double>(stats.down_edges);
  state.counters["bytes_per_element"] = static_cast<double>(stats.bytes) / elements;
  state.counters["build_ms"] = build_ms / n;
  state.counters["dijkstra_ms"] = dijkstra_ms / n;
  state.counters["build_ratio"] = build_ms / dijkstra_ms;
  state.counters["keys"] = static_cast<double>(keys.size());
  state.counters["table_ms"] = table_ms / n;
  state.counters["table_settled"] = static_cast<double>(table_settled);
  state.counters["bound_ms"] = bound_ms / n;
  state.counters["table_ratio"] = table_ms / bound_ms;
  state.counters["longest_route_h"] = static_cast<double>(longest_ms) / 3.6e6;
  state.counters["p2p_us"] = 1e3 * p2p_ms / static_cast<double>(p2p_queries);
}
BENCHMARK(BM_ContractionHierarchy)
    ->ArgNames({"generator", "manholes", "tasks", "keep_ties"})
    ->ArgsProduct({{0, 1}, {1000, 10000, 100000}, {20}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

// Routes key to key: the route search's (forward from each key, every key a target) against the
// hierarchy's unpacked path. `routes`: pairs with a way; `cost_differs`: pairs of other costs
// (must be 0); `path_differs`: equal costs, other nodes; `first_step_differs`: of those, how many
// leave the key by another move; `routes_with_ties`: routes with another way of the same cost
// into one of their nodes (where the tie rule chose); `mean_hops`: nodes per route (the route
// search's). With a hierarchy built with keep_ties, its table's `unique` flags: `flagged` routes
// not unique, `flags_wrong` routes flagged otherwise than their ties say (must be 0), and
// `unique_but_differs` routes flagged unique whose unpacked way is not the search's (must be 0).
void BM_ContractionHierarchyTies(benchmark::State& state) {
  const Instance& instance = bench::bound_instance(static_cast<int>(state.range(0)),
                                                   static_cast<std::size_t>(state.range(1)),
                                                   static_cast<std::size_t>(state.range(2)));
  const MissionProgress progress = initial_progress(instance.mission, instance.map);
  PositionGraph graph(instance.map, instance.mission);
  const std::vector<Node> keys = map_keys(graph, instance, progress);
  if (!graph.build_adjacency(nullptr)) {
    state.SkipWithError("no adjacency");
    return;
  }
  const bench::Csr adjacency = adjacency_of(graph.core());
  auto ch = ContractionHierarchy::build(adjacency.begin, adjacency.to, adjacency.cost);
  if (!ch.has_value()) {
    state.SkipWithError(ch.error().message.c_str());
    return;
  }
  ChQuery query(*ch);
  auto tie_aware = ContractionHierarchy::build(adjacency.begin, adjacency.to, adjacency.cost,
                                               {.keep_ties = true});
  if (!tie_aware.has_value()) {
    state.SkipWithError(tie_aware.error().message.c_str());
    return;
  }
  ChQuery tie_query(*tie_aware);
  std::vector<Cost> table;
  std::vector<bool> unique;
  std::size_t flagged = 0, unique_but_differs = 0, flags_wrong = 0;
  detail::GraphSearch search(graph);
  std::size_t routes = 0, cost_differs = 0, path_differs = 0, first_step_differs = 0;
  std::size_t hops_search = 0, routes_with_ties = 0;
  std::vector<Node> want, got;
  for (auto _ : state) {
    routes = cost_differs = path_differs = first_step_differs = hops_search = routes_with_ties = 0;
    flagged = unique_but_differs = flags_wrong = 0;
    tie_query.table(keys, keys, table, &unique);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      const Node s = keys[i];
      search.run(std::span<const Node>(&s, 1), keys, kInfiniteCost,
                 detail::GraphSearch::Direction::kForward);
      for (std::size_t j = 0; j < keys.size(); ++j) {
        const Node t = keys[j];
        if (t == s || search.distance(t) == kInfiniteCost) continue;
        ++routes;
        search.path(t, want);
        const Cost d = query.path(s, t, got);
        hops_search += want.size();
        // Another way of the same cost into a node of the route: a predecessor other than the
        // route's at the same distance (settled before the node, so its distance is final).
        bool tied = false;
        for (std::size_t h = 1; h < want.size() && !tied; ++h) {
          graph.for_each_predecessor(want[h], [&](Node p, Cost c) {
            const Cost dp = search.distance(p);
            tied = tied ||
                   (p != want[h - 1] && dp != kInfiniteCost && dp + c == search.distance(want[h]));
          });
        }
        routes_with_ties += tied ? 1 : 0;
        const bool is_unique = unique[i * keys.size() + j];
        flagged += is_unique ? 0 : 1;
        flags_wrong += is_unique == tied ? 1 : 0;
        if (is_unique) {
          tie_query.path(s, t, got);
          unique_but_differs += got != want ? 1U : 0U;
        }
        if (d != search.distance(t)) {
          ++cost_differs;
        } else if (got != want) {
          ++path_differs;
          if (got.size() < 2 || want.size() < 2 || got[1] != want[1]) ++first_step_differs;
        }
      }
    }
  }
  state.counters["keys"] = static_cast<double>(keys.size());
  state.counters["routes"] = static_cast<double>(routes);
  state.counters["cost_differs"] = static_cast<double>(cost_differs);
  state.counters["path_differs"] = static_cast<double>(path_differs);
  state.counters["routes_with_ties"] = static_cast<double>(routes_with_ties);
  state.counters["flagged"] = static_cast<double>(flagged);
  state.counters["flags_wrong"] = static_cast<double>(flags_wrong);
  state.counters["unique_but_differs"] = static_cast<double>(unique_but_differs);
  state.counters["first_step_differs"] = static_cast<double>(first_step_differs);
  state.counters["mean_hops"] = static_cast<double>(hops_search) / static_cast<double>(routes);
}
BENCHMARK(BM_ContractionHierarchyTies)
    ->ArgNames({"generator", "manholes", "tasks"})
    ->ArgsProduct({{0, 1}, {1000, 10000, 100000}, {20}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace sewerplan::domain
