// SPDX-License-Identifier: MIT
// sewerplan info --map MAP [--profile PROFILE [--start MANHOLE]] [--json]
#include <iomanip>
#include <map>
#include <optional>
#include <ostream>
#include <string_view>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/map_queries.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/domain/driveability.h"
#include "sewerplan/server/driveability_output.h"

#include "command.h"
#include "condition_options.h"
#include "crs_option.h"
#include "json_output.h"
#include "map_input.h"
#include "motion_options.h"
#include "text_format.h"

namespace sewerplan::cli {
namespace {

struct InfoOptions {
  std::string map;
  std::string gis_fields;      // --gis-fields
  std::string map_positional;  // deprecated: info MAP
  std::string profile;
  std::vector<std::string> starts;
  bool json = false;
  MotionOptions motion;
  std::string condition;
  std::string risk_table;
  std::string crs;
};

std::map<std::string, std::size_t> findings_by_code(const SewerMap& map) {
  std::map<std::string, std::size_t> counts;
  for (const Finding& f : map.findings()) ++counts[f.code];
  return counts;
}

void print_findings(const SewerMap& map, const RobotProfile* profile, const RiskTable& table,
                    const domain::DriveabilityReport* report, std::ostream& out) {
  if (map.finding_count() == 0) return;
  out << "findings       " << map.finding_count();
  bool first = true;
  for (const auto& [code, count] : findings_by_code(map)) {
    out << (first ? ": " : ", ") << code << " " << count;
    first = false;
  }
  out << '\n';
  if (profile == nullptr || report == nullptr) return;
  const server::Closures closed = server::split_closures(map, *profile, table, *report);
  auto place = [&](const FindingRisk& r) {
    const Finding& f = map.findings()[r.finding];
    return "  pipe " + map.pipe(f.pipe).name + " at " + metres(f.offset_m) + ": " + r.reason;
  };
  out << "closed by findings " << closed.enterable.size() << '\n';
  for (const FindingRisk& r : closed.enterable) out << place(r) << '\n';
  if (closed.undrivable.empty()) return;
  out << "closed by findings in pipes the robot cannot enter anyway " << closed.undrivable.size()
      << " (no change for a plan)\n";
  for (const auto& [r, why] : closed.undrivable) {
    out << place(r) << " (the pipe is " << why << ")\n";
  }
}

std::vector<std::string> exit_names(const SewerMap& map) {
  std::vector<std::string> names;
  for (const Manhole& m : map.manholes()) {
    if (m.exit) names.push_back(m.name);
  }
  return names;
}

nlohmann::json info_json(const SewerMap& map, const MapStatistics& s) {
  nlohmann::json types = nlohmann::json::object();
  for (auto [type, count] : s.manholes_by_type) types[std::to_string(type)] = count;
  return {{"name", map.name()},
          {"crs", map.crs() ? nlohmann::json(map.crs()->to_string()) : nlohmann::json()},
          {"manholes", s.manholes},
          {"pipes", s.pipes},
          {"inspection_points", s.inspection_points},
          {"manholes_by_type", types},
          {"total_length_m", s.total_length_m},
          {"pipe_diameter_m", {{"min", s.min_pipe_diameter_m}, {"max", s.max_pipe_diameter_m}}},
          {"manhole_diameter_m",
           {{"min", s.min_manhole_diameter_m}, {"max", s.max_manhole_diameter_m}}},
          {"blind_pipe_ends", s.blind_pipe_ends},
          {"components", s.components},
          {"bounding_box_m", {{"min", s.min_xy_m}, {"max", s.max_xy_m}}},
          {"exits", exit_names(map)},
          {"findings", map.finding_count()},
          {"findings_by_code", findings_by_code(map)},
          {"memory_bytes", map.memory_bytes()}};
}

void print_info(const SewerMap& map, const MapStatistics& s, std::ostream& out) {
  out << std::fixed << std::setprecision(2);
  out << "map            " << map.name() << '\n'
      << "crs            " << (map.crs() ? map.crs()->to_string() : "none (local coordinates)")
      << '\n'
      << "manholes       " << s.manholes << '\n'
      << "pipes          " << s.pipes << " (" << s.total_length_m << " m in all)\n"
      << "by type        ";
  for (auto [type, count] : s.manholes_by_type) {
    out << "TYPE_" << type << ": " << count << "  ";
  }
  out << '\n'
      << "pipe diameter  " << s.min_pipe_diameter_m << " to " << s.max_pipe_diameter_m << " m\n"
      << "manhole diam.  " << s.min_manhole_diameter_m << " to " << s.max_manhole_diameter_m
      << " m\n"
      << "extent         (" << s.min_xy_m[0] << ", " << s.min_xy_m[1] << ") to (" << s.max_xy_m[0]
      << ", " << s.max_xy_m[1] << ") m\n"
      << "connected      "
      << (s.components == 1 ? "yes" : "no, " + std::to_string(s.components) + " parts") << '\n'
      << "points         " << s.inspection_points << '\n'
      << "blind ends     " << s.blind_pipe_ends << '\n';
  const std::vector<std::string> exits = exit_names(map);
  out << "exits          " << exits.size();
  for (std::size_t i = 0; i < exits.size() && i < 12; ++i)
    out << (i == 0 ? ": " : ", ") << exits[i];
  if (exits.size() > 12) out << ", ...";
  out << '\n';
}

int run(const InfoOptions& o, Context& c) {
  int exit_code = kExitOk;
  const std::optional<std::string> path =
      map_path(o.map, o.map_positional, "info", c, o.json, exit_code);
  if (!path) return exit_code;
  Diagnostics diagnostics;
  Result<SewerMap> map = read_map_with_condition({*path, o.gis_fields}, o.condition, diagnostics);
  if (map.has_value()) map = apply_crs_option(std::move(*map), o.crs);
  if (!map.has_value()) return fail(c, o.json, map.error(), diagnostics);
  print_diagnostics(diagnostics, c.err);
  const MapStatistics stats = map_statistics(*map);
  Diagnostics table_diagnostics;
  Result<RiskTable> table = risk_table({.table = o.risk_table}, table_diagnostics);
  print_diagnostics(table_diagnostics, c.err);
  if (!table.has_value()) {
    if (table_diagnostics.error_count() == 0) c.err << table.error().message << '\n';
    return exit_code_for(table.error());
  }
  std::optional<RobotProfile> profile;
  std::vector<ManholeId> starts;
  if (!o.profile.empty()) {
    Result<RobotProfile> loaded = load_profile(o.profile);
    if (!loaded.has_value()) {
      return fail(c, o.json, Error{loaded.error().code, "--profile: " + loaded.error().message});
    }
    profile = *loaded;
    for (const std::string& name : o.starts) {
      const std::optional<ManholeId> m = map->find_manhole(name);
      if (!m) {
        return fail(
            c, o.json,
            Error{ErrorCode::kInvalidMap, "--start: no manhole '" + name + "' in " + *path});
      }
      starts.push_back(*m);
    }
    if (o.starts.empty()) starts = domain::default_starts(*map);
  } else if (!o.starts.empty()) {
    return usage_error(c, o.json, "--start needs --profile");
  }
  std::optional<domain::DriveabilityReport> report;
  if (profile) {
    Mission with_motion;  // only to carry the motion table, as plan does
    with_motion.profile = *profile;
    if (auto motion = attach_motion_table(o.motion, *path, *map, with_motion, c.err);
        !motion.has_value()) {
      return fail(c, o.json, motion.error());
    }
    // What the findings close, as plan closes it (the default risk mode).
    report =
        server::analyse_profile(*map, *profile, starts, with_motion.passage_motion.get(), *table);
  }
  if (o.json) {
    nlohmann::json j = info_json(*map, stats);
    if (report) {
      j["driveability"] = server::driveability_json(*report, *map, *profile);
      j["driveability"].update(
          server::closures_json(*map, server::split_closures(*map, *profile, *table, *report)));
    }
    print_json(c.out, j);
  } else {
    print_info(*map, stats, c.out);
    print_findings(*map, profile ? &*profile : nullptr, *table, report ? &*report : nullptr, c.out);
    if (report) server::print_driveability(*report, *map, *profile, c.out);
  }
  return kExitOk;
}

}  // namespace

void add_info_command(CLI::App& app, Context& context) {
  // Shared with the callback, which CLI11 keeps after this function returns.
  auto options = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "info",
      "Summarise a map: counts, manhole types, lengths, diameters, exits, connectivity; with "
      "--profile, what a robot can drive");
  cmd->add_option("--map", options->map, "Map file (.json, .sewer, SWMM .inp, ISYBAU .xml)");
  add_gis_fields_option(*cmd, options->gis_fields);
  cmd->add_option("map", options->map_positional, "Deprecated: use --map")->group("");
  add_motion_options(*cmd, options->motion);
  cmd->add_option("--profile", options->profile,
                  "Also report what this robot can drive: a built-in profile (makro-1.1, "
                  "makro-plus) or a profile JSON file");
  cmd->add_option("--start", options->starts,
                  "With --profile: reachability from this manhole (repeatable; default: the "
                  "map's exits, or the largest connected part if it has none)");
  cmd->add_flag("--json", options->json, "Print the summary as JSON");
  add_condition_option(*cmd, options->condition);
  add_crs_option(*cmd, options->crs);
  cmd->add_option("--risk-table", options->risk_table,
                  "The risk table that decides what the findings close (JSON, "
                  "docs/formats/risk-table.md); default: the built-in one");
  cmd->callback([options, &context] { context.exit_code = run(*options, context); });
}

}  // namespace sewerplan::cli
