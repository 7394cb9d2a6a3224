// SPDX-License-Identifier: MIT
// sewerplan: plan and replan missions of sewer-inspection robots from the command line.
#include <charconv>
#include <cmath>
#include <iostream>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "sewerplan/core/check.h"
#include "sewerplan/version.h"

#include "command.h"
#include "help_format.h"
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
    "sim-node, serve and completion, prints one JSON document on standard output; a failure "
    "prints\n"
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

struct CommandEntry {
  std::string_view name;  // as registered by `add`
  void (*add)(CLI::App& app, sewerplan::cli::Context& context);
};

constexpr CommandEntry kCommands[] = {
    {"validate", &sewerplan::cli::add_validate_command},
    {"info", &sewerplan::cli::add_info_command},
    {"generate", &sewerplan::cli::add_generate_command},
    {"convert", &sewerplan::cli::add_convert_command},
    {"plan", &sewerplan::cli::add_plan_command},
    {"check", &sewerplan::cli::add_check_command},
    {"export-pddl", &sewerplan::cli::add_export_pddl_command},
    {"import-plan", &sewerplan::cli::add_import_plan_command},
    {"simulate", &sewerplan::cli::add_simulate_command},
    {"sim-node", &sewerplan::cli::add_sim_node_command},
    {"campaign", &sewerplan::cli::add_campaign_command},
    {"render", &sewerplan::cli::add_render_command},
    {"motion", &sewerplan::cli::add_motion_command},
    {"index", &sewerplan::cli::add_index_command},
#ifdef SEWERPLAN_WITH_GIS
    {"export-geojson", &sewerplan::cli::add_export_geojson_command},
#endif
    {"serve", &sewerplan::cli::add_serve_command},
    {"merge-measurements", &sewerplan::cli::add_merge_measurements_command},
    {"fit-risk", &sewerplan::cli::add_fit_risk_command},
    {"completion", &sewerplan::cli::add_completion_command},
};

// Every number on the command line is checked before a command sees it: CLI11 reads "-5" into an
// unsigned option as 2^64 - 5 (a campaign of 2^64 runs, -j of 2^64 threads), and "nan" or "inf"
// into a double. A whole number must be digits only (no sign, no exponent) and fit its type; a
// real must be finite and not negative. The one signed option, a coordinate, is exempt from the
// sign. A failed check is a usage error (exit 2) naming the option.
std::string check_whole(std::string& text) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
    return "must be a whole number, 0 or more; got \"" + text + "\"";
  }
  return {};
}

std::string check_real(std::string& text, bool may_be_negative) {
  double value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) {
    return "must be a finite number; got \"" + text + "\"";
  }
  if (value < 0 && !may_be_negative) return "must not be negative; got " + text;
  return {};
}

void check_numbers(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    // The type's name, without what validators add ("UINT:INT in [1 - 9]").
    const std::string full = option->get_type_name();
    const std::string type = full.substr(0, full.find(':'));
    if (type == "UINT" || type == "INT") {
      option->check(CLI::Validator(check_whole, ""));
    } else if (type == "FLOAT") {
      const bool signed_option = option->check_lname("nav2-origin");
      option->check(CLI::Validator(
          [signed_option](std::string& text) { return check_real(text, signed_option); }, ""));
    }
  }
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    check_numbers(*command);
  }
}

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
  // Before the commands are added: each takes its parent's formatter.
  app.formatter(std::make_shared<HelpFormatter>(help_width()));
  Context context{std::cout, std::cerr};
  // Only the command argv names first is registered, when it names one: CLI11 builds every option
  // of every command it is given (strings, validators, callbacks), 2.4 M instructions for all of
  // them, more than a 10-manhole plan takes. `sewerplan --version` alone needs none. Help, an
  // option or an unknown word first: all, in this order (the order of --help).
  const std::span<const CommandEntry> commands = kCommands;
  const CommandEntry* named = nullptr;
  for (const CommandEntry& c : commands) {
    if (argc > 1 && std::string_view(argv[1]) == c.name) named = &c;
  }
  const bool version_only = argc == 2 && std::string_view(argv[1]) == "--version";
  // completion prints every command's options: it is registered with all of them.
  if (named != nullptr && named->add != &add_completion_command) {
    named->add(app, context);
  } else if (!version_only) {
    for (std::size_t i = 0; i < commands.size(); ++i) {
      commands[i].add(app, context);
      // The table's name is the one the command registers, or that command would never be alone.
      SEWER_CHECK(app.get_subcommand(static_cast<int>(i))->get_name() == commands[i].name,
                  "main.cc: kCommands names a command other than the one it adds");
    }
  }
  check_numbers(app);
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
