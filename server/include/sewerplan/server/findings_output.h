// SPDX-License-Identifier: MIT
// What the operator station draws of a map's inspection findings (core/condition.h) and of what a
// robot learnt on a run (executor/learnt.h, core/map_measurements.h), as JSON documents.
//
// Findings: each finding of the map with where it is (the pipe and the offset from its ends[0]),
// its DIN EN 13508-2 code, the code's name, its characterisation and quantifications, its class by
// the risk table for the robot (none, danger, blockage, impassable; condition_risk.h) with the
// probability and reason, and what planning in the risk mode makes of it (closed, weighed,
// ignored: finding_use, the one rule close_findings applies):
//
//   {"profile": "makro-plus", "risk": "expected", "findings": [{"pipe": "S1", "offset_m": 7.5,
//    "code": "BBA", "name": "roots", "characterisation": "B", "quantity1": 10, "class":
//    "blockage", "probability": 0.3, "reason": "BBA roots", "planner": "weighed"}, ...],
//    "counts": {"closed": 1, "weighed": 3, "ignored": 5}}
//
// Learnt: the Learnt's own JSON (what `simulate --learnt` writes and reads) and the map
// corrections the run's measurements show (discrepancies(), each with describe()'s line).
//
// Thread safety: Pure functions over values they only read.
#pragma once

#include <nlohmann/json.hpp>

#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/map_measurements.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/executor/learnt.h"

namespace sewerplan::server {

// The map's findings as above. Runtime: O(findings x rules).
nlohmann::ordered_json findings_json(const SewerMap& map, const RobotProfile& profile,
                                     RiskMode mode, std::string_view mode_name,
                                     const RiskTable& table);

// {"learnt": learnt_json's document, "measurements": {"pipes_measured", "manholes_observed",
// "junctions", "discrepancies": [{"kind", "pipe" | "manhole", "slot", "offset_m", "map_value",
// "value", "sigma", "text"}]}}: the discrepancies derived from `measurements` here.
nlohmann::ordered_json learnt_json_document(const executor::Learnt& learnt,
                                            const MapMeasurements& measurements,
                                            const SewerMap& map);

}  // namespace sewerplan::server
