// SPDX-License-Identifier: MIT
// sewerplan merge-measurements --map MAP A.json B.json ... -o merged.json [--corrected-map
// OUT.json]
//
// Pools what several missions measured of one map (core/map_measurements.h: lengths and positions
// by inverse variance, every observation kept) into one measurements file with its discrepancies
// derived again; with --corrected-map, also the corrected map and its discrepancy report. A file of
// another map is an error naming it (exit 1); a file that cannot be read or written, exit 3.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "sewerplan/core/measurements_json.h"
#include "sewerplan/core/output_file.h"

#include "command.h"
#include "corrected_map_output.h"
#include "json_output.h"
#include "map_input.h"

namespace sewerplan::cli {
namespace {

struct MergeOptions {
  std::string map;
  std::string gis_fields;
  std::vector<std::string> inputs;
  std::string output;
  std::string corrected_map;
  bool json = false;
};

int run(const MergeOptions& o, Context& c) {
  if (!o.corrected_map.empty()) {
    if (Result<void> ok = check_corrected_map_target(o.corrected_map, o.map); !ok.has_value()) {
      return fail(c, o.json, ok.error());
    }
  }
  Diagnostics diagnostics;
  Result<SewerMap> map = read_input_map({o.map, o.gis_fields}, diagnostics);
  if (!map.has_value()) return fail(c, o.json, map.error(), diagnostics);
  std::optional<MapMeasurements> merged;
  for (const std::string& input : o.inputs) {
    Result<MapMeasurements> m = read_measurements(input, *map, diagnostics);
    if (!m.has_value()) return fail(c, o.json, m.error(), diagnostics);
    if (!merged) {
      merged = std::move(*m);
      continue;
    }
    Result<MapMeasurements> both = merge(*merged, *m);
    if (!both.has_value()) {
      return fail(c, o.json, Error{both.error().code, input + ": " + both.error().message});
    }
    merged = std::move(*both);
  }
  print_diagnostics(diagnostics, c.err);
  std::ostream& text = o.json ? c.err : c.out;
  if (!o.corrected_map.empty()) {
    Diagnostics written;
    Result<void> w = write_corrected_map(o.corrected_map, o.map, *map, *merged, text, written);
    print_diagnostics(written, c.err);
    if (!w.has_value()) return fail(c, o.json, w.error());
  } else {
    merged->discrepancies = discrepancies(*merged, *map);
  }
  if (Result<void> w = write_text_file(o.output, measurements_json(*merged, *map));
      !w.has_value()) {
    return fail(c, o.json, w.error());
  }
  text << "merged " << o.inputs.size() << " files (" << merged->sources.size() << " missions) into "
       << o.output << ": " << merged->pipes.size() << " pipes, " << merged->manholes.size()
       << " manholes, " << merged->discrepancies.size() << " discrepancies\n";
  if (o.json) {
    Json j = Json::object();
    j["output"] = o.output;
    j["sources"] = merged->sources.size();
    j["pipes"] = merged->pipes.size();
    j["manholes"] = merged->manholes.size();
    j["discrepancies"] = merged->discrepancies.size();
    if (!o.corrected_map.empty()) j["corrected_map"] = o.corrected_map;
    print_json(c.out, j);
  }
  return kExitOk;
}

}  // namespace

void add_merge_measurements_command(CLI::App& app, Context& context) {
  auto options = std::make_shared<MergeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "merge-measurements",
      "Pool several missions' measurements of one map (simulate --corrected-map writes them)");
  cmd->add_option("--map", options->map, "Map file the measurements are of")->required();
  add_gis_fields_option(*cmd, options->gis_fields);
  cmd->add_option("inputs", options->inputs, "Measurements files (.measurements.json)")->required();
  cmd->add_option("-o,--output", options->output, "The merged measurements file")->required();
  cmd->add_option("--corrected-map", options->corrected_map,
                  "Also write the corrected map (JSON; for an ISYBAU map also OUT.xml, ISYBAU) and "
                  "OUT.discrepancies.json beside it");
  cmd->add_flag("--json", options->json, "Print a JSON summary (docs/cli.md)");
  cmd->callback([options, &context] { context.exit_code = run(*options, context); });
}

}  // namespace sewerplan::cli
