// SPDX-License-Identifier: MIT
// One fault-campaign run (campaign/run.h): drawing its faults, the oracle's plan, and the mission
// carried out twice (ours and the paper-era baseline) on the simulated robot, in this process. On
// the paper's test environment and on generated networks; the run index cycles so that every
// iteration meets other faults.
#include <benchmark/benchmark.h>

#include "sewerplan/campaign/run.h"

#include "support/instances.h"

namespace sewerplan::bench {
namespace {

void run_campaign_runs(benchmark::State& state, const Instance& instance) {
  const campaign::RunSettings settings{.campaign_seed = 1};
  std::size_t index = 0;
  std::size_t tasks = 0;
  for (auto _ : state) {
    Result<campaign::RunResult> r =
        campaign::run_one(instance.map, instance.mission, settings, index++ % 64);
    if (!r.has_value()) {
      state.SkipWithError(r.error().message.c_str());
      return;
    }
    tasks += r->ours.tasks;
    benchmark::DoNotOptimize(r);
  }
  state.counters["tasks_per_run"] =
      benchmark::Counter(static_cast<double>(tasks) / static_cast<double>(state.iterations()));
}

void BM_CampaignRunAis(benchmark::State& state) { run_campaign_runs(state, ais_instance()); }
BENCHMARK(BM_CampaignRunAis)->Unit(benchmark::kMicrosecond);

void BM_CampaignRunGenerated(benchmark::State& state) {
  run_campaign_runs(state, generated_instance(static_cast<std::size_t>(state.range(0)), 10));
}
BENCHMARK(BM_CampaignRunGenerated)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewerplan::bench
