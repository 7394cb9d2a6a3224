// SPDX-License-Identifier: MIT
// The station's GeoJSON export: the network with a mission, the plan's route and the run's trace,
// as `sewerplan export-geojson --mission M --plan PLAN --log EVENTS` writes them. The plan is its
// text (what `plan -o` writes, the plan answer's "text"), the trace an event log (`simulate
// --log`'s JSON lines); both are read as the CLI reads its files (domain::parse_plan,
// render::read_event_trace) and written by the gis library's to_geojson, which the program gives
// (StationGis, station_gis.h: the command's loads the GIS module the first time a page asks,
// never in a server that is not asked).
//
//   Result<std::string> text =
//       export_geojson(map, mission, {.plan_text = plan, .log_text = log}, gis, d);
//
// Thread safety: shares nothing but gis.to_geojson (station_gis.h: any thread).
#pragma once

#include <string>
#include <string_view>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/server/station_gis.h"

namespace sewerplan::server {

struct GeoJsonExport {
  std::string_view plan_text;  // a plan's text; empty: no planned route
  std::string_view log_text;   // an event log's JSON lines; empty: no driven route
};

// A map without a CRS, a plan or log that does not read (kParse, naming "plan" or "events.jsonl"
// and the line), or no GIS (a build without it, an empty gis.to_geojson, or its own error: the
// GIS module missing): an error saying which.
Result<std::string> export_geojson(const SewerMap& map, const Mission& mission,
                                   const GeoJsonExport& what, const StationGis& gis,
                                   Diagnostics& diagnostics);

}  // namespace sewerplan::server
