// SPDX-License-Identifier: MIT
// sewerplan convert --map IN -o OUT [--to json|ascii]
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "sewerplan/core/map_io.h"

#include "command.h"
#include "condition_options.h"
#include "crs_option.h"
#include "json_output.h"
#include "map_input.h"

namespace sewerplan::cli {
namespace {

struct ConvertOptions {
  std::string map;
  std::string gis_fields;  // --gis-fields
  std::string out;
  std::vector<std::string> positional;  // OUT, or (deprecated) IN OUT
  bool json = false;
  std::string to;
  std::string condition;
  std::string crs;
};

int run(const ConvertOptions& o, Context& c) {
  // convert --map IN -o OUT (or --map IN OUT); the old convert IN OUT still works.
  std::vector<std::string> rest = o.positional;
  std::string in_positional;
  if (o.map.empty() && !rest.empty()) {
    in_positional = rest.front();
    rest.erase(rest.begin());
  }
  int exit_code = kExitOk;
  const std::optional<std::string> in =
      map_path(o.map, in_positional, "convert", c, o.json, exit_code);
  if (!in) return exit_code;
  if (rest.size() > 1 || (!rest.empty() && !o.out.empty())) {
    return usage_error(c, o.json, "convert: give the output once, with --out");
  }
  const std::string out = o.out.empty() ? (rest.empty() ? std::string() : rest.front()) : o.out;
  if (out.empty()) return usage_error(c, o.json, "convert: --out is required");
  std::optional<MapFormat> format;
  if (!o.to.empty()) {
    format = map_format_from_name(o.to);
    if (!format) {
      return usage_error(c, o.json, "--to: unknown format '" + o.to + "' (json or ascii)");
    }
    if (!is_writable(*format)) {
      return usage_error(
          c, o.json, "--to: sewerplan reads " + o.to + " but does not write it (json or ascii)");
    }
  }
  // The output's format, before the map is read.
  if (Result<MapFormat> checked = map_output_format(out, format); !checked.has_value()) {
    return fail(c, o.json, checked.error());
  }
  Diagnostics diagnostics;
  Result<SewerMap> map = read_map_with_condition({*in, o.gis_fields}, o.condition, diagnostics);
  if (map.has_value()) map = apply_crs_option(std::move(*map), o.crs);
  if (!map.has_value()) return fail(c, o.json, map.error(), diagnostics);
  print_diagnostics(diagnostics, c.err);
  Result<void> written = write_map(*map, out, format);
  if (!written.has_value()) return fail(c, o.json, written.error());
  if (o.json) {
    print_json(c.out, {{"wrote", out},
                       {"manholes", map->manhole_count()},
                       {"pipes", map->pipe_count()},
                       {"crs", map->crs() ? Json(map->crs()->to_string()) : Json()},
                       {"findings", map->finding_count()}});
  } else {
    c.out << "wrote " << out << " (" << map->manhole_count() << " manholes, " << map->pipe_count()
          << " pipes)\n";
  }
  return kExitOk;
}

}  // namespace

void add_convert_command(CLI::App& app, Context& context) {
  // Shared with the callback, which CLI11 keeps after this function returns.
  auto options = std::make_shared<ConvertOptions>();
  CLI::App* cmd =
      app.add_subcommand("convert", "Convert a map between the formats sewerplan reads");
  cmd->add_option("--map", options->map, "Map to read (.json, .sewer, SWMM .inp, ISYBAU .xml)");
  add_gis_fields_option(*cmd, options->gis_fields);
  cmd->add_option("--out,-o", options->out, "Map to write; the extension gives the format");
  cmd->add_option("files", options->positional, "OUT (or, deprecated, IN OUT)")
      ->expected(0, 2)
      ->group("");
  cmd->add_flag("--json", options->json, "Print what was written as JSON");
  cmd->add_option("--to", options->to,
                  "Output format when the extension does not tell: json, ascii (swmm and isybau "
                  "are read only)");
  add_condition_option(*cmd, options->condition);
  add_crs_option(*cmd, options->crs);
  cmd->callback([options, &context] { context.exit_code = run(*options, context); });
}

}  // namespace sewerplan::cli
