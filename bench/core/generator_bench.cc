// SPDX-License-Identifier: MIT
// BM_GenerateNetwork: synthetic networks of 1e3 .. 1e6 manholes, tree and meshed.
// BM_MapBuilderOnly, the baseline: validating and building the same records without generating
// them, i.e. the part of BM_GenerateNetwork that any map format pays.
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_builder.h"

namespace sewerplan {
namespace {

void BM_GenerateNetwork(benchmark::State& state, Topology topology) {
  const GeneratorOptions options{.manholes = static_cast<std::size_t>(state.range(0)),
                                 .topology = topology};
  std::size_t bytes = 0;
  for (auto _ : state) {
    Result<SewerMap> map = generate_network(options);
    if (!map.has_value()) {
      state.SkipWithError(map.error().message.c_str());
      return;
    }
    bytes = map->memory_bytes();
    benchmark::DoNotOptimize(map);
  }
  state.counters["manholes/s"] = benchmark::Counter(static_cast<double>(options.manholes),
                                                    benchmark::Counter::kIsIterationInvariantRate);
  state.counters["map_MB"] = static_cast<double>(bytes) / 1e6;
}

struct Records {
  std::string name;
  std::vector<ManholeRecord> manholes;
  std::vector<PipeRecord> pipes;
};

Records records_of(const SewerMap& map) {
  Records records{.name = map.name()};
  for (ManholeId m : map.manhole_ids()) {
    const Manhole& manhole = map.manhole(m);
    ManholeRecord& r = records.manholes.emplace_back(ManholeRecord{
        .name = manhole.name,
        .position = manhole.position,
        .diameter_m = manhole.diameter_m,
        .exit = manhole.exit,
        .variant = manhole.variant,
    });
    for (const Slot& slot : map.slots(m)) {
      r.slots.push_back({.pipe = map.pipe(slot.pipe).name,
                         .azimuth_deg = slot.azimuth_deg,
                         .invert_z_m = slot.invert_z_m});
    }
  }
  for (const Pipe& pipe : map.pipes()) {
    records.pipes.push_back({.name = pipe.name,
                             .from = map.manhole(*pipe.ends[0].manhole).name,
                             .to = map.manhole(*pipe.ends[1].manhole).name,
                             .length_m = pipe.length_m,
                             .diameter_m = pipe.diameter_m});
  }
  return records;
}

void BM_MapBuilderOnly(benchmark::State& state) {
  Result<SewerMap> map = generate_network({.manholes = static_cast<std::size_t>(state.range(0))});
  if (!map.has_value()) {
    state.SkipWithError(map.error().message.c_str());
    return;
  }
  const Records records = records_of(*map);
  for (auto _ : state) {
    state.PauseTiming();
    MapBuilder builder(records.name);
    builder.reserve(records.manholes.size(), records.pipes.size());
    for (const ManholeRecord& r : records.manholes) builder.add_manhole(r);
    for (const PipeRecord& r : records.pipes) builder.add_pipe(r);
    state.ResumeTiming();
    Diagnostics diagnostics;
    Result<SewerMap> built = std::move(builder).build(diagnostics);
    benchmark::DoNotOptimize(built);
  }
  state.counters["manholes/s"] = benchmark::Counter(static_cast<double>(records.manholes.size()),
                                                    benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK_CAPTURE(BM_GenerateNetwork, tree, Topology::kTree)
    ->Arg(1'000)
    ->Arg(10'000)
    ->Arg(100'000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_GenerateNetwork, tree, Topology::kTree)
    ->Arg(1'000'000)
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_GenerateNetwork, meshed, Topology::kMeshed)
    ->Arg(1'000)
    ->Arg(10'000)
    ->Arg(100'000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_GenerateNetwork, meshed, Topology::kMeshed)
    ->Arg(1'000'000)
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MapBuilderOnly)->Arg(1'000)->Arg(10'000)->Arg(100'000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MapBuilderOnly)->Arg(1'000'000)->Iterations(3)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewerplan
