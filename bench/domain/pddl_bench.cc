// SPDX-License-Identifier: MIT
// Writing the PDDL export: what a comparison with FF and Fast Downward costs before they start.
#include <benchmark/benchmark.h>

#include "sewerplan/domain/pddl.h"

#include "support/instances.h"

namespace sewerplan::bench {
namespace {

// Arguments: manholes, action costs (0 or 1); 10 tasks.
void BM_ExportPddl(benchmark::State& state) {
  const Instance& instance = generated_instance(static_cast<std::size_t>(state.range(0)), 10);
  std::size_t bytes = 0;
  for (auto _ : state) {
    auto files =
        domain::export_pddl(instance.map, instance.mission, {.action_costs = state.range(1) != 0});
    bytes = files->domain.size() + files->problem.size();
    benchmark::DoNotOptimize(files);
  }
  state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_ExportPddl)
    ->ArgNames({"manholes", "costs"})
    ->ArgsProduct({{1000, 100000}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewerplan::bench
