// SPDX-License-Identifier: MIT
// Issue 35: the routing index made beforehand (domain/route_index.h): what building, writing,
// reading and checking it cost, against what it saves the first compile.
//
// On the issue-35 instances (bench/support/dijkstra_bound.h: ours, generate_network, and the
// scrambled generator; 20 tasks), in the thread's CPU time, one iteration:
//   - build_ms: RouteIndex::build (the map's moves and the contraction hierarchy);
//   - file_bytes, bytes_per_element (per manhole + pipe);
//   - write_ms: the file's bytes (RouteIndex::bytes);
//   - read_ms: RouteIndex::read, every check included, against copy_ms, a plain copy of the
//     same bytes (the naive baseline: no reader can be faster);
//   - use_ms: CompileCache::use_route_index (the map's moves built, judging every passage, their
//     fingerprint taken and compared), of which fingerprint_ms the fingerprint alone;
//   - compile_ms: the first compile on the cache given the index, against auto_ms, the first
//     compile on a cache of the default policy (CompileCache::RoutingIndex::kAuto, which builds
//     the index in-process where the searches would cover the map).
//
// Arguments: generator (0 ours, 1 scrambled), manholes, tasks.
//
//   build/release/bench/sewerplan_domain_bench --benchmark_filter=RouteIndex
//       --benchmark_counters_tabular=true
#include <cstring>
#include <string>

#include <benchmark/benchmark.h>

#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/route_index.h"

#include "position_graph.h"
#include "route_index_internal.h"
#include "support/dijkstra_bound.h"

namespace sewerplan::domain {
namespace {

using bench::cpu_ms;

void BM_RouteIndexFile(benchmark::State& state) {
  const bench::Instance& instance = bench::bound_instance(static_cast<int>(state.range(0)),
                                                          static_cast<std::size_t>(state.range(1)),
                                                          static_cast<std::size_t>(state.range(2)));
  const SewerMap& map = instance.map;
  const Mission& mission = instance.mission;
  const MissionProgress progress = initial_progress(mission, map);
  for (auto _ : state) {
    double t = cpu_ms();
    Result<RouteIndex> built = RouteIndex::build(map, mission.profile, mission.passage_motion);
    const double build_ms = cpu_ms() - t;
    if (!built.has_value()) {
      state.SkipWithError(built.error().message.c_str());
      return;
    }
    t = cpu_ms();
    const std::string bytes = built->bytes();
    const double write_ms = cpu_ms() - t;
    t = cpu_ms();
    std::string copy(bytes.size(), '\0');
    std::memcpy(copy.data(), bytes.data(), bytes.size());
    benchmark::DoNotOptimize(copy.data());
    const double copy_ms = cpu_ms() - t;
    t = cpu_ms();
    Result<RouteIndex> read = RouteIndex::read(copy, "bench.route-index.bin");
    const double read_ms = cpu_ms() - t;
    if (!read.has_value()) {
      state.SkipWithError(read.error().message.c_str());
      return;
    }
    CompileCache cache;
    t = cpu_ms();
    const Result<void> used =
        cache.use_route_index(*read, map, mission.profile, mission.passage_motion);
    const double use_ms = cpu_ms() - t;
    if (!used.has_value()) {
      state.SkipWithError(used.error().message.c_str());
      return;
    }
    // The fingerprint alone, over a core's moves built outside the timing.
    auto core = std::make_shared<detail::GraphCore>(map, mission.profile, mission.passage_motion);
    detail::PositionGraph graph(map, mission, core);
    (void)graph.build_adjacency(nullptr);
    t = cpu_ms();
    benchmark::DoNotOptimize(detail::adjacency_fingerprint(*core));
    const double fingerprint_ms = cpu_ms() - t;
    t = cpu_ms();
    const auto with =
        compile_sewer_task(map, mission, progress, {.select_goals = true, .cache = &cache});
    const double compile_ms = cpu_ms() - t;
    CompileCache plain;
    t = cpu_ms();
    const auto without =
        compile_sewer_task(map, mission, progress, {.select_goals = true, .cache = &plain});
    const double auto_ms = cpu_ms() - t;
    if (!with.has_value() || !without.has_value()) {
      state.SkipWithError("the compile failed");
      return;
    }
    const auto elements = static_cast<double>(map.manhole_count() + map.pipe_count());
    state.counters["manholes_n"] = static_cast<double>(map.manhole_count());
    state.counters["build_ms"] = build_ms;
    state.counters["file_bytes"] = static_cast<double>(bytes.size());
    state.counters["bytes_per_element"] = static_cast<double>(bytes.size()) / elements;
    state.counters["write_ms"] = write_ms;
    state.counters["copy_ms"] = copy_ms;
    state.counters["read_ms"] = read_ms;
    state.counters["use_ms"] = use_ms;
    state.counters["fingerprint_ms"] = fingerprint_ms;
    state.counters["compile_ms"] = compile_ms;
    state.counters["index_rows"] = static_cast<double>(with->statistics().index_rows);
    state.counters["auto_ms"] = auto_ms;
    state.counters["auto_index_rows"] = static_cast<double>(without->statistics().index_rows);
  }
}
BENCHMARK(BM_RouteIndexFile)
    ->ArgNames({"generator", "manholes", "tasks"})
    ->ArgsProduct({{0, 1}, {10000, 100000}, {20}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace sewerplan::domain
