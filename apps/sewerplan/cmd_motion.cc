// SPDX-License-Identifier: MIT
// sewerplan motion precompute MAP [--profile P] [--seed S] [--iterations N] [-o FILE] [-q]
#include <iomanip>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/passage_motion.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/fusion/passage_precompute.h"

#include "command.h"

namespace sewerplan::cli {
namespace {

struct PrecomputeOptions {
  std::string map;
  std::string profile = "makro-1.1";
  std::uint32_t seed = 1;
  std::uint32_t iterations = fusion::TurnPlannerOptions{}.max_iterations;
  std::string out;
  bool quiet = false;
};

int precompute(const PrecomputeOptions& o, Context& c) {
  if (!fusion::motion_planning_available()) {
    c.err << "motion precompute: this build of sewerplan has no OMPL (built with "
             "SEWERPLAN_WITH_OMPL=OFF), so it cannot plan manhole motions; planning uses the "
             "angle and step rules\n";
    return kExitInvalidInput;
  }
  Diagnostics diagnostics;
  Result<SewerMap> map = read_map(o.map, diagnostics);
  print_diagnostics(diagnostics, c.err);
  if (!map.has_value()) {
    if (diagnostics.error_count() == 0) c.err << map.error().message << '\n';
    return exit_code_for(map.error());
  }
  Result<RobotProfile> profile = load_profile(o.profile);
  if (!profile.has_value()) {
    c.err << profile.error().message << '\n';
    return kExitInvalidInput;
  }
  SteadyClock clock;
  std::size_t last_tenth = 0;
  fusion::PrecomputeOptions options{.planner = {.seed = o.seed, .max_iterations = o.iterations}};
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
  if (!r.has_value()) {
    c.err << r.error().message << '\n';
    return exit_code_for(r.error());
  }
  const std::string out = o.out.empty() ? default_motion_path(o.map).string() : o.out;
  std::ostringstream text;
  write_passage_motion_json(r->table, *map, text);
  if (Result<void> written = write_text_file(out, text.str()); !written.has_value()) {
    c.err << written.error().message << '\n';
    return exit_code_for(written.error());
  }
  const fusion::PrecomputeStatistics& s = r->statistics;
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
  cmd->add_option("map", o->map, "Map file")->required();
  cmd->add_option("--profile", o->profile, "Robot profile: makro-1.1, makro-plus or a JSON file")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the motion planner")->capture_default_str();
  cmd->add_option("--iterations", o->iterations,
                  "Planner iterations per passage geometry before it counts as infeasible")
      ->capture_default_str();
  cmd->add_option("--out,-o", o->out, "Where to write the table (default: MAP.motion.json)");
  cmd->add_flag("--quiet,-q", o->quiet, "No progress on standard error");
  cmd->callback([o, &context] { context.exit_code = precompute(*o, context); });
}

}  // namespace sewerplan::cli
