// SPDX-License-Identifier: MIT
// The GIS module: the gis library's entry points that the sewerplan command uses, behind one table
// in a shared module (sewerplan_gis.so) that the command loads with dlopen the first time it reads
// a GIS source or writes GeoJSON. GDAL and PROJ pull in about a hundred shared libraries (poppler,
// HDF5, netCDF, database clients, ...); linked into the command, every run paid for loading and
// relocating them, a few milliseconds that were most of a small plan's process
// (docs/benchmarks.md). Behind the module only the commands that need them load them.
//
// The module exports two C symbols: kModuleStampEntry, its ABI stamp, and kModuleEntry, the table.
// The table's functions take and return the library's own C++ types, so the module and the program
// must come from the same build: same sources, compiler and flags. The stamp says which: the
// project version, the build id (a hash of core's, domain's and gis's public headers and of the
// compiler and flags, generated at build time as SEWERPLAN_GIS_BUILD_ID in
// sewerplan_gis_build_id.h, cmake/gis_build_id.cmake) and the size of every type crossing the
// table. The loader (apps/sewerplan/gis_module.h) reads the stamp, a plain C string, before it
// touches the table, and refuses a module whose stamp is not its own.
//
// Thread safety: the functions are the gis library's (map_source.h, geojson.h): each call shares
// nothing.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/gis/geojson.h"

namespace sewerplan::gis {

struct ModuleTable {
  // read_map_source (map_source.h).
  Result<SewerMap> (*read_map_source)(const std::filesystem::path& path, Diagnostics& diagnostics,
                                      const std::optional<std::filesystem::path>& field_mapping);
  // to_geojson (geojson.h) through a Wgs84Projection of the map's CRS (an error if it has none).
  Result<std::string> (*to_geojson)(const GeoJsonInput& input);
  // to_nav2_route_graph (geojson.h).
  std::string (*to_nav2_route_graph)(const SewerMap& map, MapXY origin, std::string_view frame);
};

// The names of the symbols the module exports:
//   extern "C" const char* sewerplan_gis_module_stamp();  // module_abi_stamp() of its build
//   extern "C" const ModuleTable* sewerplan_gis_module();
inline constexpr const char* kModuleStampEntry = "sewerplan_gis_module_stamp";
using ModuleStampEntry = const char* (*)();
inline constexpr const char* kModuleEntry = "sewerplan_gis_module";
using ModuleEntry = const ModuleTable* (*)();

// The ABI stamp of a build with this version and build id, as compiled here, e.g.
// "sewerplan 0.1.0 build 3f09c2a1d4e5b6a7; sizes ModuleTable 24 SewerMap 1096 ...".
inline std::string module_abi_stamp(std::string_view version, std::string_view build_id) {
  const std::pair<const char*, std::size_t> sizes[] = {
      {"ModuleTable", sizeof(ModuleTable)},
      {"SewerMap", sizeof(SewerMap)},
      {"Result<SewerMap>", sizeof(Result<SewerMap>)},
      {"Diagnostics", sizeof(Diagnostics)},
      {"path", sizeof(std::filesystem::path)},
      {"optional<path>", sizeof(std::optional<std::filesystem::path>)},
      {"GeoJsonInput", sizeof(GeoJsonInput)},
      {"Result<string>", sizeof(Result<std::string>)},
      {"string", sizeof(std::string)},
      {"MapXY", sizeof(MapXY)},
      {"string_view", sizeof(std::string_view)},
  };
  std::string stamp =
      "sewerplan " + std::string(version) + " build " + std::string(build_id) + "; sizes";
  for (const auto& [type, size] : sizes)
    stamp += " " + std::string(type) + " " + std::to_string(size);
  return stamp;
}

}  // namespace sewerplan::gis
