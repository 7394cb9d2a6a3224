// SPDX-License-Identifier: MIT
// The GIS module's two exported symbols (sewerplan/modules/gis_table.h, module.h): its ABI stamp
// and the table of the gis library's entry points, built into sewerplan_gis.so with everything
// else hidden.
#include <cmath>
#include <limits>
#include <span>
#include <string>

#include "sewerplan/gis/map_source.h"
#include "sewerplan/gis/wgs84_projection.h"
#include "sewerplan/modules/gis_table.h"

namespace sewerplan::gis {
namespace {

Result<std::string> project_to_geojson(const GeoJsonInput& input) {
  if (input.map == nullptr) return Error{ErrorCode::kInvalidArgument, "to_geojson: no map"};
  if (!input.map->crs()) {
    return Error{ErrorCode::kInvalidArgument,
                 "to_geojson: the map names no coordinate reference system"};
  }
  Result<Wgs84Projection> wgs84 = Wgs84Projection::create(*input.map->crs());
  if (!wgs84.has_value()) return wgs84.error();
  return to_geojson(input, *wgs84);
}

Result<void> reproject(const Crs& crs, bool to_wgs84, std::span<MapXY> points) {
  Result<Wgs84Projection> wgs84 = Wgs84Projection::create(crs);
  if (!wgs84.has_value()) return wgs84.error();
  constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
  for (MapXY& p : points) {
    if (to_wgs84) {
      const Result<LonLat> q = wgs84->to_wgs84(p.x, p.y);
      p = q.has_value() ? MapXY{.x = q->lon_deg, .y = q->lat_deg} : MapXY{.x = kNan, .y = kNan};
    } else {
      const Result<MapXY> q = wgs84->from_wgs84(p.x, p.y);
      p = q.has_value() ? *q : MapXY{.x = kNan, .y = kNan};
    }
  }
  return {};
}

const modules::GisTable kTable{.read_map_source = &read_map_source,
                               .to_geojson = &project_to_geojson,
                               .to_nav2_route_graph = &to_nav2_route_graph,
                               .reproject = &reproject};

}  // namespace
}  // namespace sewerplan::gis

extern "C" __attribute__((visibility("default"))) const char* sewerplan_gis_module_stamp() {
  static const std::string stamp = sewerplan::modules::gis_stamp();
  return stamp.c_str();
}

extern "C" __attribute__((visibility("default"))) const void* sewerplan_gis_module() {
  return &sewerplan::gis::kTable;
}
