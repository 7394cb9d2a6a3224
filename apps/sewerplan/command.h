// SPDX-License-Identifier: MIT
// The sewerplan CLI's commands: each registers itself as a CLI11 subcommand.
//
// Exit codes are part of the interface that scripts rely on (docs/cli.md):
//   0 success; 1 invalid input (a file that does not parse or validate, an impossible request);
//   2 command-line usage error; 3 a file could not be read or written; 4 no plan exists;
//   5 the search stopped at its time or expansion limit (or was cancelled) without a plan;
//   6 a campaign was not clean (a crash, hang, missed exit, stranded robot or reserve violation).
#pragma once

#include <iosfwd>
#include <string>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/server/documents.h"

namespace CLI {
class App;
}

namespace sewerplan::cli {

// The exit codes (0 success ... 6 campaign not clean) and exit_code_for live with the JSON
// documents that carry them (server/documents.h).
using enum server::ExitCode;
using server::exit_code_for;

// What a command's callback reports back to main().
struct Context {
  std::ostream& out;
  std::ostream& err;
  int exit_code = kExitOk;
};

void add_validate_command(CLI::App& app, Context& context);
void add_info_command(CLI::App& app, Context& context);
void add_generate_command(CLI::App& app, Context& context);
void add_convert_command(CLI::App& app, Context& context);
void add_check_command(CLI::App& app, Context& context);
void add_plan_command(CLI::App& app, Context& context);
void add_export_pddl_command(CLI::App& app, Context& context);
void add_import_plan_command(CLI::App& app, Context& context);
void add_simulate_command(CLI::App& app, Context& context);
void add_sim_node_command(CLI::App& app, Context& context);
void add_campaign_command(CLI::App& app, Context& context);
void add_render_command(CLI::App& app, Context& context);
void add_motion_command(CLI::App& app, Context& context);
void add_index_command(CLI::App& app, Context& context);
void add_export_geojson_command(CLI::App& app, Context& context);  // with SEWERPLAN_WITH_GIS
void add_serve_command(CLI::App& app, Context& context);
void add_merge_measurements_command(CLI::App& app, Context& context);
void add_fit_risk_command(CLI::App& app, Context& context);
// Needs every other command registered: it prints their options.
void add_completion_command(CLI::App& app, Context& context);

// Helpers shared by the commands.
void print_diagnostics(const Diagnostics& diagnostics, std::ostream& err);

}  // namespace sewerplan::cli
