// SPDX-License-Identifier: MIT
// sewerplan validate --map MAP [--mission FILE] [--strict] [--json] [--crs AUTHORITY:CODE]
#include <ostream>

#include <CLI/CLI.hpp>

#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"

#include "command.h"
#include "condition_options.h"
#include "crs_option.h"
#include "json_output.h"
#include "map_input.h"

namespace sewerplan::cli {
namespace {

struct ValidateOptions {
  std::string map;
  std::string gis_fields;      // --gis-fields
  std::string map_positional;  // deprecated: validate MAP
  std::string mission;
  bool strict = false;
  bool json = false;
  std::string condition;
  std::string crs;
};

int run(const ValidateOptions& o, Context& c) {
  int exit_code = kExitOk;
  const std::optional<std::string> path =
      map_path(o.map, o.map_positional, "validate", c, o.json, exit_code);
  if (!path) return exit_code;
  Diagnostics diagnostics;
  Result<SewerMap> map = read_map_with_condition({*path, o.gis_fields}, o.condition, diagnostics);
  if (map.has_value()) map = apply_crs_option(std::move(*map), o.crs);
  std::optional<Error> failure;
  if (!map.has_value()) {
    failure = map.error();
  } else if (!o.mission.empty()) {
    Result<Mission> mission = read_mission(o.mission, *map, diagnostics);
    if (!mission.has_value()) failure = mission.error();
  }
  const bool valid = !failure && !(o.strict && diagnostics.warning_count() > 0);
  if (o.json) {
    Json j = {{"valid", valid},
              {"errors", diagnostics_json(diagnostics, Severity::kError)},
              {"warnings", diagnostics_json(diagnostics, Severity::kWarning)}};
    if (failure && failure->code == ErrorCode::kIo)
      j["errors"].push_back({{"where", ""}, {"message", failure->message}});
    if (failure) j["error"] = error_object(*failure, diagnostics, exit_code_for(*failure));
    if (map.has_value()) {
      j["manholes"] = map->manhole_count();
      j["pipes"] = map->pipe_count();
    }
    print_json(c.out, j);
  } else {
    print_diagnostics(diagnostics, c.err);
    if (failure && diagnostics.error_count() == 0) c.err << failure->message << '\n';
    if (valid) {
      c.out << *path << ": valid (" << map->manhole_count() << " manholes, " << map->pipe_count()
            << " pipes" << (o.mission.empty() ? "" : ", mission " + o.mission + " valid") << ", "
            << diagnostics.warning_count() << " warnings)\n";
    }
  }
  if (failure) return exit_code_for(*failure);
  return valid ? kExitOk : kExitInvalidInput;
}

}  // namespace

void add_validate_command(CLI::App& app, Context& context) {
  // Shared with the callback, which CLI11 keeps after this function returns.
  auto options = std::make_shared<ValidateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "validate",
      "Check a map (and a mission on it): every problem with its file and line or path");
  cmd->add_option("--map", options->map, "Map file (any format of docs/formats/)");
  add_gis_fields_option(*cmd, options->gis_fields);
  cmd->add_option("map", options->map_positional, "Deprecated: use --map")->group("");
  cmd->add_option("--mission", options->mission, "Also check this mission file against the map");
  cmd->add_flag("--strict", options->strict, "Treat warnings as errors");
  cmd->add_flag("--json", options->json, "Print the result as JSON");
  add_condition_option(*cmd, options->condition);
  add_crs_option(*cmd, options->crs);
  cmd->callback([options, &context] { context.exit_code = run(*options, context); });
}

}  // namespace sewerplan::cli
