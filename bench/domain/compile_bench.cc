// SPDX-License-Identifier: MIT
// Compiling a mission into a search task, by network size and number of tasks.
// Baseline: one full Dijkstra over the primitive graph from the start (what every key would cost
// without the early stop once all keys are settled).
#include <map>

#include <benchmark/benchmark.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"

#include "support/instances.h"

namespace sewerplan::domain {
namespace {

using bench::generated_instance;
using bench::Instance;

void BM_CompileSewerTask(benchmark::State& state) {
  const Instance& i = generated_instance(static_cast<std::size_t>(state.range(0)),
                                         static_cast<std::size_t>(state.range(1)));
  const MissionProgress progress = initial_progress(i.mission, i.map);
  CompileStatistics stats;
  for (auto _ : state) {
    auto task = compile_sewer_task(i.map, i.mission, progress);
    if (!task.has_value()) {
      state.SkipWithError(task.error().message.c_str());
      return;
    }
    stats = task->statistics();
  }
  state.counters["keys"] = static_cast<double>(stats.keys);
  state.counters["settled"] = static_cast<double>(stats.settled_nodes);
  state.counters["graph_nodes"] = static_cast<double>(stats.graph_nodes);
  state.counters["actions"] = static_cast<double>(stats.actions);
}
BENCHMARK(BM_CompileSewerTask)
    ->ArgNames({"manholes", "tasks"})
    ->Args({1000, 3})
    ->Args({10000, 10})
    ->Args({100000, 3})
    ->Args({100000, 20})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewerplan::domain
