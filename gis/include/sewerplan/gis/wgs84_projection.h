// SPDX-License-Identifier: MIT
// Wgs84Projection: a map's coordinates to longitude and latitude on WGS84, through PROJ.
//
// GeoJSON (RFC 7946) has one coordinate reference system, WGS84 longitude and latitude in decimal
// degrees, in that order. A sewer map is in a projected system (its Crs, core/crs.h: ETRS89 / UTM,
// Gauss-Krüger, ...). This class asks PROJ (Debian libproj-dev) for the best transformation it
// knows between the two, offline: for a DHDN system without the national grid that is a Helmert
// transformation, good to a few metres, which is what a picture over a street map needs. The
// axis order is always x = easting (or longitude), y = northing (or latitude), whatever the EPSG
// definition says (proj_normalize_for_visualization).
//
// A map's x and y are metres whatever its CRS's unit (docs/gis.md, "Units"): to_wgs84 divides
// them by the CRS's linear unit, as PROJ defines it (0.3048006096 for the US survey feet of
// EPSG:2229), before transforming, and from_wgs84 multiplies by it.
//
//   Result<Wgs84Projection> wgs84 = Wgs84Projection::create(*map.crs());
//   Result<LonLat> p = wgs84->to_wgs84(manhole.position.x_m, manhole.position.y_m);
//
// PROJ is private to the gis library: nothing of it shows in this header.
//
// Thread safety: an object is for one thread at a time (it owns a PROJ context); make one per
// thread.
#pragma once

#include <memory>

#include "sewerplan/core/crs.h"
#include "sewerplan/core/result.h"
#include "sewerplan/domain/route_geometry.h"

namespace sewerplan::gis {

struct LonLat {
  double lon_deg = 0;
  double lat_deg = 0;
};

// A point in the map's CRS: x east, y north (route_geometry.h).
using MapXY = domain::MapXY;

class Wgs84Projection {
 public:
  // kInvalidArgument naming the CRS when PROJ does not know it or finds no transformation.
  static Result<Wgs84Projection> create(const Crs& crs);

  Wgs84Projection(Wgs84Projection&&) noexcept;
  Wgs84Projection& operator=(Wgs84Projection&&) noexcept;
  ~Wgs84Projection();

  // x, y in metres. A point outside the CRS's domain (PROJ answers infinity) is a
  // kInvalidArgument error.
  Result<LonLat> to_wgs84(double x, double y) const;
  // The inverse, for round trips and tests.
  Result<MapXY> from_wgs84(double lon_deg, double lat_deg) const;

  const Crs& crs() const;

 private:
  struct Impl;
  explicit Wgs84Projection(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace sewerplan::gis
