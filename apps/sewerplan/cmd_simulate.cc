// SPDX-License-Identifier: MIT
// sewerplan simulate --map MAP --mission MISSION [--faults FILE | --random-faults SEED[,RATE]]
//                    [--recovery FILE] [--allow-push] [--log FILE] [--learnt FILE] [--quiet]
//                    [--can slcan:TTY|socketcan:IFACE | --replay CANDUMP.log] [--can-log FILE]
//                    [--condition FILE] [--risk MODE] [--risk-table FILE]
//                    [--corrected-map OUT.json]
//                    [--world-errors NAME|SPEC] [--world-seed N]
#include <cerrno>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <optional>
#include <ostream>
#include <thread>

#include <CLI/CLI.hpp>

#include "sewerplan/core/map_io.h"
#include "sewerplan/core/measurements_json.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/executor/event_json.h"
#include "sewerplan/executor/event_text.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/executor/measuring.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"
#include "sewerplan/hal/world_errors.h"

#include "can_link.h"
#include "command.h"
#include "condition_options.h"
#include "corrected_map_output.h"
#include "json_output.h"
#include "map_input.h"
#include "motion_options.h"
#include "route_index_options.h"
#include "sim_setup.h"
#include <poll.h>
#include <unistd.h>

namespace sewerplan::cli {
namespace {

struct SimulateOptions {
  std::string map;
  std::string gis_fields;  // --gis-fields
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
  RouteIndexOptions route_index;
  std::string condition;
  RiskOptions risk;
  bool json = false;
  // The corrected map, and beside it OUT.discrepancies.json and OUT.measurements.json.
  std::string corrected_map;
  std::string world_errors = "none";  // the true world the simulated robot drives
  std::uint64_t world_seed = 1;
  bool world_given = false;  // --world-errors or --world-seed on the command line
};

// Ctrl-C (SIGINT) and SIGTERM halt the mission (Executor::halt: the robot's emergency stop, the
// log closed, exit 4) instead of killing the process with the robot driving. The handler only
// writes a byte to a pipe (async-signal-safe); a watcher thread reads it and calls halt(). It is
// installed before the map is read: a signal that comes before the executor exists (while the map
// loads) halts it as soon as it is attached, so the report and the log are still written. A halt
// while a plan is computed cancels the planner (Executor::halt is its cancel flag).
int g_signal_pipe_write = -1;

extern "C" void on_halt_signal(int) {
  const int saved = errno;
  if (g_signal_pipe_write >= 0) {
    const char byte = 'h';
    [[maybe_unused]] const ssize_t n = ::write(g_signal_pipe_write, &byte, 1);
  }
  errno = saved;
}

class HaltOnSignal {
 public:
  HaltOnSignal() {
    if (::pipe(fds_) != 0) return;
    g_signal_pipe_write = fds_[1];
    struct sigaction action {};
    action.sa_handler = on_halt_signal;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &old_int_);
    sigaction(SIGTERM, &action, &old_term_);
    watcher_ = std::thread([this] {
      pollfd fd{.fd = fds_[0], .events = POLLIN, .revents = 0};
      while (true) {
        if (::poll(&fd, 1, -1) < 0) {
          if (errno == EINTR) continue;
          return;
        }
        char byte = 0;
        if (::read(fds_[0], &byte, 1) != 1 || byte == 'q') return;
        const std::lock_guard lock(mutex_);
        signalled_ = true;
        if (executor_ != nullptr) executor_->halt();
      }
    });
  }
  // From now on a signal halts `executor`; one that came before halts it now.
  void attach(executor::Executor& executor) {
    const std::lock_guard lock(mutex_);
    executor_ = &executor;
    if (signalled_) executor.halt();
  }
  // Before the executor is destroyed.
  void detach() {
    const std::lock_guard lock(mutex_);
    executor_ = nullptr;
  }
  HaltOnSignal(const HaltOnSignal&) = delete;
  HaltOnSignal& operator=(const HaltOnSignal&) = delete;
  ~HaltOnSignal() {
    if (!watcher_.joinable()) return;
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
    g_signal_pipe_write = -1;
    const char quit = 'q';
    [[maybe_unused]] const ssize_t n = ::write(fds_[1], &quit, 1);
    watcher_.join();
    ::close(fds_[0]);
    ::close(fds_[1]);
  }

 private:
  int fds_[2] = {-1, -1};
  std::mutex mutex_;
  bool signalled_ = false;                  // under mutex_
  executor::Executor* executor_ = nullptr;  // under mutex_
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
  std::thread watcher_;
};

int run(const SimulateOptions& o, Context& c) {
  if (!o.corrected_map.empty()) {
    if (Result<void> ok = check_corrected_map_target(o.corrected_map, o.map); !ok.has_value()) {
      return fail(c, o.json, ok.error());
    }
  }
  HaltOnSignal halt_on_signal;
  // Over CAN the robot drives the node's world (sim-node takes them), or the real one; a replay
  // replays the recorded run's.
  if (o.world_given && !o.can.bus.empty()) {
    return usage_error(c, o.json,
                       "sewerplan simulate: --world-errors and --world-seed are the node's with "
                       "--can: give them to sim-node (docs/can.md)");
  }
  if (o.world_given && !o.can.replay.empty()) {
    return usage_error(c, o.json,
                       "sewerplan simulate: --world-errors and --world-seed are not for --replay: "
                       "the log holds the recorded run's observations");
  }
  if (std::string why = o.risk.strand_risk_error(); !why.empty())
    return usage_error(c, o.json, why);
  const Result<hal::WorldErrorProfile> world_errors = hal::parse_world_errors(o.world_errors);
  if (!world_errors.has_value()) return fail(c, o.json, world_errors.error());
  Diagnostics diagnostics;
  Result<SimWorld> world = read_sim_world({o.map, o.gis_fields}, o.mission, o.faults,
                                          o.random_faults, diagnostics, o.condition);
  if (!world.has_value()) return fail(c, o.json, world.error(), diagnostics);
  print_diagnostics(diagnostics, c.err);
  const SewerMap& map = world->map;
  Mission& mission = world->mission;
  Diagnostics risk_diagnostics;
  const Result<void> risk = apply_risk(o.risk, map, mission, risk_diagnostics, c.err);
  if (!risk.has_value()) return fail(c, o.json, risk.error(), risk_diagnostics);
  print_diagnostics(risk_diagnostics, c.err);
  const hal::FaultScenario& faults = world->faults;
  if (auto motion = attach_motion_table(o.motion, o.map, map, mission, c.err);
      !motion.has_value()) {
    return fail(c, o.json, motion.error());
  }
  executor::ExecutorOptions options;
  if (!o.recovery.empty()) {
    Result<std::string> text = read_text_file(o.recovery);
    Result<executor::RecoveryProfile> recovery =
        text.has_value() ? executor::read_recovery_json(*text, o.recovery)
                         : Result<executor::RecoveryProfile>(text.error());
    if (!recovery.has_value()) return fail(c, o.json, recovery.error());
    options.recovery = *recovery;
  }
  if (o.allow_push) options.recovery.push_allowed = true;
  std::optional<LogFile> log_file;
  if (!o.log.empty()) {
    Result<LogFile> opened = LogFile::open(o.log);
    if (!opened.has_value()) return fail(c, o.json, opened.error());
    log_file.emplace(std::move(*opened));
  }
  executor::ReplannerOptions replanner_options;
  replanner_options.planner.risk = o.risk.costs();
  replanner_options.planner.max_strand_risk = o.risk.max_strand_risk;
  executor::Replanner replanner(map, mission, replanner_options);
  // The routes from the map's routing index, when one is kept beside it (issue 35).
  if (auto index = attach_route_index(
          o.route_index, o.map, c.err,
          [&](const domain::RouteIndex& i) { return replanner.use_route_index(i); });
      !index.has_value()) {
    return fail(c, o.json, index.error());
  }
  if (!o.learnt.empty() && std::filesystem::exists(o.learnt)) {
    Diagnostics d;
    Result<executor::Learnt> learnt = executor::read_learnt(o.learnt, map, d);
    Result<void> learn =
        learnt.has_value() ? replanner.learn(*learnt) : Result<void>(learnt.error());
    if (!learn.has_value()) return fail(c, o.json, learn.error(), d);
  }
  std::unique_ptr<CanLink> can;
  if (!o.can.bus.empty() || !o.can.replay.empty()) {
    Result<std::unique_ptr<CanLink>> link = CanLink::open(o.can);
    if (!link.has_value()) return fail(c, o.json, link.error());
    can = std::move(*link);
  }
  // The robot drives the true world (the map itself with "none"); the executor plans on the map.
  // Over CAN the world is the node's (sim-node --world-errors, or the real one).
  std::unique_ptr<SimulatedRobot> sim;
  if (!can) {
    Result<std::unique_ptr<SimulatedRobot>> made =
        make_simulated_robot(map, mission, start_pose(replanner.progress().position), faults,
                             o.world_errors, o.world_seed);
    if (!made.has_value()) return fail(c, o.json, made.error());
    sim = std::move(*made);
  }
  hal::Robot& robot = can ? static_cast<hal::Robot&>(can->robot()) : *sim->robot;
  executor::Executor executor(map, replanner, robot, options);
  if (log_file) {
    executor.subscribe_log(*log_file);
    // Said once, when the log first fails; the mission goes on and the report names the log.
    executor.subscribe([&log_file, &c, warned = false](const executor::Event&) mutable {
      if (warned || !log_file->first_error()) return;
      warned = true;
      c.err << "sewerplan simulate: warning: " << *log_file->first_error()
            << "; the mission goes on without its log\n";
    });
  }
  // With --json, standard output is the report alone: the live log goes to standard error.
  if (!o.quiet) executor.subscribe(executor::readable_writer(o.json ? c.err : c.out));
  std::optional<executor::Measurer> measurer;
  if (!o.corrected_map.empty()) {
    measurer.emplace(map,
                     MeasurementSource{.robot = mission.profile.name,
                                       .mission = mission.name.empty() ? o.mission : mission.name,
                                       .date = measurement_date()});
    executor.subscribe_jobs(measurer->observer());
  }
  halt_on_signal.attach(executor);
  const executor::MissionReport report = executor.run();
  halt_on_signal.detach();
  if (o.json) {
    print_json(c.out, report_json(report));
  } else {
    c.out << '\n' << report << "decision " << executor::to_string(report.decision);
    if (report.outcome == executor::MissionReport::Outcome::kBeacon) {
      c.out << " (beacon: " << executor::to_string(report.beacon_cause) << ", "
            << hal::to_string(report.beacon) << ')';
    }
    c.out << '\n';
  }
  if (can) can->write_summary(c.err);
  bool log_lost = false;
  if (can) {
    if (Result<void> closed = can->close_log(); !closed.has_value()) {
      c.err << "sewerplan simulate: " << closed.error().message << '\n';
      log_lost = true;
    }
  }
  // A log that lost events, or whose close failed, is a failed write: exit 3 after the report
  // (which names it), unless the mission itself did not end (below).
  if (log_file) {
    if (Result<void> closed = log_file->close(); !closed.has_value()) {
      c.err << "sewerplan simulate: " << closed.error().message << '\n';
      log_lost = true;
    }
  }
  bool write_failed = log_lost;
  if (!o.learnt.empty()) {
    if (auto written = write_text_file(o.learnt, executor::learnt_json(replanner.learnt(), map));
        !written.has_value()) {
      // The report is out already: the failure on standard error.
      c.err << "sewerplan simulate: " << written.error().message << '\n';
      write_failed = true;
    }
  }
  if (measurer) {
    MapMeasurements measured = measurer->measurements();
    for (const std::string& why : measurer->rejected()) {
      c.err << "sewerplan simulate: warning: a report not measured: " << why << '\n';
    }
    Diagnostics written;
    Result<void> w =
        write_corrected_map(o.corrected_map, o.map, map, measured, o.json ? c.err : c.out, written);
    print_diagnostics(written, c.err);
    if (w.has_value()) {
      w = write_text_file(beside(o.corrected_map, "measurements"),
                          measurements_json(measured, map));
    }
    if (!w.has_value()) {
      // The report is out already: the failure on standard error.
      c.err << "sewerplan simulate: " << w.error().message << '\n';
      write_failed = true;
    }
  }
  // Issue 30, one rule (docs/cli.md, "Exit codes"): the mission's own outcome comes first. A robot
  // that called for recovery (beacon on) or was halted is exit 4 even when a write failed too (the
  // failure is in the report and on standard error); a mission that ended is exit 3 when a write
  // failed, else 0.
  if (report.outcome != executor::MissionReport::Outcome::kEnded) return kExitNoPlan;
  return write_failed ? kExitIo : kExitOk;
}

}  // namespace

void add_simulate_command(CLI::App& app, Context& context) {
  // Shared with the callback, which CLI11 keeps after this function returns.
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Run a mission on the simulated robot, with hidden faults, recovery and replanning");
  cmd->add_option("--map", options->map, "Map file")->required();
  add_gis_fields_option(*cmd, options->gis_fields);
  cmd->add_option("--mission", options->mission, "Mission file (.json)")->required();
  auto* faults =
      cmd->add_option("--faults", options->faults, "Fault scenario (docs/simulation.md)");
  auto* random = cmd->add_option("--random-faults", options->random_faults,
                                 "Random faults: SEED[,RATE] (RATE obstacles per km, default 20)");
  random->excludes(faults);
  cmd->add_option("--recovery", options->recovery,
                  "Recovery profile (JSON, docs/formats/recovery-json.md)");
  cmd->add_flag("--allow-push", options->allow_push,
                "Allow recovery phase 3, pushing an obstacle (off for real sewers)");
  cmd->add_option("--log", options->log, "Write the event log as JSON lines");
  cmd->add_option("--learnt", options->learnt,
                  "What the robot learnt (JSON): read if it exists, written at the end");
  cmd->add_option("--corrected-map", options->corrected_map,
                  "Write the map corrected by what the robot measured (JSON; for an ISYBAU map "
                  "also OUT.xml, ISYBAU), with OUT.discrepancies.json and "
                  "OUT.measurements.json beside it");
  cmd->add_flag("-q,--quiet", options->quiet, "Only the final report");
  cmd->add_flag("--json", options->json,
                "Print the report as JSON (the live log goes to standard error)");
  auto* can =
      cmd->add_option("--can", options->can.bus,
                      "Run on a robot over CAN: slcan:TTY or socketcan:IFACE (docs/can.md)");
  auto* replay = cmd->add_option("--replay", options->can.replay,
                                 "Run on the replay of a candump log of an earlier --can run")
                     ->excludes(can);
  cmd->add_option("--can-log", options->can.log, "Record the CAN traffic as a candump log");
  faults->excludes(can)->excludes(replay);
  random->excludes(can)->excludes(replay);
  auto* world = cmd->add_option("--world-errors", options->world_errors,
                                "NAME|SPEC: the true world the robot drives (none, realistic; or "
                                "[NAME,]key=value,...: docs/simulation.md); with --can, sim-node's")
                    ->capture_default_str();
  auto* world_seed =
      cmd->add_option("--world-seed", options->world_seed, "Seed of the true world and the sensing")
          ->capture_default_str();
  add_motion_options(*cmd, options->motion);
  add_route_index_options(*cmd, options->route_index);
  add_condition_option(*cmd, options->condition);
  add_risk_options(*cmd, options->risk);
  cmd->callback([options, world, world_seed, &context] {
    options->world_given = world->count() > 0 || world_seed->count() > 0;
    context.exit_code = run(*options, context);
  });
}

}  // namespace sewerplan::cli
