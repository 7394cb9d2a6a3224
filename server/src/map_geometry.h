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
//
// The same geometry for the page, compact (GET /api/maps/ID/geometry, "application/octet-stream"):
// typed arrays the page reads in place (no parse, no object per feature), little-endian, each
// section at an offset aligned to its element size, in this order:
//
//   header, 56 bytes: "SPGM", u32 format version (kGeometryFormatVersion), u32 manholes M,
//     u32 pipes P, f64 bounds [4] (min_x, min_y, max_x, max_y), u32 name bytes N, u32 zero
//   f64 positions [2M]      each manhole's x, y (metres)
//   f64 length_m [P], f64 diameter_m [P]
//   u32 from [P], u32 to [P] each pipe's end manholes (kNoManhole: an open end)
//   u32 name_offsets [M + P + 1]  byte offsets into names: manhole i is [i, i + 1), pipe j is
//                                 [M + j, M + j + 1)
//   u16 slots [M], u8 exit [M] (0 | 1)
//   u8 names [N]            the names, UTF-8, one after another
//
// Inspection points and the map's name are not in it (the JSON has them). Every value is the
// JSON's, bit for bit: coordinates, lengths and diameters are the map's doubles (the JSON writes
// each with the digits that read back to the same double); a slot count is the map's 16 bits
// (format 1 cut it at 255). No field is narrowed: a map with more than 4,294,967,294 manholes,
// 4,294,967,295 pipes or 4 GiB of names has no compact geometry (an error naming the limit).
#pragma once

#include <cstdint>
#include <string>

#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::server {

// Runtime: O(manholes + pipes + points).
std::string map_geometry_json(const SewerMap& map, const std::string& id);

inline constexpr std::uint32_t kGeometryFormatVersion = 2;
inline constexpr std::uint32_t kNoManhole = 0xffffffff;

// The compact geometry, or a kInvalidArgument error when a count or the names' bytes pass what
// its 32-bit fields hold. Runtime: O(manholes + pipes + the names' bytes).
Result<std::string> map_geometry_binary(const SewerMap& map);

}  // namespace sewerplan::server
