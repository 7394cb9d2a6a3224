// SPDX-License-Identifier: MIT
// The GIS module: the gis library's entry points that the sewerplan command uses, behind one table
// in a shared module (sewerplan_gis.so) that the command loads with dlopen the first time it reads
// a GIS source or writes GeoJSON. GDAL and PROJ pull in about a hundred shared libraries (poppler,
// HDF5, netCDF, database clients, ...); linked into the command, every run paid for loading and
// relocating them, a few milliseconds that were most of a small plan's process
// (docs/benchmarks.md). Behind the module only the commands that need them load them.
//
// A module of sewerplan (module.h), named "gis": it exports sewerplan_gis_module_stamp, its ABI
// stamp (gis_stamp() below as built into it), and sewerplan_gis_module, the table. The command
// loads it through gis.h (gis_module), and gives the station its functions (station_gis).
//
// Thread safety: the functions are the gis library's (map_source.h, geojson.h): each call shares
// nothing.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/gis/geojson.h"
#include "sewerplan/modules/module.h"

namespace sewerplan::modules {

struct GisTable {
  // read_map_source (map_source.h).
  Result<SewerMap> (*read_map_source)(const std::filesystem::path& path, Diagnostics& diagnostics,
                                      const std::optional<std::filesystem::path>& field_mapping);
  // to_geojson (geojson.h) through a Wgs84Projection of the map's CRS (an error if it has none).
  Result<std::string> (*to_geojson)(const gis::GeoJsonInput& input);
  // to_nav2_route_graph (geojson.h).
  std::string (*to_nav2_route_graph)(const SewerMap& map, domain::MapXY origin,
                                     std::string_view frame);
  // Transforms `points` in place through a Wgs84Projection of `crs` (wgs84_projection.h): with
  // `to_wgs84`, from the CRS's x and y in metres to WGS84 (x: longitude, y: latitude, degrees),
  // else back. A point PROJ cannot transform (outside the CRS's domain) becomes NaN, NaN; an error
  // only when PROJ does not know the CRS or finds no transformation. (The station's basemap:
  // server/basemap.h.)
  Result<void> (*reproject)(const Crs& crs, bool to_wgs84, std::span<domain::MapXY> points);
};

inline constexpr const char* kGisModule = "gis";

// This build's ABI stamp for the table: the size of every type crossing it (module.h).
inline std::string gis_stamp() {
  const ModuleType types[] = {
      {"GisTable", sizeof(GisTable)},
      {"SewerMap", sizeof(SewerMap)},
      {"Result<SewerMap>", sizeof(Result<SewerMap>)},
      {"Diagnostics", sizeof(Diagnostics)},
      {"path", sizeof(std::filesystem::path)},
      {"optional<path>", sizeof(std::optional<std::filesystem::path>)},
      {"GeoJsonInput", sizeof(gis::GeoJsonInput)},
      {"Result<string>", sizeof(Result<std::string>)},
      {"string", sizeof(std::string)},
      {"MapXY", sizeof(domain::MapXY)},
      {"string_view", sizeof(std::string_view)},
      {"Crs", sizeof(Crs)},
      {"span<MapXY>", sizeof(std::span<domain::MapXY>)},
      {"Result<void>", sizeof(Result<void>)},
  };
  return module_abi_stamp(types);
}

}  // namespace sewerplan::modules
