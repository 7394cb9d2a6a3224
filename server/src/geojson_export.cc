// SPDX-License-Identifier: MIT
#include "sewerplan/server/geojson_export.h"

#include <optional>
#include <span>
#include <utility>

#include "sewerplan/domain/plan_text.h"
#include "sewerplan/gis/geojson.h"
#include "sewerplan/render/event_trace.h"

namespace sewerplan::server {

Result<std::string> export_geojson(const SewerMap& map, const Mission& mission,
                                   const GeoJsonExport& what, const StationGis& gis,
                                   Diagnostics& diagnostics) {
  if (!map.crs()) {
    return Error{ErrorCode::kInvalidArgument,
                 "map " + map.name() +
                     " names no coordinate reference system, so its coordinates cannot be placed "
                     "on the earth: give its file one (a map JSON's \"crs\", or sewerplan convert "
                     "--crs EPSG:NNNN)"};
  }
  std::optional<domain::Plan> plan;
  if (!what.plan_text.empty()) {
    Result<domain::Plan> p = domain::parse_plan(what.plan_text, "plan", map, mission, diagnostics);
    if (!p.has_value()) return p.error();
    plan = std::move(*p);
  }
  std::optional<render::EventTrace> trace;
  if (!what.log_text.empty()) {
    Result<render::EventTrace> t =
        render::read_event_trace(what.log_text, "events.jsonl", map, mission, diagnostics);
    if (!t.has_value()) return t.error();
    trace = std::move(*t);
  }
  if (!gis.to_geojson) {
#if SEWERPLAN_WITH_GIS
    return Error{ErrorCode::kUnsupportedFormat,
                 "the GeoJSON export needs GDAL and PROJ, but this station was given no GIS "
                 "(ServerOptions::gis)"};
#else
    return Error{ErrorCode::kUnsupportedFormat,
                 "this build has no GIS (SEWERPLAN_WITH_GIS=OFF): no GeoJSON export"};
#endif
  }
  const gis::GeoJsonInput input{
      .map = &map,
      .mission = &mission,
      .plan = plan ? &*plan : nullptr,
      .driven = trace ? &trace->driven : nullptr,
      .blocked = trace ? std::span<const Blockage>(trace->blocked) : std::span<const Blockage>()};
  return gis.to_geojson(input);
}

}  // namespace sewerplan::server
