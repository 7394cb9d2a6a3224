// SPDX-License-Identifier: MIT
// Topology queries: our flat CSR slots against Boost.Graph on the same network.
//
// Issue #2 left the choice between Boost.Graph and a flat CSR structure open, to be measured. The
// map's slots already are a CSR adjacency, so connected_components walks them directly; the
// baseline copies the network into a boost::adjacency_list and runs boost::connected_components,
// which is what using Boost.Graph for the map's topology would cost per query (construction
// included, since the map would otherwise hold both).
#include <map>

#include <benchmark/benchmark.h>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/connected_components.hpp>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_queries.h"

namespace sewerplan {
namespace {

const SewerMap& network(std::size_t manholes) {
  static std::map<std::size_t, SewerMap> cache;
  auto it = cache.find(manholes);
  if (it == cache.end()) {
    it =
        cache
            .emplace(
                manholes,
                *generate_network({.manholes = manholes, .seed = 1, .topology = Topology::kMeshed}))
            .first;
  }
  return it->second;
}

void BM_ConnectedComponentsCsr(benchmark::State& state) {
  const SewerMap& map = network(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    Components c = connected_components(map);
    benchmark::DoNotOptimize(c);
  }
}

using BoostGraph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS>;

BoostGraph to_boost(const SewerMap& map) {
  BoostGraph g(map.manhole_count());
  for (const Pipe& p : map.pipes()) {
    if (p.ends[0].manhole && p.ends[1].manhole) {
      boost::add_edge(p.ends[0].manhole->index(), p.ends[1].manhole->index(), g);
    }
  }
  return g;
}

void BM_ConnectedComponentsBoostGraph(benchmark::State& state) {
  const SewerMap& map = network(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    BoostGraph g = to_boost(map);
    std::vector<int> component(map.manhole_count());
    int n = boost::connected_components(g, component.data());
    benchmark::DoNotOptimize(n);
  }
}

void BM_ConnectedComponentsBoostGraphPrebuilt(benchmark::State& state) {
  const SewerMap& map = network(static_cast<std::size_t>(state.range(0)));
  BoostGraph g = to_boost(map);
  std::vector<int> component(map.manhole_count());
  for (auto _ : state) {
    int n = boost::connected_components(g, component.data());
    benchmark::DoNotOptimize(n);
  }
}

BENCHMARK(BM_ConnectedComponentsCsr)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ConnectedComponentsBoostGraph)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ConnectedComponentsBoostGraphPrebuilt)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace sewerplan
