// SPDX-License-Identifier: MIT
// sewerplan sim-node --pty --map MAP --mission MISSION [--faults FILE | --random-faults S[,R]]
//                    [--bus-faults SPEC] [--world-errors NAME|SPEC] [--world-seed N]
//
// The simulated microcontroller node on a pseudo-terminal that speaks SLCAN, as a USB-CAN adapter
// would: prints the pty's path on the first line of its output, then serves the job protocol
// (docs/can-protocol.md) to whoever opens it, until SIGINT or SIGTERM. Its robot is the one
// `simulate` would run in process with the same options (sim_setup.h): the same true world, faults
// and sensing, so that a run over the bus equals the run in process.
#include <atomic>
#include <csignal>
#include <iostream>
#include <ostream>

#include <CLI/CLI.hpp>

#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/executor/replanner.h"
#include "sewerplan/hal/can/sim_node.h"
#include "sewerplan/hal/can/slcan.h"
#include "sewerplan/hal/world_errors.h"

#include "command.h"
#include "map_input.h"
#include "sim_setup.h"

namespace sewerplan::cli {
namespace {

struct SimNodeCliOptions {
  std::string map;
  std::string gis_fields;  // --gis-fields
  std::string mission;
  std::string faults;
  std::string random_faults;
  std::string bus_faults;
  std::string world_errors = "none";
  std::uint64_t world_seed = 1;
  bool pty = false;
};

std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

extern "C" void stop_serving(int /*signal*/) { g_stop.store(true); }

int run(const SimNodeCliOptions& o, Context& c) {
  int exit_code = kExitOk;
  if (Result<hal::WorldErrorProfile> w = hal::parse_world_errors(o.world_errors); !w.has_value()) {
    c.err << "sewerplan sim-node: " << w.error().message << '\n';
    return kExitUsage;
  }
  std::optional<SimWorld> world =
      load_sim_world({o.map, o.gis_fields}, o.mission, o.faults, o.random_faults, c.err, exit_code);
  if (!world) return exit_code;
  const SewerMap& map = world->map;
  const Mission& mission = world->mission;
  const hal::FaultScenario& faults = world->faults;
  Result<hal::BusFaults> bus_faults = hal::parse_bus_faults(o.bus_faults);
  if (!bus_faults.has_value()) {
    c.err << bus_faults.error().message << '\n';
    return kExitUsage;
  }
  Result<hal::Pty> pty = hal::open_pty();
  if (!pty.has_value()) {
    c.err << pty.error().message << '\n';
    return kExitIo;
  }
  // Where the simulate command's robot would start: the mission's start, through the Replanner.
  const executor::Replanner replanner(map, mission);
  Result<std::unique_ptr<SimulatedRobot>> sim =
      make_simulated_robot(map, mission, start_pose(replanner.progress().position), faults,
                           o.world_errors, o.world_seed);
  if (!sim.has_value()) {
    c.err << "sewerplan sim-node: " << sim.error().message << '\n';
    return exit_code_for(sim.error());
  }
  hal::SlcanDeviceBus line(std::move(pty->master), pty->slave_path);
  hal::SimNode node(line, *(*sim)->robot, {.faults = *bus_faults}, &line);
  c.out << pty->slave_path << '\n'
        << "sim-node: serving " << o.mission << " on " << pty->slave_path
        << " (SLCAN); connect with: sewerplan simulate --map " << o.map << " --mission "
        << o.mission << " --can slcan:" << pty->slave_path << std::endl;
  std::signal(SIGINT, stop_serving);
  std::signal(SIGTERM, stop_serving);
  const Result<void> served = node.serve(g_stop);
  const hal::SimNodeStats& s = node.stats();
  c.err << "sim-node: " << s.requests << " requests, " << s.jobs_run << " jobs run, " << s.repeats
        << " answered again, " << s.malformed << " malformed, " << s.ignored << " ignored, "
        << s.frames_dropped << " frames dropped\n";
  if (!served.has_value()) {
    c.err << served.error().message << '\n';
    return kExitIo;
  }
  return kExitOk;
}

}  // namespace

void add_sim_node_command(CLI::App& app, Context& context) {
  auto options = std::make_shared<SimNodeCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "sim-node", "Serve a simulated robot's CAN node over SLCAN on a pseudo-terminal");
  cmd->add_flag("--pty", options->pty, "Serve on a new pseudo-terminal (prints its path)")
      ->required();
  cmd->add_option("--map", options->map, "Map file")->required();
  add_gis_fields_option(*cmd, options->gis_fields);
  cmd->add_option("--mission", options->mission, "Mission file (.json): where the robot starts")
      ->required();
  auto* faults =
      cmd->add_option("--faults", options->faults, "Fault scenario (docs/simulation.md)");
  cmd->add_option("--random-faults", options->random_faults,
                  "Random faults: SEED[,RATE] (RATE obstacles per km, default 20)")
      ->excludes(faults);
  cmd->add_option("--bus-faults", options->bus_faults,
                  "Bus faults: drop=N,..;drop-rate=P;seed=S;garbage=N,..;silence=R+K;bus-off=R;"
                  "late-ack=J@S;lose-result=J,.. (docs/can.md)");
  cmd->add_option("--world-errors", options->world_errors,
                  "NAME|SPEC: the true world the robot drives, as simulate's (none, realistic; or "
                  "[NAME,]key=value,...: docs/simulation.md)")
      ->capture_default_str();
  cmd->add_option("--world-seed", options->world_seed, "Seed of the true world and the sensing")
      ->capture_default_str();
  cmd->callback([options, &context] { context.exit_code = run(*options, context); });
}

}  // namespace sewerplan::cli
