// SPDX-License-Identifier: MIT
// sewerplan motion precompute --map MAP [--profile P] [--seed S] [--iterations N]
//                              [--time-limit SECONDS] [-o FILE] [-q]
#include <iomanip>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/passage_motion.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/fusion/passage_precompute.h"
#include "sewerplan/modules/ompl.h"

#include "command.h"
#include "json_output.h"
#include "map_input.h"
#include "profile_option.h"

namespace sewerplan::cli {
namespace {

struct PrecomputeOptions {
  std::string map;
  std::string gis_fields;      // --gis-fields
  std::string map_positional;  // deprecated: motion precompute MAP
  std::string profile = "makro-1.1";
  std::uint32_t seed = 1;
  std::uint32_t iterations = fusion::TurnPlannerOptions{}.max_iterations;
  double time_limit_s = 0;  // 0: none
  std::string out;
  bool quiet = false;
  bool json = false;
};

int precompute(const PrecomputeOptions& o, Context& c) {
  int exit_code = kExitOk;
  const std::optional<std::string> path =
      map_path(o.map, o.map_positional, "motion precompute", c, o.json, exit_code);
  if (!path) return exit_code;
  // OMPL's planner from the OMPL module: this command is the only one that loads it.
  const Result<const fusion::HeadPathPlanner*> ompl = modules::ompl_head_path_planner();
  if (!ompl.has_value()) {
    return fail(c, o.json, Error{ompl.error().code, "motion precompute: " + ompl.error().message});
  }
  Diagnostics diagnostics;
  Result<SewerMap> map = read_input_map({*path, o.gis_fields}, diagnostics);
  if (!map.has_value()) return fail(c, o.json, map.error(), diagnostics);
  print_diagnostics(diagnostics, c.err);
  Result<RobotProfile> profile = load_profile_option(o.profile);
  if (!profile.has_value()) return fail(c, o.json, profile.error());
  SteadyClock clock;
  std::size_t last_tenth = 0;
  fusion::PrecomputeOptions options{.head_paths = *ompl,
                                    .planner = {.seed = o.seed, .max_iterations = o.iterations}};
  // The same stop condition as every planner's (core/stop_condition.h): no table when it fires.
  if (o.time_limit_s > 0) options.stop = StopCondition::after_seconds(clock, o.time_limit_s);
  if (!o.quiet) {
    options.progress = [&](std::size_t done, std::size_t total) {
      const std::size_t tenth = done * 10 / total;
      if (tenth == last_tenth) return;
      last_tenth = tenth;
      c.err << "motion: " << done << " of " << total << " manholes\n";
    };
  }
  Result<fusion::PrecomputeResult> r =
      fusion::precompute_passage_motion(*map, *profile, options, clock);
  if (!r.has_value()) return fail(c, o.json, r.error());
  const std::string out = o.out.empty() ? default_motion_path(*path).string() : o.out;
  std::ostringstream text;
  write_passage_motion_json(r->table, *map, text);
  if (Result<void> written = write_text_file(out, text.str()); !written.has_value()) {
    return fail(c, o.json, written.error());
  }
  const fusion::PrecomputeStatistics& s = r->statistics;
  if (o.json) {
    print_json(c.out, {{"wrote", out},
                       {"profile", profile->name},
                       {"seed", o.seed},
                       {"iterations", o.iterations},
                       {"passages", s.passages},
                       {"geometries", s.distinct_geometries},
                       {"feasible", s.feasible},
                       {"rules_allow", s.rules_allow},
                       {"rejected_by_motion_rules_allow", s.rejected_by_motion_rules_allow},
                       {"allowed_by_motion_rules_reject", s.allowed_by_motion_rules_reject},
                       {"time_s", s.time_s}});
    return kExitOk;
  }
  c.out << "motion: " << s << "\n"
        << "  profile " << profile->name << ", seed " << o.seed << ", " << o.iterations
        << " iterations per geometry\n"
        << "  rules allow " << s.rules_allow << " of " << s.passages
        << " passages, the motion planner " << s.feasible << "\n"
        << "  wrote " << out << '\n';
  return kExitOk;
}

}  // namespace

void add_motion_command(CLI::App& app, Context& context) {
  CLI::App* motion = app.add_subcommand("motion", "Plan the robot's motion through manholes");
  motion->require_subcommand(1);
  // Shared with the callback, which CLI11 keeps after this function returns.
  auto o = std::make_shared<PrecomputeOptions>();
  CLI::App* cmd = motion->add_subcommand(
      "precompute",
      "Plan every manhole passage of a map with OMPL and write MAP.motion.json beside it");
  cmd->add_option("--map", o->map, "Map file");
  add_gis_fields_option(*cmd, o->gis_fields);
  cmd->add_option("map", o->map_positional, "Deprecated: use --map")->group("");
  cmd->add_option("--profile", o->profile, "Robot profile: makro-1.1, makro-plus or a JSON file")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the motion planner")->capture_default_str();
  cmd->add_option("--iterations", o->iterations,
                  "Planner iterations per passage geometry before it counts as infeasible")
      ->capture_default_str();
  cmd->add_option("--time-limit", o->time_limit_s,
                  "Seconds before the precompute stops without a table (exit 5; 0: none)")
      ->check(CLI::Range(0.0, 86400.0))
      ->capture_default_str();
  cmd->add_option("--out,-o", o->out, "Where to write the table (default: MAP.motion.json)");
  cmd->add_flag("--quiet,-q", o->quiet, "No progress on standard error");
  cmd->add_flag("--json", o->json, "Print the summary as JSON");
  cmd->callback([o, &context] { context.exit_code = precompute(*o, context); });
}

}  // namespace sewerplan::cli
