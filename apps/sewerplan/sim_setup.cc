// SPDX-License-Identifier: MIT
#include "sim_setup.h"

#include <exception>
#include <string>
#include <utility>

#include "sewerplan/core/map_io.h"

#include "command.h"
#include "condition_options.h"

namespace sewerplan::cli {

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

Result<SimWorld> read_sim_world(const std::string& map_path, const std::string& mission_path,
                                const std::string& faults_file, const std::string& random_faults,
                                Diagnostics& diagnostics, const std::string& condition) {
  Result<SewerMap> map = read_map_with_condition(map_path, condition, diagnostics);
  if (!map.has_value()) return map.error();
  Result<Mission> mission = read_mission(mission_path, *map, diagnostics);
  if (!mission.has_value()) return mission.error();
  Result<hal::FaultScenario> faults =
      faults_for(faults_file, random_faults, *map, *mission, diagnostics);
  if (!faults.has_value()) {
    Error error = faults.error();
    if (!faults_file.empty() && error.code == ErrorCode::kInvalidArgument) {
      error.code = ErrorCode::kInvalidMission;
    }
    return error;
  }
  return SimWorld{std::move(*map), std::move(*mission), std::move(*faults)};
}

std::optional<SimWorld> load_sim_world(const std::string& map_path, const std::string& mission_path,
                                       const std::string& faults_file,
                                       const std::string& random_faults, std::ostream& err,
                                       int& exit_code, const std::string& condition) {
  Diagnostics diagnostics;
  Result<SimWorld> world =
      read_sim_world(map_path, mission_path, faults_file, random_faults, diagnostics, condition);
  print_diagnostics(diagnostics, err);
  if (!world.has_value()) {
    if (diagnostics.error_count() == 0) err << world.error().message << '\n';
    exit_code = exit_code_for(world.error());
    return std::nullopt;
  }
  return std::move(*world);
}

}  // namespace sewerplan::cli
