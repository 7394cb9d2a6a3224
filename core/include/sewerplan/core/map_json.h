// SPDX-License-Identifier: MIT
// The native JSON map format: read and write a SewerMap.
//
// The format is documented field by field, with units, in docs/formats/map-json.md. In short:
//   {"format": "sewerplan-map", "version": 1, "name": "ais-testbed",
//    "manholes": [{"name": "M2", "x_m": 0, "y_m": 0, "z_m": 0, "diameter_m": 1.0, "exit": true,
//                  "variant": "B",
//                  "slots": [{"pipe": "P12", "azimuth_deg": 180, "invert_m": 0.0}, ...]}],
//    "pipes": [{"name": "P12", "from": "M1", "to": "M2", "length_m": 8.5, "diameter_m": 0.6}],
//    "inspection_points": [{"name": "W1", "pipe": "P6", "offset_m": 2.5}]}
// Problems are reported with the file and the JSON path ("map.json:$.pipes[3].length_m"), all of
// them in one pass; misspelt fields are warned about. Writing is streamed (a million manholes
// need no document tree) and exact: numbers are written in their shortest form that reads back
// bit-identical, so read(write(map)) == map.
//
//   Diagnostics diagnostics;
//   Result<SewerMap> map = read_map_json(text, "ais.json", diagnostics);
//   write_map_json(*map, std::cout);
//
// Thread safety: The readers and writers share nothing: call them from any number of threads, each
// with its own Diagnostics.
#pragma once

#include <ostream>
#include <string>
#include <string_view>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

inline constexpr std::string_view kMapJsonFormat = "sewerplan-map";
inline constexpr int kMapJsonVersion = 1;

Result<SewerMap> read_map_json(std::string_view text, const std::string& file_name,
                               Diagnostics& diagnostics);

void write_map_json(const SewerMap& map, std::ostream& out);

}  // namespace sewerplan
