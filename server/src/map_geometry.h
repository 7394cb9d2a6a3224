// SPDX-License-Identifier: MIT
// A map's geometry as the page draws it: one compact JSON document of columns (one array per
// field, index i of each is object i), in the map's own coordinates (metres):
//
//   {"id", "name", "bounds": [min_x, min_y, max_x, max_y],
//    "manholes": {"name": [...], "x": [...], "y": [...], "slots": [...], "exit": [0|1, ...]},
//    "pipes": {"name": [...], "from": [manhole index | -1], "to": [...], "length_m": [...],
//              "diameter_m": [...]},
//    "points": [{"name", "pipe", "offset_m"}]}
//
// A pipe end without a manhole (an open end) is -1; the page draws such a pipe from its one end.
#pragma once

#include <string>

#include "sewerplan/core/sewer_map.h"

namespace sewerplan::server {

// Runtime: O(manholes + pipes + points).
std::string map_geometry_json(const SewerMap& map, const std::string& id);

}  // namespace sewerplan::server
