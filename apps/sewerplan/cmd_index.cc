// SPDX-License-Identifier: MIT
// sewerplan index build --map MAP [--profile P | --mission M] [--motion FILE | --no-motion]
//                       [--condition FILE] [--time-limit SECONDS] [-o FILE] [-q] [--json]
// The map's routing index for a robot (domain/route_index.h, issue 35), kept beside the map as
// MAP.route-index.bin, where `plan` and `simulate` find it (route_index_options.h).
#include <iomanip>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/output_file.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/domain/route_index.h"

#include "command.h"
#include "condition_options.h"
#include "json_output.h"
#include "map_input.h"
#include "motion_options.h"
#include "profile_option.h"

namespace sewerplan::cli {
namespace {

struct BuildOptions {
  std::string map;
  std::string gis_fields;
  std::string profile = "makro-1.1";
  std::string mission;  // the profile from this mission's, as plan and simulate take it
  std::string condition;
  MotionOptions motion;
  double time_limit_s = 0;  // 0: none
  std::string out;
  bool quiet = false;
  bool json = false;
};

int build(const BuildOptions& o, Context& c) {
  Diagnostics diagnostics;
  Result<SewerMap> map = read_map_with_condition({o.map, o.gis_fields}, o.condition, diagnostics);
  if (!map.has_value()) return fail(c, o.json, map.error(), diagnostics);
  print_diagnostics(diagnostics, c.err);
  Result<RobotProfile> profile = Error{ErrorCode::kInvalidProfile, "no profile"};
  if (!o.mission.empty()) {
    Diagnostics read;
    Result<Mission> mission = read_mission(o.mission, *map, read);
    if (!mission.has_value()) return fail(c, o.json, mission.error(), read);
    print_diagnostics(read, c.err);
    profile = mission->profile;
  } else {
    profile = load_profile_option(o.profile);
  }
  if (!profile.has_value()) return fail(c, o.json, profile.error());
  // The index is of the moves the compile has: with the motion table plan would use.
  Mission robot;
  robot.profile = *profile;
  std::ostringstream motion_note;
  if (auto motion = attach_motion_table(o.motion, o.map, *map, robot, motion_note);
      !motion.has_value()) {
    return fail(c, o.json, motion.error());
  }
  if (!o.quiet && !o.json) c.err << motion_note.str();
  SteadyClock clock;
  StopCondition stop;
  if (o.time_limit_s > 0) stop = StopCondition::after_seconds(clock, o.time_limit_s);
  const double start_s = clock.now_s();
  Result<domain::RouteIndex> index =
      domain::RouteIndex::build(*map, robot.profile, robot.passage_motion, stop);
  if (!index.has_value()) return fail(c, o.json, index.error());
  const double build_s = clock.now_s() - start_s;
  const std::string out = o.out.empty() ? domain::default_route_index_path(o.map).string() : o.out;
  const std::string bytes = index->bytes();
  if (Result<void> written = write_text_file(out, bytes); !written.has_value()) {
    return fail(c, o.json, written.error());
  }
  const domain::RouteIndexStatistics& s = index->statistics();
  if (o.json) {
    print_json(c.out, {{"wrote", out},
                       {"profile", profile->name},
                       {"fingerprint", domain::fingerprint_hex(s.fingerprint)},
                       {"nodes", s.nodes},
                       {"moves", s.moves},
                       {"shortcuts", s.shortcuts},
                       {"bytes", bytes.size()},
                       {"time_s", build_s}});
    return kExitOk;
  }
  c.out << std::fixed << std::setprecision(2) << "index: " << s.nodes << " positions, " << s.moves
        << " moves, " << s.shortcuts << " shortcuts; " << build_s << " s\n"
        << "  profile " << profile->name << ", fingerprint "
        << domain::fingerprint_hex(s.fingerprint) << "\n"
        << "  wrote " << out << " (" << bytes.size() << " bytes)\n";
  return kExitOk;
}

}  // namespace

void add_index_command(CLI::App& app, Context& context) {
  CLI::App* index = app.add_subcommand("index", "Build a map's routing index for a robot");
  index->require_subcommand(1);
  // Shared with the callback, which CLI11 keeps after this function returns.
  auto o = std::make_shared<BuildOptions>();
  CLI::App* cmd = index->add_subcommand(
      "build", "Build the map's routing index and write MAP.route-index.bin beside it");
  cmd->add_option("--map", o->map, "Map file")->required();
  add_gis_fields_option(*cmd, o->gis_fields);
  CLI::Option* profile = cmd->add_option("--profile", o->profile,
                                         "Robot profile: makro-1.1, makro-plus or a JSON file")
                             ->capture_default_str();
  cmd->add_option("--mission", o->mission,
                  "Take the robot profile from this mission (the one plan and simulate will use)")
      ->excludes(profile);
  add_motion_options(*cmd, o->motion);
  add_condition_option(*cmd, o->condition);
  cmd->add_option("--time-limit", o->time_limit_s,
                  "Seconds before the build stops without an index (exit 5; 0: none)")
      ->check(CLI::Range(0.0, 86400.0))
      ->capture_default_str();
  cmd->add_option("--out,-o", o->out, "Where to write the index (default: MAP.route-index.bin)");
  cmd->add_flag("--quiet,-q", o->quiet, "No note of the motion table on standard error");
  cmd->add_flag("--json", o->json, "Print the summary as JSON");
  cmd->callback([o, &context] { context.exit_code = build(*o, context); });
}

}  // namespace sewerplan::cli
