// SPDX-License-Identifier: MIT
// sewerplan: plan and replan missions of sewer-inspection robots from the command line.
#include <iostream>

#include <CLI/CLI.hpp>

#include "command.h"

namespace sewerplan::cli {

int exit_code_for(const Error& error) {
  switch (error.code) {
    case ErrorCode::kIo:
    case ErrorCode::kCanTimeout:
    case ErrorCode::kBusError:
      return kExitIo;
    case ErrorCode::kInvalidArgument:
      return kExitUsage;
    case ErrorCode::kNoPlan:
      return kExitNoPlan;
    case ErrorCode::kSearchLimit:
    case ErrorCode::kCancelled:
      return kExitSearchLimit;
    case ErrorCode::kParse:
    case ErrorCode::kInvalidMap:
    case ErrorCode::kInvalidMission:
    case ErrorCode::kInvalidProfile:
    case ErrorCode::kUnsupportedFormat:
      return kExitInvalidInput;
  }
  return kExitInvalidInput;
}

void print_diagnostics(const Diagnostics& diagnostics, std::ostream& err) {
  for (const Diagnostic& d : diagnostics.all()) err << d << '\n';
  if (diagnostics.dropped() > 0) err << "(" << diagnostics.dropped() << " more not shown)\n";
}

}  // namespace sewerplan::cli

int main(int argc, char** argv) {
  using namespace sewerplan::cli;  // NOLINT: the CLI's own namespace
  CLI::App app{"sewerplan: planning and replanning for autonomous sewer-inspection robots"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "sewerplan 0.1.0");
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }
  return context.exit_code;
}
