// SPDX-License-Identifier: MIT
// Benchmark instances: the paper's mission on the AIS test environment, and seeded missions on
// generated meshed networks, each built once per process and kept for every benchmark using it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <utility>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/domain/mission_generator.h"

namespace sewerplan::bench {

struct Instance {
  SewerMap map;
  Mission mission;
};

inline const Instance& ais_instance() {
  static const Instance instance = [] {
    Diagnostics d;
    const std::string dir = std::string(SEWERPLAN_SOURCE_DIR) + "/datasets/ais-testbed/";
    Instance i;
    i.map = *read_map(dir + "map.json", d);
    i.mission = *read_mission(dir + "missions/paper.json", i.map, d);
    return i;
  }();
  return instance;
}

// A meshed network of `manholes` (seed 1) with a `tasks`-task mission (seed 1).
inline const Instance& generated_instance(std::size_t manholes, std::size_t tasks) {
  static std::map<std::pair<std::size_t, std::size_t>, Instance> cache;
  const auto key = std::make_pair(manholes, tasks);
  auto it = cache.find(key);
  if (it == cache.end()) {
    Instance i;
    i.map = *generate_network({.manholes = manholes, .seed = 1, .topology = Topology::kMeshed});
    i.mission = *domain::generate_mission(i.map, {.tasks = tasks, .seed = 1});
    it = cache.emplace(key, std::move(i)).first;
  }
  return it->second;
}

// A meshed network of `manholes` (seed 1) with a `tasks`-task mission (seed 1) of the given
// spread: the planning benchmarks' default is uniform (issue 16).
inline const Instance& spread_instance(std::size_t manholes, std::size_t tasks,
                                       domain::MissionSpread spread) {
  static std::map<std::tuple<std::size_t, std::size_t, domain::MissionSpread>, Instance> cache;
  const auto key = std::make_tuple(manholes, tasks, spread);
  auto it = cache.find(key);
  if (it == cache.end()) {
    Instance i;
    i.map = *generate_network({.manholes = manholes, .seed = 1, .topology = Topology::kMeshed});
    i.mission = *domain::generate_mission(i.map, {.tasks = tasks, .seed = 1, .spread = spread});
    it = cache.emplace(key, std::move(i)).first;
  }
  return it->second;
}

}  // namespace sewerplan::bench
