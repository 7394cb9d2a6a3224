// SPDX-License-Identifier: MIT
// The driveability report of `sewerplan info --profile` (domain/driveability.h), as text for
// people and as JSON for scripts, and what goes into it: the planned manhole passages (a motion
// table) and the places the map's inspection findings close for the robot, as `plan` closes them
// by default. The station's driveability endpoint answers with the same. Names stand for IDs and
// slots are numbered from 1, as in missions and plans.
#pragma once

#include <ostream>
#include <span>
#include <vector>

#include <nlohmann/json.hpp>

#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/passage_motion.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/driveability.h"

namespace sewerplan::server {

// The findings that close a place for this robot by `table` (RiskEffect::kImpassable).
std::vector<FindingRisk> closing_findings(const SewerMap& map, const RobotProfile& profile,
                                          const RiskTable& table);

// analyse_driveability from `starts` with the motion table (none: the angle and step rules) and
// the closures of closing_findings.
domain::DriveabilityReport analyse_profile(const SewerMap& map, const RobotProfile& profile,
                                           std::span<const ManholeId> starts,
                                           const PassageMotionTable* motion,
                                           const RiskTable& table);

// closing_findings as [{"pipe", "offset_m", "code", "reason"}]: `info --json`'s
// "closed_by_findings".
nlohmann::json closed_by_findings_json(const SewerMap& map, const RobotProfile& profile,
                                       const RiskTable& table);

void print_driveability(const domain::DriveabilityReport& report, const SewerMap& map,
                        const RobotProfile& profile, std::ostream& out);

nlohmann::json driveability_json(const domain::DriveabilityReport& report, const SewerMap& map,
                                 const RobotProfile& profile);

}  // namespace sewerplan::server
