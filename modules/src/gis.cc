// SPDX-License-Identifier: MIT
#include "sewerplan/modules/gis.h"

#include <span>
#include <string>

#include "sewerplan/modules/module.h"

namespace sewerplan::modules {

Result<const GisTable*> gis_module(const std::string& need, std::string_view what) {
  static const std::string stamp = gis_stamp();
  Result<const GisTable*> table = load_module_table<GisTable>(kGisModule, stamp);
  if (!table.has_value()) {
    return Error{table.error().code,
                 need + " needs " + std::string(what) + ", but " + table.error().message};
  }
  return *table;
}

server::StationGis station_gis() {
  return {.reproject = [](const Crs& crs, bool to_wgs84,
                          std::span<domain::MapXY> points) -> Result<void> {
            Result<const GisTable*> gis = gis_module("the basemap", "PROJ");
            if (!gis.has_value()) return gis.error();
            return (*gis)->reproject(crs, to_wgs84, points);
          },
          .to_geojson = [](const gis::GeoJsonInput& input) -> Result<std::string> {
            Result<const GisTable*> gis = gis_module("the GeoJSON export");
            if (!gis.has_value()) return gis.error();
            return (*gis)->to_geojson(input);
          }};
}

}  // namespace sewerplan::modules
