// SPDX-License-Identifier: MIT
#include "sim_setup.h"

#include <string>
#include <utility>

#include "sewerplan/core/map_io.h"

#include "command.h"
#include "condition_options.h"

namespace sewerplan::cli {

Result<SimWorld> read_sim_world(const MapSource& map_source, const std::string& mission_path,
                                const std::string& faults_file, const std::string& random_faults,
                                Diagnostics& diagnostics, const std::string& condition) {
  Result<SewerMap> map = read_map_with_condition(map_source, condition, diagnostics);
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

Result<std::unique_ptr<SimulatedRobot>> make_simulated_robot(
    const SewerMap& map, const Mission& mission, const hal::SimPose& start,
    const hal::FaultScenario& faults, const std::string& world_errors, std::uint64_t world_seed) {
  const Result<hal::WorldErrorProfile> profile = hal::parse_world_errors(world_errors);
  if (!profile.has_value()) return profile.error();
  Result<hal::TrueWorld> truth = hal::make_true_world(map, *profile, world_seed);
  if (!truth.has_value()) return truth.error();
  auto simulated = std::make_unique<SimulatedRobot>();
  simulated->truth = std::move(*truth);
  const hal::TrueWorld& t = simulated->truth;
  simulated->robot.emplace(t.world, mission.profile, hal::world_pose(map, t, start),
                           hal::world_faults(map, t, faults),
                           hal::SimOptions{.sensing = hal::make_sensing(t)});
  return simulated;
}

std::optional<SimWorld> load_sim_world(const MapSource& map_source, const std::string& mission_path,
                                       const std::string& faults_file,
                                       const std::string& random_faults, std::ostream& err,
                                       int& exit_code, const std::string& condition) {
  Diagnostics diagnostics;
  Result<SimWorld> world =
      read_sim_world(map_source, mission_path, faults_file, random_faults, diagnostics, condition);
  print_diagnostics(diagnostics, err);
  if (!world.has_value()) {
    if (diagnostics.error_count() == 0) err << world.error().message << '\n';
    exit_code = exit_code_for(world.error());
    return std::nullopt;
  }
  return std::move(*world);
}

}  // namespace sewerplan::cli
