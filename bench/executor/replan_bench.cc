// SPDX-License-Identifier: MIT
// Replanning after a blockage: the time from report_failure to the new fused plan (world-model
// change, goal selection, search, fusion), on the paper's test environment and on generated
// networks. The robot is put where its first plan has it drive into a pipe after `steps_in` steps,
// half-way along that pipe, and an obstacle is reported just ahead.
#include <map>

#include <benchmark/benchmark.h>

#include "sewerplan/domain/route_index.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/executor/replanner.h"

#include "support/instances.h"
#include "support/scrambled_network.h"

namespace sewerplan::bench {
namespace {

struct Blocked {
  domain::MissionProgress progress;
  std::uint8_t heading_end = 1;
  executor::Failure failure;
};

// The first pipe the plan drives through after `steps_in` steps, half-way, blocked ahead.
std::optional<Blocked> blockage_on_route(const Instance& instance,
                                         const executor::PlanResponse& plan, std::size_t steps_in) {
  domain::PlanReplay replay(instance.map, instance.mission,
                            domain::initial_progress(instance.mission, instance.map));
  for (std::size_t i = 0; i < plan.plan.steps.size(); ++i) {
    const auto& step = plan.plan.steps[i];
    if (!replay.apply(step).has_value()) return std::nullopt;
    const auto* in = std::get_if<domain::InPipe>(&replay.position());
    if (i < steps_in || in == nullptr || !std::holds_alternative<domain::DriveManhole>(step)) {
      continue;
    }
    const Pipe& pipe = instance.map.pipe(in->pipe);
    const bool forward = in->offset_m == 0;
    Blocked b{replay.progress(), static_cast<std::uint8_t>(forward ? 1 : 0), {}};
    const double mid = pipe.length_m / 2;
    b.progress.position = domain::InPipe{in->pipe, mid};
    b.failure = {.kind = executor::Failure::Kind::kBlockage,
                 .pipe = in->pipe,
                 .offset_m = mid + (forward ? 0.05 : -0.05)};
    return b;
  }
  return std::nullopt;
}

// `warm`: the replanner has made the first plan itself, as on a mission (its compile cache holds
// the map's indices, domain::CompileCache); else a fresh replanner replans.
// `index`: the replanner is given the map's routing index first (as `plan` and `simulate` load
// it from beside the map, domain/route_index.h).
void replan_after_blockage(benchmark::State& state, const Instance& instance, bool warm = true,
                           const domain::RouteIndex* index = nullptr) {
  executor::Replanner first(instance.map, instance.mission);
  const executor::PlanResponse plan = first.plan();
  const auto blocked = blockage_on_route(instance, plan, plan.plan.steps.size() / 3);
  if (!blocked) {
    state.SkipWithError("no pipe on the route to block");
    return;
  }
  std::size_t dropped = 0;
  for (auto _ : state) {
    state.PauseTiming();
    executor::Replanner replanner(instance.map, instance.mission);
    if (index != nullptr && !replanner.use_route_index(*index).has_value()) {
      state.SkipWithError("the routing index is not the map's");
      return;
    }
    if (warm) (void)replanner.plan();
    (void)replanner.update(blocked->progress, blocked->heading_end);
    state.ResumeTiming();
    executor::PlanResponse r = replanner.report_failure(blocked->failure);
    dropped = r.newly_dropped.size();
    benchmark::DoNotOptimize(r);
  }
  state.counters["dropped"] = static_cast<double>(dropped);
  state.counters["steps"] = static_cast<double>(plan.plan.steps.size());
}

void BM_ReplanAfterBlockageAis(benchmark::State& state) {
  replan_after_blockage(state, ais_instance());
}
BENCHMARK(BM_ReplanAfterBlockageAis)->Unit(benchmark::kMicrosecond);

// Arguments: manholes, tasks.
void BM_ReplanAfterBlockageGenerated(benchmark::State& state) {
  replan_after_blockage(state, generated_instance(static_cast<std::size_t>(state.range(0)),
                                                  static_cast<std::size_t>(state.range(1))));
}
BENCHMARK(BM_ReplanAfterBlockageGenerated)
    ->ArgNames({"manholes", "tasks"})
    ->Args({1000, 5})
    ->Args({100000, 5})
    ->Args({100000, 10})
    ->Args({100000, 20})
    ->Unit(benchmark::kMillisecond);

// Issue 16: the same on missions spread over the network (the generator's and the planning
// benchmarks' default). Arguments: manholes, tasks, spread (MissionSpread: 0 uniform, 1 clustered),
// warm (1: the replanner made the first plan, as on a mission; 0: a fresh one, the baseline).
// Goal at 100,000 manholes and 20 tasks: under 10 ms.
void BM_ReplanAfterBlockageSpread(benchmark::State& state) {
  replan_after_blockage(state,
                        spread_instance(static_cast<std::size_t>(state.range(0)),
                                        static_cast<std::size_t>(state.range(1)),
                                        static_cast<domain::MissionSpread>(state.range(2))),
                        state.range(3) != 0);
}
BENCHMARK(BM_ReplanAfterBlockageSpread)
    ->ArgNames({"manholes", "tasks", "spread", "warm"})
    ->ArgsProduct({{100000}, {20}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

// Issue 35: the same on the scrambled generator's networks (bench/support/scrambled_network.h:
// numbered and named without spatial order, degree 2 to 4), the tasks spread over the whole
// network and a battery that bounds no search, where every route search settles most of the map.
// Arguments: manholes, warm (as above), index (1: the replanner has the map's routing index,
// built beforehand and not timed, as `sewerplan index build` keeps it beside the map). With
// warm, the replanner takes the rows of its last compile whose routes the blockage does not
// touch (domain::CompileCache, incremental replanning); cold, it compiles everything again. With
// the index, the rows' routes the blockage touches are searched toward each target, guided by
// the index (GraphSearch::run_toward), rather than by a search of the whole network.
void BM_ReplanAfterBlockageScrambled(benchmark::State& state) {
  static std::map<std::size_t, Instance> instances;
  static std::map<std::size_t, domain::RouteIndex> indices;
  const auto manholes = static_cast<std::size_t>(state.range(0));
  auto it = instances.find(manholes);
  if (it == instances.end()) {
    Instance i;
    i.map = *generate_scrambled_network({.manholes = manholes, .seed = 1});
    i.mission = *scrambled_mission(i.map, 20, 1);
    it = instances.emplace(manholes, std::move(i)).first;
  }
  const domain::RouteIndex* index = nullptr;
  if (state.range(2) != 0) {
    auto at = indices.find(manholes);
    if (at == indices.end()) {
      auto built = domain::RouteIndex::build(it->second.map, it->second.mission.profile,
                                             it->second.mission.passage_motion);
      if (!built.has_value()) {
        state.SkipWithError(built.error().message.c_str());
        return;
      }
      at = indices.emplace(manholes, std::move(*built)).first;
    }
    index = &at->second;
  }
  replan_after_blockage(state, it->second, state.range(1) != 0, index);
}
BENCHMARK(BM_ReplanAfterBlockageScrambled)
    ->ArgNames({"manholes", "warm", "index"})
    ->ArgsProduct({{10000, 100000}, {0, 1}, {0, 1}})
    ->Iterations(12)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewerplan::bench
