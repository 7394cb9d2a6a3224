// SPDX-License-Identifier: MIT
// sewerplan convert IN OUT [--to json|ascii]
#include <ostream>

#include <CLI/CLI.hpp>

#include "sewerplan/core/map_io.h"

#include "command.h"
#include "condition_options.h"

namespace sewerplan::cli {
namespace {

struct ConvertOptions {
  std::string in;
  std::string out;
  std::string to;
  std::string condition;
};

int run(const ConvertOptions& o, Context& c) {
  std::optional<MapFormat> format;
  if (!o.to.empty()) {
    format = map_format_from_name(o.to);
    if (!format) {
      c.err << "--to: unknown format '" << o.to << "' (json or ascii)\n";
      return kExitUsage;
    }
    if (!is_writable(*format)) {
      c.err << "--to: sewerplan reads " << o.to << " but does not write it (json or ascii)\n";
      return kExitUsage;
    }
  }
  Diagnostics diagnostics;
  Result<SewerMap> map = read_map_with_condition(o.in, o.condition, diagnostics);
  print_diagnostics(diagnostics, c.err);
  if (!map.has_value()) {
    if (diagnostics.error_count() == 0) c.err << map.error().message << '\n';
    return exit_code_for(map.error());
  }
  Result<void> written = write_map(*map, o.out, format);
  if (!written.has_value()) {
    c.err << written.error().message << '\n';
    return exit_code_for(written.error());
  }
  c.out << "wrote " << o.out << " (" << map->manhole_count() << " manholes, " << map->pipe_count()
        << " pipes)\n";
  return kExitOk;
}

}  // namespace

void add_convert_command(CLI::App& app, Context& context) {
  // Shared with the callback, which CLI11 keeps after this function returns.
  auto options = std::make_shared<ConvertOptions>();
  CLI::App* cmd =
      app.add_subcommand("convert", "Convert a map between the formats sewerplan reads");
  cmd->add_option("in", options->in, "Map to read (.json, .sewer, SWMM .inp, ISYBAU .xml)")
      ->required();
  cmd->add_option("out", options->out, "Map to write; the extension gives the format")->required();
  cmd->add_option("--to", options->to,
                  "Output format when the extension does not tell: json, ascii (swmm and isybau "
                  "are read only)");
  add_condition_option(*cmd, options->condition);
  cmd->callback([options, &context] { context.exit_code = run(*options, context); });
}

}  // namespace sewerplan::cli
