// SPDX-License-Identifier: MIT
// The driveability report of `sewerplan info --profile` (domain/driveability.h), as text for
// people and as JSON for scripts. Names stand for IDs and slots are numbered from 1, as in
// missions and plans.
#pragma once

#include <ostream>

#include <nlohmann/json.hpp>

#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/driveability.h"

namespace sewerplan::server {

void print_driveability(const domain::DriveabilityReport& report, const SewerMap& map,
                        const RobotProfile& profile, std::ostream& out);

nlohmann::json driveability_json(const domain::DriveabilityReport& report, const SewerMap& map,
                                 const RobotProfile& profile);

}  // namespace sewerplan::server
