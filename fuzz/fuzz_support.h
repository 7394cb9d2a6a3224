// SPDX-License-Identifier: MIT
// What the fuzz targets share: the AIS test bed's map and mission, read once, for the parsers that
// resolve names against a map (missions, plans).
#pragma once

#include <cstdlib>
#include <iostream>
#include <string>

#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"

namespace sewerplan::fuzz {

struct Testbed {
  SewerMap map;
  Mission mission;
};

// Aborts if the test bed does not load: the fuzz target would test nothing.
inline const Testbed& testbed() {
  static const Testbed kTestbed = [] {
    const std::string dir = std::string(SEWERPLAN_SOURCE_DIR) + "/datasets/ais-testbed/";
    Diagnostics d;
    Result<SewerMap> map = read_map(dir + "map.json", d);
    if (!map.has_value()) {
      std::cerr << map.error() << '\n';
      std::abort();
    }
    Result<Mission> mission = read_mission(dir + "missions/paper.json", *map, d);
    if (!mission.has_value()) {
      std::cerr << mission.error() << '\n';
      std::abort();
    }
    return Testbed{std::move(map).value(), std::move(mission).value()};
  }();
  return kTestbed;
}

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};  // NOLINT: bytes as text
}

}  // namespace sewerplan::fuzz
