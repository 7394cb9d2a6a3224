// SPDX-License-Identifier: MIT
// The GIS module: the gis library's entry points that the sewerplan command uses, behind one table
// in a shared module (sewerplan_gis.so) that the command loads with dlopen the first time it reads
// a GIS source or writes GeoJSON. GDAL and PROJ pull in about a hundred shared libraries (poppler,
// HDF5, netCDF, database clients, ...); linked into the command, every run paid for loading and
// relocating them, a few milliseconds that were most of a small plan's process
// (docs/benchmarks.md). Behind the module only the commands that need them load them.
//
// The module exports one C symbol, kModuleEntry, that returns the table. The table's functions
// take and return the library's own C++ types, so the module and the program must be built from
// the same sources: the table carries the project version it was built from, and the loader
// (apps/sewerplan/gis_module.h) refuses a module of another version.
//
// Thread safety: the functions are the gis library's (map_source.h, geojson.h): each call shares
// nothing.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/gis/geojson.h"

namespace sewerplan::gis {

struct ModuleTable {
  const char* version;  // the project version the module was built from
  // read_map_source (map_source.h).
  Result<SewerMap> (*read_map_source)(const std::filesystem::path& path, Diagnostics& diagnostics,
                                      const std::optional<std::filesystem::path>& field_mapping);
  // to_geojson (geojson.h) through a Wgs84Projection of the map's CRS (an error if it has none).
  Result<std::string> (*to_geojson)(const GeoJsonInput& input);
  // to_nav2_route_graph (geojson.h).
  std::string (*to_nav2_route_graph)(const SewerMap& map, MapXY origin, std::string_view frame);
};

// The name of the symbol the module exports: extern "C" const ModuleTable* sewerplan_gis_module().
inline constexpr const char* kModuleEntry = "sewerplan_gis_module";
using ModuleEntry = const ModuleTable* (*)();

}  // namespace sewerplan::gis
