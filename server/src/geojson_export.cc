// SPDX-License-Identifier: MIT
#include "sewerplan/server/geojson_export.h"

#include <optional>
#include <span>
#include <utility>

#include "sewerplan/domain/plan_text.h"
#include "sewerplan/render/event_trace.h"
#if SEWERPLAN_WITH_GIS
#include "sewerplan/core/module.h"
#include "sewerplan/gis/module.h"
#endif

namespace sewerplan::server {

Result<std::string> export_geojson(const SewerMap& map, const Mission& mission,
                                   const GeoJsonExport& what, Diagnostics& diagnostics) {
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
#if SEWERPLAN_WITH_GIS
  static const std::string stamp = gis::module_stamp();
  Result<const gis::ModuleTable*> module =
      load_module_table<gis::ModuleTable>(gis::kModuleName, stamp);
  if (!module.has_value()) {
    return Error{module.error().code,
                 "the GeoJSON export needs GDAL and PROJ, but " + module.error().message};
  }
  const gis::GeoJsonInput input{
      .map = &map,
      .mission = &mission,
      .plan = plan ? &*plan : nullptr,
      .driven = trace ? &trace->driven : nullptr,
      .blocked = trace ? std::span<const Blockage>(trace->blocked) : std::span<const Blockage>()};
  return (*module)->to_geojson(input);
#else
  return Error{ErrorCode::kUnsupportedFormat,
               "this build has no GIS (SEWERPLAN_WITH_GIS=OFF): no GeoJSON export"};
#endif
}

}  // namespace sewerplan::server
