// SPDX-License-Identifier: MIT
// What `simulate` and `sim-node` share: where the simulated robot starts and which hidden faults
// it meets (--faults FILE or --random-faults SEED[,RATE]).
#pragma once

#include <string>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/robot_state.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"

namespace sewerplan::cli {

// The simulated robot starts where the mission puts it; in a pipe it faces the pipe's ends[1],
// as fusion assumes (fusion/fuse.h).
hal::SimPose start_pose(const domain::RobotPosition& p);

// The fault file if given, else random faults if given (SEED[,RATE]), else none.
Result<hal::FaultScenario> faults_for(const std::string& faults_file,
                                      const std::string& random_faults, const SewerMap& map,
                                      Diagnostics& diagnostics);

}  // namespace sewerplan::cli
