// SPDX-License-Identifier: MIT
#include "driveability_option.h"

#include "sewerplan/core/robot_profile.h"

namespace sewerplan::cli {

Result<std::optional<domain::DriveabilityReport>> driveability_for_profile(
    const SewerMap& map, const std::string& profile) {
  if (profile.empty()) return std::optional<domain::DriveabilityReport>();
  Result<RobotProfile> robot = load_profile(profile);
  if (!robot.has_value()) {
    return Error{robot.error().code, "--profile: " + robot.error().message};
  }
  return std::optional<domain::DriveabilityReport>(
      domain::analyse_driveability(map, *robot, domain::default_starts(map)));
}

}  // namespace sewerplan::cli
