// SPDX-License-Identifier: MIT
// sewerplan export-pddl --map MAP --mission MISSION --out DIR [--action-costs]
// sewerplan import-plan --format ff|fd --map MAP --mission MISSION FILE [-o PLAN] [--json]
#include <filesystem>
#include <ostream>

#include <CLI/CLI.hpp>

#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/domain/pddl.h"
#include "sewerplan/domain/plan_json.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"

#include "command.h"
#include "json_output.h"
#include "map_input.h"

namespace sewerplan::cli {
namespace {

struct Inputs {
  SewerMap map;
  Mission mission;
};

// Loads the map and the mission, or reports why not and sets the exit code.
std::optional<Inputs> load(const MapSource& map_source, const std::string& mission_path, bool json,
                           Context& c) {
  Diagnostics diagnostics;
  Result<SewerMap> map = read_input_map(map_source, diagnostics);
  Result<Mission> mission = map.has_value() ? read_mission(mission_path, *map, diagnostics)
                                            : Result<Mission>(map.error());
  if (!mission.has_value()) {
    c.exit_code = fail(c, json, mission.error(), diagnostics);
    return std::nullopt;
  }
  print_diagnostics(diagnostics, c.err);
  return Inputs{std::move(*map), std::move(*mission)};
}

struct ExportOptions {
  std::string map;
  std::string gis_fields;  // --gis-fields
  std::string mission;
  std::string out;
  bool action_costs = false;
  bool json = false;
};

int run_export(const ExportOptions& o, Context& c) {
  std::optional<Inputs> in = load({o.map, o.gis_fields}, o.mission, o.json, c);
  if (!in) return c.exit_code;
  Result<domain::PddlFiles> files =
      domain::export_pddl(in->map, in->mission, {.action_costs = o.action_costs});
  if (!files.has_value()) return fail(c, o.json, files.error());
  if (Result<void> made = create_output_directory(o.out); !made.has_value()) {
    return fail(c, o.json, made.error());
  }
  const std::filesystem::path dir(o.out);
  for (const auto& [name, text] :
       {std::pair{"domain.pddl", &files->domain}, std::pair{"problem.pddl", &files->problem}}) {
    Result<void> written = write_text_file(dir / name, *text);
    if (!written.has_value()) return fail(c, o.json, written.error());
  }
  if (o.json) {
    print_json(c.out, {{"domain", (dir / "domain.pddl").string()},
                       {"problem", (dir / "problem.pddl").string()},
                       {"action_costs", o.action_costs}});
  } else {
    c.out << "wrote " << (dir / "domain.pddl").string() << " and "
          << (dir / "problem.pddl").string() << (o.action_costs ? " (with action costs)" : "")
          << '\n';
  }
  return kExitOk;
}

struct ImportOptions {
  std::string map;
  std::string gis_fields;  // --gis-fields
  std::string mission;
  std::string format;
  std::string file;
  std::string out;
  bool json = false;
};

int run_import(const ImportOptions& o, Context& c) {
  const auto format = domain::pddl_plan_format_from_name(o.format);
  if (!format) {
    return usage_error(c, o.json, "--format: unknown planner output '" + o.format + "' (ff or fd)");
  }
  std::optional<Inputs> in = load({o.map, o.gis_fields}, o.mission, o.json, c);
  if (!in) return c.exit_code;
  Result<std::string> text = read_text_file(o.file);
  if (!text.has_value()) return fail(c, o.json, text.error());
  Diagnostics diagnostics;
  Result<domain::Plan> plan =
      domain::import_pddl_plan(*text, o.file, *format, in->map, in->mission, diagnostics);
  if (!plan.has_value()) return fail(c, o.json, plan.error(), diagnostics);
  print_diagnostics(diagnostics, c.err);
  if (!o.out.empty()) {
    Result<void> written = write_text_file(o.out, domain::format_plan(*plan, in->map, in->mission));
    if (!written.has_value()) return fail(c, o.json, written.error());
  }
  const domain::ValidationReport report = domain::validate_plan(*plan, in->map, in->mission);
  if (o.json) {
    print_json(c.out, plan_verdict_json(*plan, report, in->map, in->mission));
  } else {
    if (o.out.empty()) c.out << domain::format_plan(*plan, in->map, in->mission);
    c.out << report << '\n';
  }
  return report.valid ? kExitOk : kExitInvalidInput;
}

}  // namespace

void add_export_pddl_command(CLI::App& app, Context& context) {
  // Shared with the callback, which CLI11 keeps after this function returns.
  auto options = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export-pddl",
      "Write a map and mission as PDDL (domain.pddl, problem.pddl) for FF or Fast "
      "Downward, in the paper's action vocabulary");
  cmd->add_option("--map", options->map, "Map file")->required();
  add_gis_fields_option(*cmd, options->gis_fields);
  cmd->add_option("--mission", options->mission, "Mission file (.json)")->required();
  cmd->add_option("--out", options->out, "Directory to write domain.pddl and problem.pddl to")
      ->required();
  cmd->add_flag("--action-costs", options->action_costs,
                "Add :action-costs with each action's cost in ms (Fast Downward; not FF 2.3)");
  cmd->add_flag("--json", options->json, "Print the files written as JSON");
  cmd->callback([options, &context] { context.exit_code = run_export(*options, context); });
}

void add_import_plan_command(CLI::App& app, Context& context) {
  auto options = std::make_shared<ImportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "import-plan",
      "Read FF's output or Fast Downward's sas_plan for an export-pddl problem, and validate it");
  cmd->add_option("--format", options->format, "ff (FF's standard output) or fd (sas_plan)")
      ->required();
  cmd->add_option("--map", options->map, "Map file the PDDL was exported from")->required();
  add_gis_fields_option(*cmd, options->gis_fields);
  cmd->add_option("--mission", options->mission, "Mission file the PDDL was exported from")
      ->required();
  cmd->add_option("file", options->file, "The planner's output")->required();
  cmd->add_option("-o,--out", options->out, "Write the plan in sewerplan's text form to this file");
  cmd->add_flag("--json", options->json, "Print the plan, its costs and the verdict as JSON");
  cmd->callback([options, &context] { context.exit_code = run_import(*options, context); });
}

}  // namespace sewerplan::cli
