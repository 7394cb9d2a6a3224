// SPDX-License-Identifier: MIT
// The naive bound the planning benchmarks compare against (issues 16 and 35): K + 1 plain
// Dijkstra searches, one from the start and one from each task, over a compressed-sparse-row copy
// of the same primitive graph the compiler searches (domain/src/position_graph.h), built outside
// the timing; and the instances of the issue-35 rows (ours, the scrambled generator, the real
// networks in datasets/), each built once per process.
//
//   const Csr csr = to_csr(graph);
//   for (Node s : bound_sources(graph, instance, progress)) settled += dijkstra(csr, s, dist);
#pragma once

#include <cstddef>
#include <cstdint>
#include <ctime>
#include <functional>
#include <map>
#include <queue>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"

#include "position_graph.h"
#include "support/instances.h"
#include "support/scrambled_network.h"

namespace sewerplan::bench {

struct Csr {
  std::vector<std::uint32_t> begin;
  std::vector<domain::detail::Node> to;
  std::vector<domain::Cost> cost;
};

inline Csr to_csr(const domain::detail::PositionGraph& graph) {
  Csr g;
  g.begin.reserve(graph.size() + 1);
  for (domain::detail::Node n = 0; n < graph.size(); ++n) {
    g.begin.push_back(static_cast<std::uint32_t>(g.to.size()));
    graph.for_each_successor(n, [&](domain::detail::Node to, domain::Cost c) {
      g.to.push_back(to);
      g.cost.push_back(c);
    });
  }
  g.begin.push_back(static_cast<std::uint32_t>(g.to.size()));
  return g;
}

// Plain Dijkstra from `source` (a binary heap); with `stop_after` > 0 it stops once that many
// `marked` nodes (and an exit, with `exits`) are settled, else it settles everything it reaches.
// Returns the nodes settled.
inline std::size_t dijkstra(const Csr& g, domain::detail::Node source,
                            std::vector<domain::Cost>& dist,
                            const std::vector<bool>* marked = nullptr, std::size_t stop_after = 0,
                            const std::vector<bool>* exits = nullptr) {
  using domain::Cost;
  using domain::detail::Node;
  std::fill(dist.begin(), dist.end(), domain::kInfiniteCost);
  using Entry = std::pair<Cost, Node>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  dist[source] = 0;
  open.emplace(0, source);
  std::size_t settled = 0, found = 0;
  bool exit_found = exits == nullptr;
  while (!open.empty()) {
    const auto [d, n] = open.top();
    open.pop();
    if (d != dist[n]) continue;
    ++settled;
    if (stop_after > 0) {
      found += (*marked)[n] ? 1U : 0U;
      exit_found = exit_found || (*exits)[n];
      if (found >= stop_after && exit_found) break;
    }
    for (std::uint32_t e = g.begin[n]; e < g.begin[n + 1]; ++e) {
      const Cost nd = d + g.cost[e];
      if (nd < dist[g.to[e]]) {
        dist[g.to[e]] = nd;
        open.emplace(nd, g.to[e]);
      }
    }
  }
  return settled;
}

// The bound's K + 1 sources: the start (in a pipe, a node of its own, which the CSR copy holds),
// one end of each task's pipe, each task's manhole.
inline std::vector<domain::detail::Node> bound_sources(domain::detail::PositionGraph& graph,
                                                       const Mission& mission,
                                                       const domain::MissionProgress& progress) {
  std::vector<domain::detail::Node> sources{graph.node(progress.position)};
  for (const Task& t : mission.tasks) {
    if (const auto* spot = std::get_if<PipeSpot>(&t.place)) {
      sources.push_back(graph.pipe_end(spot->pipe, 0));
    } else {
      sources.push_back(graph.in_manhole(std::get<ManholeId>(t.place)));
    }
  }
  return sources;
}

// The thread's CPU time in ms: on a machine shared with other work, wall time counts their time
// too, and the two sides, measured one after the other, would be stretched unevenly.
inline double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

// Issue 35's generated instances: `generator` 0 is ours (generate_network, meshed, seed 1, with
// generate_mission's uniform spread for MAKRO PLUS, whose battery bounds the searches), 1 the
// scrambled generator (scrambled_network.h) with a battery that bounds nothing.
inline const Instance& bound_instance(int generator, std::size_t manholes, std::size_t tasks) {
  static std::map<std::tuple<int, std::size_t, std::size_t>, Instance> cache;
  const auto key = std::make_tuple(generator, manholes, tasks);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  Instance i;
  if (generator == 0) {
    i.map = *generate_network({.manholes = manholes, .seed = 1, .topology = Topology::kMeshed});
    i.mission = *domain::generate_mission(
        i.map, {.tasks = tasks, .seed = 1, .spread = domain::MissionSpread::kUniform});
  } else {
    i.map = *generate_scrambled_network({.manholes = manholes, .seed = 1});
    i.mission = *scrambled_mission(i.map, tasks, 1);
  }
  return cache.emplace(key, std::move(i)).first->second;
}

// The real networks of datasets/ and a mission on each: 0 the AIS test bed and the paper's
// mission; 1 EPA example 1, 2 the swmmio state-plane model, 3 Bellinge small, 4 the ISYBAU street
// of 2017, each with the most tasks, up to 20, the uniform spread finds room for, and a battery
// that bounds nothing.
inline constexpr int kRealNetworks = 5;
inline const Instance& real_instance(int network) {
  static std::map<int, Instance> cache;
  auto it = cache.find(network);
  if (it != cache.end()) return it->second;
  const std::string dir = std::string(SEWERPLAN_SOURCE_DIR) + "/datasets/";
  static const char* const kFiles[kRealNetworks] = {
      "ais-testbed/map.json", "swmm/epa-example1.inp", "swmm/swmmio-state-plane.inp",
      "swmm/bellinge-small.inp", "isybau/street-2017.xml"};
  if (network == 0) return ais_instance();
  Diagnostics d;
  Instance i;
  i.map = *read_map(dir + kFiles[network], d);
  for (std::size_t tasks = 20; tasks > 0; --tasks) {
    auto mission = domain::generate_mission(
        i.map,
        {.tasks = tasks, .seed = 1, .spread = domain::MissionSpread::kUniform, .battery_wh = 1e6});
    if (mission.has_value()) {
      i.mission = std::move(*mission);
      break;
    }
  }
  return cache.emplace(network, std::move(i)).first->second;
}

}  // namespace sewerplan::bench
