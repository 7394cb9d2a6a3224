// SPDX-License-Identifier: MIT
// Plan JSON: a plan with its validation, for programs (the CLI's `check --json`, dashboards).
//
// The steps are written as the paper's text (plan_text.h) and, for programs, as their kind and
// their objects by name; the costs are the validator's (validator.h):
//
//   {"format": "sewerplan-plan", "version": 1, "valid": true, "cost_s": 585.38,
//    "energy_wh": 19.51, "steps": [{"action": "DRIVE_PIPE_TO_MANHOLE P12 M2",
//    "kind": "drive_pipe_to_manhole", "pipe": "P12", "manhole": "M2", "cost_s": 9.43}, ...]}
//
// An invalid plan adds "error" and, when a step failed, "failed_step" (from 1, as in the error);
// steps after it have no "cost_s". Slots are numbered from 1, as in the paper. A mission with
// hazards (risk-aware planning, route_risk.h) adds "risk": {"unobstructed_probability": 0.72,
// "hazards": [{"pipe": "P5", "offset_m": 12.5, "probability": 0.45, "reason": "BBA roots",
// "step": 3}, ...]}, the possible blockages the route passes, in order.
//
//   ValidationReport report = validate_plan(plan, map, mission);
//   write_plan_json(plan, report, map, mission, std::cout);
//
// Thread-safety: free functions over values they only read; reentrant.
#pragma once

#include <ostream>
#include <string_view>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/domain/validator.h"

namespace sewerplan::domain {

inline constexpr std::string_view kPlanJsonFormat = "sewerplan-plan";
inline constexpr int kPlanJsonVersion = 1;

// Writes the plan and its report, indented, with a final newline.
void write_plan_json(const Plan& plan, const ValidationReport& report, const SewerMap& map,
                     const Mission& mission, std::ostream& out);

}  // namespace sewerplan::domain
