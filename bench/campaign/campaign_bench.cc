// SPDX-License-Identifier: MIT
// One fault-campaign run (campaign/run.h): drawing its faults, the oracle's plan, and the mission
// carried out twice (ours and the paper-era baseline) on the simulated robot, in this process. On
// the paper's test environment and on generated networks; the run index cycles so that every
// iteration meets other faults.
#include <benchmark/benchmark.h>

#include "sewerplan/campaign/record.h"
#include "sewerplan/campaign/run.h"
#include "sewerplan/core/json_fields.h"

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

// Reading runs.jsonl back (`campaign merge`, docs/campaign.md): one line of a real AIS run, with a
// fresh parser per line (argument 0, as before) or one parser for all lines (1, as merge reads).
void BM_ParseRunLine(benchmark::State& state) {
  const Instance& ais = ais_instance();
  Result<campaign::RunResult> run =
      campaign::run_one(ais.map, ais.mission, campaign::RunSettings{.campaign_seed = 1}, 3);
  if (!run.has_value()) {
    state.SkipWithError(run.error().message.c_str());
    return;
  }
  campaign::RunRecord record{.index = 3, .seed = 7, .result = *run, .wall_s = 0.25};
  const std::string line = campaign::run_json_line(record);
  JsonLineParser shared;
  std::size_t n = 0;
  for (auto _ : state) {
    Result<campaign::RunRecord> back =
        state.range(0) == 1 ? campaign::parse_run_line(line, "runs.jsonl", ++n, shared)
                            : campaign::parse_run_line(line, "runs.jsonl", ++n);
    if (!back.has_value()) {
      state.SkipWithError(back.error().message.c_str());
      return;
    }
    benchmark::DoNotOptimize(back);
  }
  state.counters["line_bytes"] = static_cast<double>(line.size());
}
BENCHMARK(BM_ParseRunLine)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace sewerplan::bench
