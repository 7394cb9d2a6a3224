// SPDX-License-Identifier: MIT
// sewerplan simulate --map MAP --mission MISSION [--faults FILE | --random-faults SEED[,RATE]]
//                    [--recovery FILE] [--allow-push] [--log FILE] [--learnt FILE] [--quiet]
//                    [--can slcan:TTY|socketcan:IFACE | --replay CANDUMP.log] [--can-log FILE]
//                    [--condition FILE] [--risk MODE] [--risk-table FILE]
#include <filesystem>
#include <fstream>
#include <iostream>
#include <ostream>

#include <CLI/CLI.hpp>

#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/executor/event_json.h"
#include "sewerplan/executor/event_text.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"

#include "can_link.h"
#include "command.h"
#include "condition_options.h"
#include "motion_options.h"
#include "sim_setup.h"

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
  std::string learnt;  // what the robot learnt: read if it exists, written at the end
  bool quiet = false;
  CanLinkOptions can;  // the robot over a CAN bus (docs/can.md)
  MotionOptions motion;
  std::string condition;
  RiskOptions risk;
};

int run(const SimulateOptions& o, Context& c) {
  int exit_code = kExitOk;
  std::optional<SimWorld> world =
      load_sim_world(o.map, o.mission, o.faults, o.random_faults, c.err, exit_code, o.condition);
  if (!world) return exit_code;
  const SewerMap& map = world->map;
  Mission& mission = world->mission;
  Diagnostics risk_diagnostics;
  const Result<void> risk = apply_risk(o.risk, map, mission, risk_diagnostics, c.err);
  print_diagnostics(risk_diagnostics, c.err);
  if (!risk.has_value()) {
    if (risk_diagnostics.error_count() == 0) c.err << risk.error().message << '\n';
    return exit_code_for(risk.error());
  }
  const hal::FaultScenario& faults = world->faults;
  if (int code = attach_motion(o.motion, o.map, map, mission, c.err); code != kExitOk) {
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
  executor::ReplannerOptions replanner_options;
  replanner_options.planner.risk = o.risk.costs();
  executor::Replanner replanner(map, mission, replanner_options);
  if (!o.learnt.empty() && std::filesystem::exists(o.learnt)) {
    Diagnostics d;
    Result<executor::Learnt> learnt = executor::read_learnt(o.learnt, map, d);
    Result<void> learn =
        learnt.has_value() ? replanner.learn(*learnt) : Result<void>(learnt.error());
    if (!learn.has_value()) {
      c.err << learn.error().message << '\n';
      return exit_code_for(learn.error());
    }
  }
  std::unique_ptr<CanLink> can;
  if (!o.can.bus.empty() || !o.can.replay.empty()) {
    Result<std::unique_ptr<CanLink>> link = CanLink::open(o.can);
    if (!link.has_value()) {
      c.err << link.error().message << '\n';
      return exit_code_for(link.error());
    }
    can = std::move(*link);
  }
  hal::SimRobot sim(map, mission.profile, start_pose(replanner.progress().position), faults);
  hal::Robot& robot = can ? static_cast<hal::Robot&>(can->robot()) : sim;
  executor::Executor executor(map, replanner, robot, options);
  if (!o.log.empty()) executor.subscribe(executor::json_lines_writer(log_file));
  if (!o.quiet) executor.subscribe(executor::readable_writer(c.out));
  const executor::MissionReport report = executor.run();
  c.out << '\n' << report;
  if (can) can->write_summary(c.err);
  if (!o.learnt.empty()) {
    if (auto written = write_text_file(o.learnt, executor::learnt_json(replanner.learnt(), map));
        !written.has_value()) {
      c.err << written.error().message << '\n';
      return kExitIo;
    }
  }
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
  auto* random = cmd->add_option("--random-faults", options->random_faults,
                                 "Random faults: SEED[,RATE] (RATE obstacles per km, default 20)");
  random->excludes(faults);
  cmd->add_option("--recovery", options->recovery, "Recovery settings (JSON, docs/executor.md)");
  cmd->add_flag("--allow-push", options->allow_push,
                "Allow recovery phase 3, pushing an obstacle (off for real sewers)");
  cmd->add_option("--log", options->log, "Write the event log as JSON lines");
  cmd->add_option("--learnt", options->learnt,
                  "What the robot learnt (JSON): read if it exists, written at the end");
  cmd->add_flag("-q,--quiet", options->quiet, "Only the final report");
  auto* can =
      cmd->add_option("--can", options->can.bus,
                      "Run on a robot over CAN: slcan:TTY or socketcan:IFACE (docs/can.md)");
  auto* replay = cmd->add_option("--replay", options->can.replay,
                                 "Run on the replay of a candump log of an earlier --can run")
                     ->excludes(can);
  cmd->add_option("--can-log", options->can.log, "Record the CAN traffic as a candump log");
  faults->excludes(can)->excludes(replay);
  random->excludes(can)->excludes(replay);
  add_motion_options(*cmd, options->motion);
  add_condition_option(*cmd, options->condition);
  add_risk_options(*cmd, options->risk);
  cmd->callback([options, &context] { context.exit_code = run(*options, context); });
}

}  // namespace sewerplan::cli
