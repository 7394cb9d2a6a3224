// SPDX-License-Identifier: MIT
// sewerplan generate --manholes N [--seed S] [--topology tree|meshed] ... -o FILE
#include <ostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/domain/mission_generator.h"

#include "command.h"
#include "crs_option.h"
#include "json_output.h"

namespace sewerplan::cli {
namespace {

struct GenerateOptions {
  GeneratorOptions generator;
  std::string topology = "tree";
  std::string out;
  std::size_t mission_tasks = 0;
  std::string mission_out;
  std::string profile = "makro-plus";
  std::string spread = "uniform";
  bool json = false;
  std::string crs;
};

// A seeded mission on the generated map (domain/mission_generator.h), written as JSON; `report`
// receives what --json says about it.
int write_mission(const SewerMap& map, const GenerateOptions& o, Context& c, Json& report) {
  const auto spread = domain::mission_spread_from_string(o.spread);  // checked in run()
  Result<Mission> mission = domain::generate_mission(map, {.tasks = o.mission_tasks,
                                                           .seed = o.generator.seed,
                                                           .profile = o.profile,
                                                           .spread = *spread});
  if (!mission.has_value()) return fail(c, o.json, mission.error());
  std::ostringstream text;
  write_mission_json(*mission, map, text);
  if (Result<void> written = write_text_file(o.mission_out, text.str()); !written.has_value()) {
    return fail(c, o.json, written.error());
  }
  report = {{"wrote", o.mission_out},
            {"tasks", o.mission_tasks},
            {"profile", o.profile},
            {"spread", o.spread}};
  if (!o.json) {
    c.out << "wrote " << o.mission_out << " (" << o.mission_tasks << " tasks for " << o.profile
          << ")\n";
  }
  return kExitOk;
}

int run(GenerateOptions& o, Context& c) {
  auto topology = topology_from_string(o.topology);
  if (!topology) {
    return usage_error(
        c, o.json, "--topology: unknown topology '" + o.topology + "' (" + topology_names() + ")");
  }
  o.generator.topology = *topology;
  if (!domain::mission_spread_from_string(o.spread)) {
    return usage_error(c, o.json,
                       "--mission-spread: unknown spread '" + o.spread + "' (" +
                           domain::mission_spread_names() + ")");
  }
  if ((o.mission_tasks > 0 || !o.mission_out.empty()) &&
      (o.mission_out.empty() || o.mission_tasks == 0)) {
    return usage_error(c, o.json, "--mission-tasks and --mission-out go together");
  }
  // The map's format by -o's extension, before the network is made (a large one takes minutes).
  if (Result<MapFormat> format = map_output_format(o.out); !format.has_value()) {
    return fail(c, o.json, format.error());
  }
  Result<SewerMap> map = generate_network(o.generator);
  if (map.has_value()) map = apply_crs_option(std::move(*map), o.crs);
  if (!map.has_value()) return fail(c, o.json, map.error());
  Result<void> written = write_map(*map, o.out);
  if (!written.has_value()) return fail(c, o.json, written.error());
  Json report = {{"map",
                  {{"wrote", o.out},
                   {"name", map->name()},
                   {"manholes", map->manhole_count()},
                   {"pipes", map->pipe_count()},
                   {"topology", to_string(*topology)},
                   {"seed", o.generator.seed}}}};
  if (!o.json) {
    c.out << "wrote " << o.out << " (" << map->manhole_count() << " manholes, " << map->pipe_count()
          << " pipes, " << to_string(*topology) << ", seed " << o.generator.seed << ")\n";
  }
  if (o.mission_tasks > 0) {
    Json mission;
    if (int code = write_mission(*map, o, c, mission); code != kExitOk) return code;
    report["mission"] = std::move(mission);
  }
  if (o.json) print_json(c.out, report);
  return kExitOk;
}

}  // namespace

void add_generate_command(CLI::App& app, Context& context) {
  // Shared with the callback, which CLI11 keeps after this function returns.
  auto o = std::make_shared<GenerateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "generate",
      "Generate a seeded synthetic sewer network (the same arguments give the same map)");
  cmd->add_option("--manholes,-n", o->generator.manholes, "Number of manholes, 10 to 1000000")
      ->required();
  cmd->add_option("--seed,-s", o->generator.seed, "Random seed")->capture_default_str();
  cmd->add_option("--topology,-t", o->topology, "tree or meshed")->capture_default_str();
  cmd->add_option("--mesh-fraction", o->generator.mesh_fraction,
                  "meshed: share of the street lattice's other edges added as loops, 0 to 1")
      ->capture_default_str();
  cmd->add_option("--exit-fraction", o->generator.exit_fraction, "Share of manholes that are exits")
      ->capture_default_str();
  cmd->add_option("--undrivable-fraction", o->generator.undrivable_pipe_fraction,
                  "Share of pipes outside 0.30-0.60 m")
      ->capture_default_str();
  cmd->add_option("--high-step-fraction", o->generator.high_step_fraction,
                  "Share of incoming pipe ends more than 0.30 m above the manhole floor")
      ->capture_default_str();
  cmd->add_option("--findings-per-km", o->generator.findings_per_km,
                  "Inspection findings per km of pipe, for risk-aware planning (docs/planning.md)")
      ->capture_default_str();
  cmd->add_option("--name", o->generator.name,
                  "Map name (default generated-<topology>-<n>-<seed>)");
  cmd->add_option("--out,-o", o->out, "Output map (.json or .sewer)")->required();
  cmd->add_option("--mission-tasks", o->mission_tasks,
                  "Also write a seeded mission with this many tasks");
  cmd->add_option("--mission-spread", o->spread,
                  "Where its tasks lie: uniform (all over the robot's range), clustered (around "
                  "a random place in it) or near-exit (near the start)")
      ->capture_default_str();
  cmd->add_option("--mission-out", o->mission_out, "Where to write that mission (.json)");
  cmd->add_option("--profile", o->profile, "The mission's robot profile")->capture_default_str();
  add_crs_option(*cmd, o->crs);
  cmd->add_flag("--json", o->json, "Print what was written as JSON");
  cmd->callback([o, &context] { context.exit_code = run(*o, context); });
}

}  // namespace sewerplan::cli
