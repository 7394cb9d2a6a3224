// SPDX-License-Identifier: MIT
// sewerplan export-geojson --map MAP [--crs EPSG:N] [--mission M [--plan PLAN | --plan-route]
//                          [--log EVENTS]] [--profile P] [--condition Z] -o OUT.geojson
//                          [--nav2 GRAPH.geojson [--nav2-origin X,Y]] [--json]
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "sewerplan/core/measurements_json.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/gis/geojson.h"
#include "sewerplan/modules/gis.h"
#include "sewerplan/render/event_trace.h"
#include "sewerplan/search/planner.h"

#include "command.h"
#include "condition_options.h"
#include "crs_option.h"
#include "driveability_option.h"
#include "json_output.h"
#include "map_input.h"
#include "output_format.h"

namespace sewerplan::cli {
namespace {

struct ExportOptions {
  std::string map;
  std::string gis_fields;  // --gis-fields
  std::string crs;
  std::string mission;
  std::string plan;
  bool plan_route = false;
  double time_limit_s = 10;
  std::string log;
  std::string measurements;  // a measurements file: its discrepancies as a layer
  std::string profile;
  std::string condition;
  std::string out;
  std::string nav2;
  std::vector<double> nav2_origin;
  bool json = false;
};

// A plan as text (PLAN files, plan -o) or as plan --json / check --json output, whose steps carry
// the same text in "action".
Result<domain::Plan> read_plan_any(const std::string& path, const SewerMap& map,
                                   const Mission& mission, Diagnostics& diagnostics) {
  Result<std::string> text = read_text_file(path);
  if (!text.has_value()) return text.error();
  const std::size_t first = text->find_first_not_of(" \t\r\n");
  if (first == std::string::npos || (*text)[first] != '{') {
    return domain::parse_plan(*text, path, map, mission, diagnostics);
  }
  const Json doc = Json::parse(*text, nullptr, false);
  if (doc.is_discarded() || !doc.contains("steps") || !doc["steps"].is_array()) {
    return Error{ErrorCode::kParse,
                 path +
                     ": neither a plan nor plan --json output with \"steps\" (a failed plan has "
                     "none)"};
  }
  std::string actions;
  for (const Json& step : doc["steps"]) {
    if (!step.is_object() || !step.contains("action") || !step["action"].is_string()) {
      return Error{ErrorCode::kParse, path + ": a step without its \"action\" text"};
    }
    actions += step["action"].get<std::string>() + "\n";
  }
  return domain::parse_plan(actions, path, map, mission, diagnostics);
}

Result<domain::Plan> plan_now(const SewerMap& map, const Mission& mission, double time_limit_s) {
  Result<search::PlanOutcome> outcome = search::plan_mission(
      map, mission, domain::initial_progress(mission, map), {.time_limit_s = time_limit_s});
  if (!outcome.has_value()) return outcome.error();
  return std::move(outcome->plan);
}

int run(const ExportOptions& o, Context& c) {
  if (o.out.empty() && o.nav2.empty()) {
    return usage_error(c, o.json, "export-geojson: give --out, --nav2 or both");
  }
  if ((!o.plan.empty() || o.plan_route || !o.log.empty()) && o.mission.empty()) {
    return usage_error(c, o.json, "export-geojson: --plan, --plan-route and --log need --mission");
  }
  if (!o.plan.empty() && o.plan_route) {
    return usage_error(c, o.json, "export-geojson: --plan or --plan-route, not both");
  }
  if (!o.nav2_origin.empty() && o.nav2_origin.size() != 2) {
    return usage_error(c, o.json, "--nav2-origin: give X,Y");
  }
  // Both files are GeoJSON (output_format.h): a GeoPackage or Shapefile name, which the command
  // reads, is refused rather than written as GeoJSON under that name.
  constexpr OutputExtension kGeoJson[] = {{".geojson", "geojson"}, {".json", "geojson"}};
  for (const auto& [file, option] : {std::pair{&o.out, "export-geojson -o"}, {&o.nav2, "--nav2"}}) {
    if (file->empty()) continue;
    if (Result<std::string_view> f = output_format(*file, option, kGeoJson); !f.has_value()) {
      return fail(c, o.json, f.error());
    }
  }
  Diagnostics diagnostics;
  auto failed = [&](const Error& e) { return fail(c, o.json, e, diagnostics); };
  Result<SewerMap> map = read_map_with_condition({o.map, o.gis_fields}, o.condition, diagnostics);
  if (map.has_value()) map = apply_crs_option(std::move(*map), o.crs);
  if (!map.has_value()) return failed(map.error());
  std::optional<Mission> mission;
  if (!o.mission.empty()) {
    Result<Mission> m = read_mission(o.mission, *map, diagnostics);
    if (!m.has_value()) return failed(m.error());
    mission = std::move(*m);
  }
  std::optional<domain::Plan> plan;
  if (!o.plan.empty() || o.plan_route) {
    Result<domain::Plan> p = o.plan_route ? plan_now(*map, *mission, o.time_limit_s)
                                          : read_plan_any(o.plan, *map, *mission, diagnostics);
    if (!p.has_value()) return failed(p.error());
    plan = std::move(*p);
  }
  std::optional<render::EventTrace> trace;
  if (!o.log.empty()) {
    Result<render::EventTrace> t =
        render::read_event_trace_file(o.log, *map, *mission, diagnostics);
    if (!t.has_value()) return failed(t.error());
    trace = std::move(*t);
  }
  std::optional<MapMeasurements> measured;
  if (!o.measurements.empty()) {
    Result<MapMeasurements> m = read_measurements(o.measurements, *map, diagnostics);
    if (!m.has_value()) return failed(m.error());
    measured = std::move(*m);
  }
  Result<std::optional<domain::DriveabilityReport>> driveability =
      driveability_for_profile(*map, o.profile);
  if (!driveability.has_value()) return failed(driveability.error());
  print_diagnostics(diagnostics, c.err);
  Json report = {{"crs", map->crs() ? Json(map->crs()->to_string()) : Json()}};
  if (!o.out.empty()) {
    if (!map->crs()) {
      return fail(c, o.json,
                  Error{ErrorCode::kInvalidArgument,
                        "export-geojson: " + o.map +
                            " names no coordinate reference system, so its coordinates cannot be "
                            "placed on the earth; give it with --crs EPSG:NNNN (e.g. EPSG:25832 "
                            "for ETRS89 / UTM 32N)"});
    }
    Result<const modules::GisTable*> module = modules::gis_module("export-geojson");
    if (!module.has_value()) return failed(module.error());
    const gis::GeoJsonInput input{
        .map = &*map,
        .mission = mission ? &*mission : nullptr,
        .plan = plan ? &*plan : nullptr,
        .driven = trace ? &trace->driven : nullptr,
        .blocked = trace ? std::span<const Blockage>(trace->blocked) : std::span<const Blockage>(),
        .driveability = *driveability ? &**driveability : nullptr,
        .discrepancies = measured ? std::span<const FoundDiscrepancy>(measured->discrepancies)
                                  : std::span<const FoundDiscrepancy>()};
    Result<std::string> text = (*module)->to_geojson(input);
    if (!text.has_value()) return failed(text.error());
    if (Result<void> w = write_text_file(o.out, *text); !w.has_value()) return failed(w.error());
    report["wrote"] = o.out;
    report["plan_steps"] = plan ? Json(plan->steps.size()) : Json();
    report["driven_steps"] = trace ? Json(trace->driven.size()) : Json();
    report["driveability"] = driveability->has_value();
    if (!o.json) c.out << "wrote " << o.out << " (WGS84, from " << map->crs()->to_string() << ")\n";
  }
  if (!o.nav2.empty()) {
    const gis::MapXY origin = o.nav2_origin.empty()
                                  ? gis::MapXY{}
                                  : gis::MapXY{.x = o.nav2_origin[0], .y = o.nav2_origin[1]};
    Result<const modules::GisTable*> module = modules::gis_module("export-geojson --nav2");
    if (!module.has_value()) return failed(module.error());
    if (Result<void> w =
            write_text_file(o.nav2, (*module)->to_nav2_route_graph(*map, origin, "map"));
        !w.has_value()) {
      return failed(w.error());
    }
    report["nav2"] = o.nav2;
    if (!o.json) c.out << "wrote " << o.nav2 << " (Nav2 route graph)\n";
  }
  if (o.json) print_json(c.out, report);
  return kExitOk;
}

}  // namespace

void add_export_geojson_command(CLI::App& app, Context& context) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export-geojson",
      "Write the network, a plan's route, a driven route and driveability as GeoJSON (WGS84), "
      "and Nav2's route graph");
  cmd->add_option("--map", o->map, "Map file")->required();
  add_gis_fields_option(*cmd, o->gis_fields);
  cmd->add_option("--crs,--assume-crs", o->crs,
                  "The map's coordinate reference system when its file names none, e.g. "
                  "EPSG:25832");
  cmd->add_option("--mission", o->mission, "Mission file (.json): start and tasks");
  cmd->add_option("--plan", o->plan, "The planned route: a plan text or plan --json output");
  cmd->add_flag("--plan-route", o->plan_route, "Plan the mission now and export its route");
  cmd->add_option("--time-limit", o->time_limit_s, "With --plan-route: seconds to plan")
      ->capture_default_str();
  cmd->add_option("--log", o->log, "Event log (simulate --log): route driven, blocked pipes");
  cmd->add_option("--measurements", o->measurements,
                  "Measurements file (simulate --corrected-map): its discrepancies as a layer");
  cmd->add_option("--profile", o->profile,
                  "Mark each pipe driveable or not for this robot (from the map's exits)");
  add_condition_option(*cmd, o->condition);
  cmd->add_option("-o,--out", o->out, "GeoJSON file to write (RFC 7946, WGS84)");
  cmd->add_option("--nav2", o->nav2, "Also write the route graph of Nav2's Route Server");
  cmd->add_option("--nav2-origin", o->nav2_origin,
                  "Subtract this X,Y from the Nav2 graph's coordinates (map units)")
      ->delimiter(',');
  cmd->add_flag("--json", o->json, "Print what was written as JSON");
  cmd->callback([o, &context] { context.exit_code = run(*o, context); });
}

}  // namespace sewerplan::cli
