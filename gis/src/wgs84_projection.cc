// SPDX-License-Identifier: MIT
#include "sewerplan/gis/wgs84_projection.h"

#include <cmath>
#include <string>

#include <proj.h>

namespace sewerplan::gis {

// Metres per unit of a projected CRS's axes (PROJ's unit_conv_factor of its first axis:
// 0.3048006096 for US survey feet); 1 for any other CRS (a geographic one's degrees are not
// scaled).
Result<double> linear_unit(PJ_CONTEXT* context, const std::string& name) {
  PJ* crs = proj_create(context, name.c_str());
  if (crs == nullptr) {
    return Error{ErrorCode::kInvalidArgument, "CRS " + name + ": PROJ does not know it"};
  }
  double factor = 1;
  const PJ_TYPE type = proj_get_type(crs);
  if (type == PJ_TYPE_PROJECTED_CRS || type == PJ_TYPE_COMPOUND_CRS) {
    PJ* horizontal = type == PJ_TYPE_COMPOUND_CRS ? proj_crs_get_sub_crs(context, crs, 0) : nullptr;
    PJ* cs = proj_crs_get_coordinate_system(context, horizontal != nullptr ? horizontal : crs);
    double conv = 0;
    if (cs != nullptr && proj_cs_get_type(context, cs) == PJ_CS_TYPE_CARTESIAN &&
        proj_cs_get_axis_info(context, cs, 0, nullptr, nullptr, nullptr, &conv, nullptr, nullptr,
                              nullptr) != 0 &&
        conv > 0) {
      factor = conv;
    }
    if (cs != nullptr) proj_destroy(cs);
    if (horizontal != nullptr) proj_destroy(horizontal);
  }
  proj_destroy(crs);
  return factor;
}

struct Wgs84Projection::Impl {
  Crs crs;
  PJ_CONTEXT* context = nullptr;
  PJ* transform = nullptr;
  double metres_per_unit = 1;  // the CRS's linear unit: a map's metres are divided by it

  ~Impl() {
    if (transform != nullptr) proj_destroy(transform);
    if (context != nullptr) proj_context_destroy(context);
  }

  Result<LonLat> apply(double x, double y, PJ_DIRECTION direction) const {
    const PJ_COORD out =
        proj_trans(transform, direction,
                   direction == PJ_FWD ? proj_coord(x / metres_per_unit, y / metres_per_unit, 0, 0)
                                       : proj_coord(x, y, 0, 0));
    if (!std::isfinite(out.xy.x) || !std::isfinite(out.xy.y)) {
      return Error{ErrorCode::kInvalidArgument, "(" + std::to_string(x) + ", " + std::to_string(y) +
                                                    ") lies outside what " + crs.to_string() +
                                                    " can transform to WGS84"};
    }
    return LonLat{.lon_deg = out.xy.x, .lat_deg = out.xy.y};
  }
};

Wgs84Projection::Wgs84Projection(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Wgs84Projection::Wgs84Projection(Wgs84Projection&&) noexcept = default;
Wgs84Projection& Wgs84Projection::operator=(Wgs84Projection&&) noexcept = default;
Wgs84Projection::~Wgs84Projection() = default;

Result<Wgs84Projection> Wgs84Projection::create(const Crs& crs) {
  auto impl = std::make_unique<Impl>();
  impl->crs = crs;
  impl->context = proj_context_create();
  // Offline: no grids fetched from the CDN, whatever the environment says.
  proj_context_set_enable_network(impl->context, 0);
  proj_log_level(impl->context, PJ_LOG_NONE);
  const std::string source = crs.to_string();
  Result<double> unit = linear_unit(impl->context, source);
  if (!unit.has_value()) return unit.error();
  impl->metres_per_unit = *unit;
  PJ* raw = proj_create_crs_to_crs(impl->context, source.c_str(), "EPSG:4326", nullptr);
  if (raw == nullptr) {
    const int code = proj_context_errno(impl->context);
    return Error{ErrorCode::kInvalidArgument,
                 "CRS " + source + ": PROJ finds no transformation to WGS84 (" +
                     proj_context_errno_string(impl->context, code) + ")"};
  }
  impl->transform = proj_normalize_for_visualization(impl->context, raw);
  proj_destroy(raw);
  if (impl->transform == nullptr) {
    return Error{ErrorCode::kInvalidArgument,
                 "CRS " + source + ": PROJ cannot order its axes as x east, y north"};
  }
  return Wgs84Projection(std::move(impl));
}

Result<LonLat> Wgs84Projection::to_wgs84(double x, double y) const {
  return impl_->apply(x, y, PJ_FWD);
}

Result<MapXY> Wgs84Projection::from_wgs84(double lon_deg, double lat_deg) const {
  Result<LonLat> xy = impl_->apply(lon_deg, lat_deg, PJ_INV);
  if (!xy.has_value()) return xy.error();
  return MapXY{.x = xy->lon_deg * impl_->metres_per_unit,
               .y = xy->lat_deg * impl_->metres_per_unit};
}

const Crs& Wgs84Projection::crs() const { return impl_->crs; }

}  // namespace sewerplan::gis
