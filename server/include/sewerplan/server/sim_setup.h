// SPDX-License-Identifier: MIT
// What `simulate`, `sim-node` and the operator station's simulations share: where the simulated
// robot starts and which hidden faults it meets (a fault file, or random faults from SEED[,RATE]).
//
//   hal::SimRobot sim(map, mission.profile, start_pose(replanner.progress().position), faults);
#pragma once

#include <string>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/robot_state.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"

namespace sewerplan::server {

// The simulated robot starts where the mission puts it; in a pipe it faces the pipe's ends[1],
// as fusion assumes (fusion/fuse.h).
hal::SimPose start_pose(const domain::RobotPosition& p);

// The fault file if given, else random faults if given (SEED[,RATE]) on the pipes the mission's
// robot fits (as `campaign` draws them), else none.
Result<hal::FaultScenario> faults_for(const std::string& faults_file,
                                      const std::string& random_faults, const SewerMap& map,
                                      const Mission& mission, Diagnostics& diagnostics);

}  // namespace sewerplan::server
