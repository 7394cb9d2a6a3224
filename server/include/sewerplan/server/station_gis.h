// SPDX-License-Identifier: MIT
// StationGis: what the operator station needs of GDAL and PROJ, given by the program that runs it.
// The basemap (basemap.h) places tiles through PROJ, and the GeoJSON export (geojson_export.h)
// writes through the gis library's to_geojson; neither the server library nor the station loads
// anything. The `sewerplan` command fills both from the GIS module, loaded the first time a page
// asks (sewerplan/modules/gis.h: station_gis), so a station never asked loads no PROJ; a program
// that links the gis library may fill them with its functions.
//
//   ServerOptions options{.maps = {...}, .gis = modules::station_gis()};
//
// Thread safety: the functions are called from the station's worker threads, several at once.
#pragma once

#include <functional>
#include <span>
#include <string>

#include "sewerplan/core/crs.h"
#include "sewerplan/core/result.h"
#include "sewerplan/domain/route_geometry.h"

namespace sewerplan::gis {
struct GeoJsonInput;  // sewerplan/gis/geojson.h
}  // namespace sewerplan::gis

namespace sewerplan::server {

struct StationGis {
  // Transforms `points` in place between `crs`'s metres and WGS84 longitude, latitude (x, y); a
  // point PROJ cannot transform becomes NaN, NaN; an error only when PROJ does not know the CRS
  // or the GIS cannot be had (its message says what the basemap needs).
  std::function<Result<void>(const Crs& crs, bool to_wgs84, std::span<domain::MapXY> points)>
      reproject;
  // The gis library's to_geojson through a WGS84 projection of the map's CRS.
  std::function<Result<std::string>(const gis::GeoJsonInput& input)> to_geojson;
};

}  // namespace sewerplan::server
