// SPDX-License-Identifier: MIT
// Crs: the coordinate reference system a map's x and y are in, named by authority and code.
//
// A sewer network from GIS is surveyed in a projected system: "EPSG:25832" is ETRS89 / UTM zone
// 32N (x east, y north, metres), "EPSG:31467" the older DHDN / Gauss-Krüger zone 3. The map keeps
// the name so that its coordinates can be put on a street map again (export-geojson, through
// PROJ); core only names the system and never transforms a coordinate. A map without a CRS (the
// paper's test environment, a generated city) has local coordinates.
//
//   Result<Crs> crs = parse_crs("epsg:25832");   // {"EPSG", 25832}
//   crs->to_string();                             // "EPSG:25832"
//
// Thread safety: a plain value.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "sewerplan/core/result.h"

namespace sewerplan {

struct Crs {
  std::string authority;  // upper case, e.g. "EPSG"
  std::uint32_t code = 0;

  std::string to_string() const;  // "EPSG:25832"
  friend bool operator==(const Crs&, const Crs&) = default;
};

// "AUTHORITY:CODE" (the authority in letters, any case; the code a positive decimal number), or
// the OGC URN "urn:ogc:def:crs:AUTHORITY::CODE". Anything else is a kInvalidArgument error that
// quotes the text and shows the form expected. Whether the authority knows the code is for PROJ
// to say when a coordinate is transformed.
Result<Crs> parse_crs(std::string_view text);

}  // namespace sewerplan
