// SPDX-License-Identifier: MIT
#include "sewerplan/server/sim_setup.h"

#include <exception>
#include <string>

namespace sewerplan::server {

hal::SimPose start_pose(const domain::RobotPosition& p) {
  if (const auto* in = std::get_if<domain::InManhole>(&p)) return hal::InManhole{in->manhole};
  if (const auto* at = std::get_if<domain::AtSlot>(&p)) return hal::AtSlot{at->manhole, at->slot};
  const auto& pipe = std::get<domain::InPipe>(p);
  return hal::InPipe{pipe.pipe, pipe.offset_m, hal::Heading::kTowardsEnd1};
}

Result<hal::FaultScenario> faults_for(const std::string& faults_file,
                                      const std::string& random_faults, const SewerMap& map,
                                      const Mission& mission, Diagnostics& diagnostics) {
  if (!faults_file.empty()) return hal::read_faults(faults_file, map, diagnostics);
  if (random_faults.empty()) return hal::FaultScenario{};
  // Where the mission's robot fits, as `campaign` draws them (one rule for both).
  // SEED[,RATE]: RATE obstacles per km of drivable pipe (default 20), a quarter as many danger
  // spots, and one malfunction per 2 hours.
  const auto comma = random_faults.find(',');
  hal::RandomFaultOptions r = hal::random_fault_options(mission.profile);
  try {
    r.seed = std::stoull(random_faults.substr(0, comma));
    r.obstacle_rate_per_km =
        comma == std::string::npos ? 20.0 : std::stod(random_faults.substr(comma + 1));
  } catch (const std::exception&) {
    return Error{ErrorCode::kInvalidArgument,
                 "--random-faults: expected SEED[,RATE], got '" + random_faults + "'"};
  }
  r.danger_rate_per_km = r.obstacle_rate_per_km / 4;
  r.malfunction_rate_per_hour = 0.5;
  return hal::random_faults(map, r);
}

}  // namespace sewerplan::server
