// SPDX-License-Identifier: MIT
#include "sewerplan/gis/wgs84_projection.h"

#include <cmath>
#include <string>

#include <proj.h>

namespace sewerplan::gis {

struct Wgs84Projection::Impl {
  Crs crs;
  PJ_CONTEXT* context = nullptr;
  PJ* transform = nullptr;

  ~Impl() {
    if (transform != nullptr) proj_destroy(transform);
    if (context != nullptr) proj_context_destroy(context);
  }

  Result<LonLat> apply(double x, double y, PJ_DIRECTION direction) const {
    const PJ_COORD out = proj_trans(transform, direction, proj_coord(x, y, 0, 0));
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
  return MapXY{.x = xy->lon_deg, .y = xy->lat_deg};
}

const Crs& Wgs84Projection::crs() const { return impl_->crs; }

}  // namespace sewerplan::gis
