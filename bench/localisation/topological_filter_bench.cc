// SPDX-License-Identifier: MIT
// The localisation update per observation (issue 29: < 1 ms at 100,000 manholes).
//
// One observation is what the executor feeds the filter per manhole: the passage it took, the
// drive's odometry and the arrival's signature (pass + drive + arrive); the time is per
// observation, the filter reset to the leg's start each time (a reset is O(1)). Legs are the first
// 256 of a seeded walk on a meshed network (core/generator.h, seed 7), each with its pipe 10 %
// longer than mapped, and odometry drift of 3 % (one hypothesis stays likely) or 15 % (several
// do), and with nothing pruned (every explanation kept, up to eight misses in a row). The naive
// baseline is global localisation: scoring the same signature against every mouth of the network,
// as a filter without a local belief would, which grows with the network.
#include <map>
#include <vector>

#include <benchmark/benchmark.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/manhole_signature.h"
#include "sewerplan/localisation/topological_filter.h"

namespace sewerplan::localisation {
namespace {

struct Leg {
  ManholeId from{0};
  SlotIndex arrival{0};
  SlotIndex to{0};
  double length_m = 0;
  ManholeSignature seen;  // at the manhole the leg ends in
};

struct Instance {
  SewerMap map;
  std::vector<Leg> legs;
};

const Instance& instance(std::size_t manholes) {
  static std::map<std::size_t, Instance> cache;
  auto it = cache.find(manholes);
  if (it != cache.end()) return it->second;
  Instance i;
  i.map = *generate_network({.manholes = manholes, .seed = 7, .topology = Topology::kMeshed});
  ManholeId here = *i.map.find_manhole("M1");
  SlotIndex arrival{0};
  for (int step = 0; i.legs.size() < 256 && step < 4096; ++step) {
    const Manhole& m = i.map.manhole(here);
    std::optional<SlotIndex> to;
    for (int k = 0; k + 1 < m.slot_count && !to; ++k) {
      const SlotIndex s{static_cast<std::uint16_t>(
          (arrival.value() + 1 + (k + step) % (m.slot_count - 1)) % m.slot_count)};
      const Slot& slot = i.map.slot(here, s);
      if (i.map.pipe(slot.pipe).ends[1 - slot.pipe_end].manhole) to = s;
    }
    if (!to) {  // a dead end: start again from its neighbour
      const Slot& slot = i.map.slot(here, arrival);
      const PipeEnd& back = i.map.pipe(slot.pipe).ends[1 - slot.pipe_end];
      here = *back.manhole;
      arrival = back.slot;
      continue;
    }
    const Slot& slot = i.map.slot(here, *to);
    const Pipe& pipe = i.map.pipe(slot.pipe);
    const PipeEnd& far = pipe.ends[1 - slot.pipe_end];
    i.legs.push_back({.from = here,
                      .arrival = arrival,
                      .to = *to,
                      .length_m = pipe.length_m,
                      .seen = expected_signature(i.map, *far.manhole, far.slot)});
    here = *far.manhole;
    arrival = far.slot;
  }
  return cache.emplace(manholes, std::move(i)).first->second;
}

void run_legs(benchmark::State& state, double drift, LocalisationOptions options = {}) {
  const Instance& in = instance(static_cast<std::size_t>(state.range(0)));
  TopologicalFilter filter = *TopologicalFilter::create(in.map, options);
  std::size_t leg = 0;
  std::size_t hypotheses = 0;
  for (auto _ : state) {
    const Leg& l = in.legs[leg];
    leg = (leg + 1) % in.legs.size();
    (void)filter.reset({.position = domain::AtSlot{l.from, l.arrival}});
    (void)filter.pass(l.from, l.arrival, l.to);
    const double odometry = l.length_m * 1.10 * (1 + drift);
    (void)filter.drive(odometry, DriveDirection::kForward, drift * odometry);
    (void)filter.arrive(l.seen);
    hypotheses += filter.estimate().hypotheses.size();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["hypotheses"] =
      static_cast<double>(hypotheses) / static_cast<double>(state.iterations());
}

void BM_TopologicalFilterObservation(benchmark::State& state) { run_legs(state, 0.03); }
void BM_TopologicalFilterObservationDrifting(benchmark::State& state) { run_legs(state, 0.15); }
// Nothing pruned, up to eight missed manholes in a row: every explanation is kept.
void BM_TopologicalFilterObservationUnpruned(benchmark::State& state) {
  run_legs(state, 0.15, {.max_misses = 8, .prune_ratio = 0});
}

// The worst case: a belief full of hypotheses (max_hypotheses, 64), built by arrivals without a
// signature far from any mouth with odometry as uncertain as the pipes are long, nothing pruned,
// half the manholes missed, up to eight in a row. Each observation (turn, drive, arrive) then
// explains 64 hypotheses in up to 27 ways each and merges them. The copy of the belief it starts
// from is timed too.
void BM_TopologicalFilterObservationFullBelief(benchmark::State& state) {
  const Instance& in = instance(static_cast<std::size_t>(state.range(0)));
  const LocalisationOptions options{.miss_probability = 0.5,
                                    .unmapped_junctions_per_m = 0.01,
                                    .false_detections_per_m = 0.01,
                                    .max_misses = 8,
                                    .prune_ratio = 0};
  TopologicalFilter full = *TopologicalFilter::create(in.map, options);
  const Leg& l = in.legs[0];
  (void)full.reset({.position = domain::AtSlot{l.from, l.arrival}});
  (void)full.pass(l.from, l.arrival, l.to);
  for (int i = 0; i < 2; ++i) {
    if (i > 0) (void)full.turn(180);
    (void)full.drive(l.length_m * 2.5, DriveDirection::kForward, l.length_m);
    (void)full.arrive(std::nullopt);
  }
  std::size_t hypotheses = 0;
  for (auto _ : state) {
    TopologicalFilter filter = full;
    (void)filter.turn(180);
    (void)filter.drive(l.length_m * 1.5, DriveDirection::kForward, l.length_m);
    (void)filter.arrive(l.seen);
    hypotheses += filter.estimate().hypotheses.size();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["hypotheses_before"] = static_cast<double>(full.estimate().hypotheses.size());
  state.counters["hypotheses"] =
      static_cast<double>(hypotheses) / static_cast<double>(state.iterations());
}

// The naive baseline: the signature scored at every mouth of the network.
void BM_GlobalSignatureScan(benchmark::State& state) {
  const Instance& in = instance(static_cast<std::size_t>(state.range(0)));
  std::size_t leg = 0;
  for (auto _ : state) {
    const Leg& l = in.legs[leg];
    leg = (leg + 1) % in.legs.size();
    double best = -1e300;
    for (ManholeId m : in.map.manhole_ids()) {
      for (std::uint16_t s = 0; s < in.map.manhole(m).slot_count; ++s) {
        best = std::max(
            best, compare(expected_signature(in.map, m, SlotIndex{s}), l.seen).log_likelihood);
      }
    }
    benchmark::DoNotOptimize(best);
  }
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK(BM_TopologicalFilterObservation)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TopologicalFilterObservationDrifting)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TopologicalFilterObservationUnpruned)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TopologicalFilterObservationFullBelief)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_GlobalSignatureScan)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace sewerplan::localisation
