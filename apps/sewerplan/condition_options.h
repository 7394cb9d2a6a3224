// SPDX-License-Identifier: MIT
// --condition FILE: inspection findings (ISYBAU Zustandsdaten) joined to the map a command reads,
// and what they mean for planning: --risk MODE and --risk-table FILE (core/condition.h,
// core/condition_risk.h, docs/planning.md "Risk-aware planning").
#pragma once

#include <ostream>
#include <string>

#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/compile.h"

#include "map_input.h"

namespace CLI {
class App;
}

namespace sewerplan::cli {

void add_condition_option(CLI::App& command, std::string& condition);

// read_input_map, then read_condition when `condition` is not empty.
Result<SewerMap> read_map_with_condition(const MapSource& map, const std::string& condition,
                                         Diagnostics& diagnostics);

// --risk (a RiskMode's name, core/condition_risk.h) and --risk-table.
struct RiskOptions {
  std::string mode = "impassable";
  std::string table;  // a risk table file; empty: the built-in one
  // --max-strand-risk (search::PlannerOptions::max_strand_risk).
  double max_strand_risk = 0;
  RiskMode risk_mode() const;
  // Why --max-strand-risk is not a probability (outside 0..1, or not a number); empty if it is.
  std::string strand_risk_error() const;
  // The planner's risk costs: kDefaultRiskCosts for kExpected, none otherwise.
  domain::RiskCosts costs() const;
};

// --risk, --risk-table and --max-strand-risk on `command`.
void add_risk_options(CLI::App& command, RiskOptions& options);

// The table of --risk-table, or the built-in one; problems go to `diagnostics`.
Result<RiskTable> risk_table(const RiskOptions& options, Diagnostics& diagnostics);

// risk_table, then close_findings, saying what was closed on `err`; an error for a bad table.
Result<void> apply_risk(const RiskOptions& options, const SewerMap& map, Mission& mission,
                        Diagnostics& diagnostics, std::ostream& err);

}  // namespace sewerplan::cli
