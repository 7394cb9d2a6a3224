// SPDX-License-Identifier: MIT
// What `simulate` and `sim-node` share: where the simulated robot starts and which hidden faults
// it meets (--faults FILE or --random-faults SEED[,RATE]).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/robot_state.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"
#include "sewerplan/hal/world_errors.h"
#include "sewerplan/server/sim_setup.h"

#include "map_input.h"

namespace sewerplan::cli {

// start_pose and faults_for are shared with the operator station (server/sim_setup.h).
using server::faults_for;
using server::start_pose;

// The map, the mission and the hidden faults of a simulated run, read together.
struct SimWorld {
  SewerMap map;
  Mission mission;
  hal::FaultScenario faults;
};

// Reads them (the map with the condition data of `condition`, if given); the problems go to
// `diagnostics`. A fault file with a bad value is invalid input (kInvalidMission, exit code 1)
// like a bad map; a bad --random-faults a usage error (kInvalidArgument, exit code 2).
Result<SimWorld> read_sim_world(const MapSource& map_source, const std::string& mission_path,
                                const std::string& faults_file, const std::string& random_faults,
                                Diagnostics& diagnostics, const std::string& condition = {});

// The simulated robot of a run and the true world it drives (hal/world_errors.h): the world drawn
// from the map by `world_errors` (NAME|SPEC) and `world_seed` (the map itself with "none"), the
// robot started at `start` and meeting `faults` (both on the map) in it, sensing as the profile
// says. `simulate` runs it in process and `sim-node` behind CAN, both through this: the same
// inputs give the same robot, observation for observation. Errors: a bad profile
// (kInvalidArgument, a usage error).
struct SimulatedRobot {
  hal::TrueWorld truth;
  std::optional<hal::SimRobot> robot;  // drives truth.world: a SimulatedRobot never moves
};
Result<std::unique_ptr<SimulatedRobot>> make_simulated_robot(
    const SewerMap& map, const Mission& mission, const hal::SimPose& start,
    const hal::FaultScenario& faults, const std::string& world_errors, std::uint64_t world_seed);

// Reads them, printing every problem to `err`; empty with `exit_code` set when one is wrong.
std::optional<SimWorld> load_sim_world(const MapSource& map_source, const std::string& mission_path,
                                       const std::string& faults_file,
                                       const std::string& random_faults, std::ostream& err,
                                       int& exit_code, const std::string& condition = {});

}  // namespace sewerplan::cli
