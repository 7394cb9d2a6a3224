// SPDX-License-Identifier: MIT
// The driveability report of `sewerplan info --profile` (domain/driveability.h), as text for
// people and as JSON for scripts, and what goes into it: the planned manhole passages (a motion
// table) and the places the map's inspection findings close for the robot, as `plan` closes them
// by default. The station's driveability endpoint answers with the same. Names stand for IDs and
// slots are numbered from 1, as in missions and plans.
#pragma once

#include <ostream>
#include <span>
#include <string_view>
#include <utility>
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

// What the findings close for the robot, split: the places it could otherwise drive to, and those
// in pipes it cannot enter anyway (too narrow or too wide for it, or out of reach from the starts:
// a closure there changes nothing for a plan), each with why.
struct Closures {
  std::vector<FindingRisk> enterable;
  std::vector<std::pair<FindingRisk, std::string_view>> undrivable;
};

// closing_findings, split by `report` (analyse_profile's, with the same table).
Closures split_closures(const SewerMap& map, const RobotProfile& profile, const RiskTable& table,
                        const domain::DriveabilityReport& report);

// `info --json`'s and the station's {"closed_by_findings": [{"pipe", "offset_m", "code",
// "reason"}], "closed_by_findings_in_undrivable_pipes": [... and "pipe_not_driveable"]}.
nlohmann::json closures_json(const SewerMap& map, const Closures& closed);

void print_driveability(const domain::DriveabilityReport& report, const SewerMap& map,
                        const RobotProfile& profile, std::ostream& out);

nlohmann::json driveability_json(const domain::DriveabilityReport& report, const SewerMap& map,
                                 const RobotProfile& profile);

}  // namespace sewerplan::server
