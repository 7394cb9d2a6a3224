// SPDX-License-Identifier: MIT
// Plan text: the MAKRO paper's symbolic plan format, one action a line, read and written.
//
// A Plan (plan.h) names objects by ID; its text names them as the map and the mission do, in the
// paper's words (Adria, Streich and Hertzberg 2004, section 6):
//
//   DRIVE_PIPE_TO_MANHOLE P12 M2
//   DRIVE_MANHOLE_TYPE_3_TYPE_B_FROM_3_TO_1 M3 P5 P2 P1
//   TAKE_WATER_SAMPLE P6
//   INSPECT_PIPE P4
//
// The grammar of every action, and when its optional tokens (a task's name, an inspection's
// finish manhole) are written, is in docs/domain.md. parse_plan also reads the plans FF and Fast
// Downward print for the PDDL export ("step 0: DRIVE_PIPE_TO_MANHOLE P12 M2",
// "(drive_pipe_to_manhole p12 m2)"). Parsing checks that a line names an action that exists on the
// map and in the mission; whether the plan can be executed is the validator's question
// (validator.h).
//
//   Diagnostics diagnostics;
//   Result<Plan> plan = parse_plan(text, "paper.plan", map, mission, diagnostics);
//   if (plan.has_value()) out << format_plan(*plan, map, mission);
//
// Thread-safety: free functions over values they only read; reentrant.
#pragma once

#include <string>
#include <string_view>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/plan.h"

namespace sewerplan::domain {

// One action as the paper writes it, without a line break: "DRIVE_PIPE_TO_MANHOLE P12 M2". IDs that
// are not in the map or the mission are written as "#7" rather than rejected, so that a broken
// plan can still be shown. Runtime: O(slots of the manhole) for DRIVE_MANHOLE, else O(tasks).
std::string format_step(const PlanStep& step, const SewerMap& map, const Mission& mission);

// Every step, each followed by '\n'.
std::string format_plan(const Plan& plan, const SewerMap& map, const Mission& mission);

// The step's kind as the JSON output names it: "drive_pipe_to_manhole", "drive_manhole",
// "enter_pipe", "take_water_sample", "inspect_pipe", "go_to_point", "go_to_manhole".
std::string_view step_kind(const PlanStep& step);

// Reads a plan. Blank lines and lines starting with ';' or '#' are skipped, as is anything after a
// ';' on an action's line; a leading "step N:" or "N:" (FF) and enclosing parentheses (Fast
// Downward) are stripped. Action names are read in any case; object names exactly, or else
// case-insensitively when that identifies one object. Every bad line is reported in `diagnostics`
// as "FILE:LINE"; then the result is a kParse Error listing them. Never fails otherwise, whatever
// the bytes. Runtime: O(text length + tokens x log(names)), plus one O(names) index the first time
// a name needs a case-insensitive match.
Result<Plan> parse_plan(std::string_view text, const std::string& file_name, const SewerMap& map,
                        const Mission& mission, Diagnostics& diagnostics);

}  // namespace sewerplan::domain
