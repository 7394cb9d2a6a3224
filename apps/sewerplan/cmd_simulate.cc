// SPDX-License-Identifier: MIT
// sewerplan simulate --map MAP --mission MISSION [--faults FILE | --random-faults SEED[,RATE]]
//                    [--recovery FILE] [--allow-push] [--log FILE] [--quiet]
#include <fstream>
#include <iostream>
#include <ostream>

#include <CLI/CLI.hpp>

#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"

#include "command.h"
#include "motion_options.h"

namespace sewerplan::cli {
namespace {

struct SimulateOptions {
  std::string map;
  std::string mission;
  std::string faults;
  std::string random_faults;  // SEED[,RATE]
  std::string recovery;
  bool allow_push = false;
  std::string log;
  bool quiet = false;
  MotionOptions motion;
};

// The simulated robot starts where the mission puts it; in a pipe it faces the pipe's ends[1],
// as fusion assumes (fusion/fuse.h).
hal::SimPose start_pose(const domain::RobotPosition& p) {
  if (const auto* in = std::get_if<domain::InManhole>(&p)) return hal::InManhole{in->manhole};
  if (const auto* at = std::get_if<domain::AtSlot>(&p)) return hal::AtSlot{at->manhole, at->slot};
  const auto& pipe = std::get<domain::InPipe>(p);
  return hal::InPipe{pipe.pipe, pipe.offset_m, hal::Heading::kTowardsEnd1};
}

Result<hal::FaultScenario> faults_for(const SimulateOptions& o, const SewerMap& map,
                                      Diagnostics& diagnostics) {
  if (!o.faults.empty()) return hal::read_faults(o.faults, map, diagnostics);
  if (o.random_faults.empty()) return hal::FaultScenario{};
  // SEED[,RATE]: RATE obstacles per km of drivable pipe (default 20), a quarter as many danger
  // spots, and one malfunction per 2 hours.
  const auto comma = o.random_faults.find(',');
  hal::RandomFaultOptions r;
  try {
    r.seed = std::stoull(o.random_faults.substr(0, comma));
    r.obstacle_rate_per_km =
        comma == std::string::npos ? 20.0 : std::stod(o.random_faults.substr(comma + 1));
  } catch (const std::exception&) {
    return Error{ErrorCode::kInvalidArgument,
                 "--random-faults: expected SEED[,RATE], got '" + o.random_faults + "'"};
  }
  r.danger_rate_per_km = r.obstacle_rate_per_km / 4;
  r.malfunction_rate_per_hour = 0.5;
  return hal::random_faults(map, r);
}

int run(const SimulateOptions& o, Context& c) {
  Diagnostics diagnostics;
  Result<SewerMap> map = read_map(o.map, diagnostics);
  Result<Mission> mission =
      map.has_value() ? read_mission(o.mission, *map, diagnostics) : Result<Mission>(map.error());
  Result<hal::FaultScenario> faults = mission.has_value()
                                          ? faults_for(o, *map, diagnostics)
                                          : Result<hal::FaultScenario>(mission.error());
  print_diagnostics(diagnostics, c.err);
  if (!faults.has_value()) {
    if (diagnostics.error_count() == 0) c.err << faults.error().message << '\n';
    return exit_code_for(faults.error());
  }
  if (int code = attach_motion(o.motion, o.map, *map, *mission, c.err); code != kExitOk) {
    return code;
  }
  executor::ExecutorOptions options;
  if (!o.recovery.empty()) {
    Result<std::string> text = read_text_file(o.recovery);
    Result<executor::RecoveryConfig> recovery =
        text.has_value() ? executor::read_recovery_json(*text, o.recovery)
                         : Result<executor::RecoveryConfig>(text.error());
    if (!recovery.has_value()) {
      c.err << recovery.error().message << '\n';
      return exit_code_for(recovery.error());
    }
    options.recovery = *recovery;
  }
  if (o.allow_push) options.recovery.push_allowed = true;
  std::ofstream log_file;
  if (!o.log.empty()) {
    log_file.open(o.log);
    if (!log_file) {
      c.err << o.log << ": cannot write the event log\n";
      return kExitIo;
    }
  }
  executor::EventLog log(o.log.empty() ? nullptr : &log_file, o.quiet ? nullptr : &c.out);
  executor::Replanner replanner(*map, *mission);
  hal::SimRobot robot(*map, mission->profile, start_pose(replanner.progress().position), *faults);
  const executor::MissionReport report =
      executor::Executor(*map, replanner, robot, options, log).run();
  c.out << '\n' << report;
  return report.outcome == executor::MissionReport::Outcome::kEnded ? kExitOk : kExitNoPlan;
}

}  // namespace

void add_simulate_command(CLI::App& app, Context& context) {
  // Shared with the callback, which CLI11 keeps after this function returns.
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Run a mission on the simulated robot, with hidden faults, recovery and replanning");
  cmd->add_option("--map", options->map, "Map file")->required();
  cmd->add_option("--mission", options->mission, "Mission file (.json)")->required();
  auto* faults =
      cmd->add_option("--faults", options->faults, "Fault scenario (docs/simulation.md)");
  cmd->add_option("--random-faults", options->random_faults,
                  "Random faults: SEED[,RATE] (RATE obstacles per km, default 20)")
      ->excludes(faults);
  cmd->add_option("--recovery", options->recovery, "Recovery settings (JSON, docs/executor.md)");
  cmd->add_flag("--allow-push", options->allow_push,
                "Allow recovery phase 3, pushing an obstacle (off for real sewers)");
  cmd->add_option("--log", options->log, "Write the event log as JSON lines");
  cmd->add_flag("-q,--quiet", options->quiet, "Only the final report");
  add_motion_options(*cmd, options->motion);
  cmd->callback([options, &context] { context.exit_code = run(*options, context); });
}

}  // namespace sewerplan::cli
