// SPDX-License-Identifier: MIT
// --condition FILE: inspection findings (ISYBAU Zustandsdaten) joined to the map a command reads,
// and what they close for planning (core/condition.h, core/condition_risk.h).
#pragma once

#include <string>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace CLI {
class App;
}

namespace sewerplan::cli {

void add_condition_option(CLI::App& command, std::string& condition);

// read_map, then read_condition when `condition` is not empty.
Result<SewerMap> read_map_with_condition(const std::string& map, const std::string& condition,
                                         Diagnostics& diagnostics);

// What planning makes of the findings (plan --risk): kIgnore none; kImpassable (the default)
// closes the places the default risk table finds impassable for the mission's robot; kAvoid
// closes every place with a risk at all (impassable, blockage or danger).
enum class RiskMode { kIgnore, kImpassable, kAvoid };

// Adds a blockage at every finding `mode` closes; returns how many.
std::size_t close_findings(const SewerMap& map, Mission& mission,
                           RiskMode mode = RiskMode::kImpassable);

}  // namespace sewerplan::cli
