// SPDX-License-Identifier: MIT
// sewerplan: plan and replan missions of sewer-inspection robots from the command line.
#include <iostream>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "sewerplan/version.h"

#include "command.h"
#include "json_output.h"

namespace sewerplan::cli {

void print_diagnostics(const Diagnostics& diagnostics, std::ostream& err) {
  for (const Diagnostic& d : diagnostics.all()) err << d << '\n';
  if (diagnostics.dropped() > 0) err << "(" << diagnostics.dropped() << " more not shown)\n";
}

}  // namespace sewerplan::cli

namespace {

constexpr const char* kFooter =
    "Give the map with --map FILE (the old positional MAP of validate, info, convert and motion\n"
    "precompute still works, with a note on standard error). --json, on every command but\n"
    "sim-node and serve, prints one JSON document on standard output; a failure prints\n"
    "{\"error\": "
    "{\"code\", \"exit_code\", \"message\", ...}} (schemas: docs/cli.md).\n"
    "\n"
    "Exit codes:\n"
    "  0  success\n"
    "  1  invalid input: a file that does not parse or validate, an impossible request\n"
    "  2  command-line usage error\n"
    "  3  a file could not be read or written (simulate --can: the bus or the node)\n"
    "  4  no plan exists (simulate: the robot called for recovery, the beacon is on)\n"
    "  5  the search stopped at its time or expansion limit without a plan\n"
    "  6  campaign: not clean (a crash, hang, missed exit, stranded robot, reserve violation)";

bool wants_json(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::string_view(argv[i]) == "--json") return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace sewerplan::cli;  // NOLINT: the CLI's own namespace
  CLI::App app{"sewerplan: planning and replanning for autonomous sewer-inspection robots"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "sewerplan " + std::string(sewerplan::kVersion));
  app.footer(kFooter);
  Context context{std::cout, std::cerr};
  add_validate_command(app, context);
  add_info_command(app, context);
  add_generate_command(app, context);
  add_convert_command(app, context);
  add_plan_command(app, context);
  add_check_command(app, context);
  add_export_pddl_command(app, context);
  add_import_plan_command(app, context);
  add_simulate_command(app, context);
  add_sim_node_command(app, context);
  add_campaign_command(app, context);
  add_render_command(app, context);
  add_motion_command(app, context);
#ifdef SEWERPLAN_WITH_GIS
  add_export_geojson_command(app, context);
#endif
  add_serve_command(app, context);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    if (code == 0) return kExitOk;  // --help, --version
    if (wants_json(argc, argv)) {
      const sewerplan::Error error{sewerplan::ErrorCode::kInvalidArgument, e.what()};
      print_json(std::cout, {{"error", error_object(error, {}, kExitUsage)}});
    }
    return kExitUsage;
  }
  return context.exit_code;
}
