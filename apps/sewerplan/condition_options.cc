// SPDX-License-Identifier: MIT
#include "condition_options.h"

#include <sstream>

#include <CLI/CLI.hpp>

#include "sewerplan/core/condition.h"
#include "sewerplan/core/map_io.h"

namespace sewerplan::cli {

void add_condition_option(CLI::App& command, std::string& condition) {
  command.add_option("--condition", condition,
                     "Inspection findings to join to the map by pipe name: an ISYBAU "
                     "Zustandsdaten file (docs/formats/isybau.md)");
}

Result<SewerMap> read_map_with_condition(const MapSource& map, const std::string& condition,
                                         Diagnostics& diagnostics) {
  Result<SewerMap> read = read_input_map(map, diagnostics);
  if (!read.has_value() || condition.empty()) return read;
  return read_condition(std::move(*read), condition, diagnostics);
}

RiskMode RiskOptions::risk_mode() const {
  return risk_mode_from_string(mode).value_or(RiskMode::kImpassable);
}

domain::RiskCosts RiskOptions::costs() const {
  return risk_mode() == RiskMode::kExpected ? domain::kDefaultRiskCosts : domain::RiskCosts{};
}

void add_risk_options(CLI::App& command, RiskOptions& options) {
  command
      .add_option("--risk", options.mode,
                  "What the inspection findings mean for planning (docs/planning.md, risk-aware "
                  "planning): impassable (the default: close what no robot of the profile "
                  "passes), avoid (close every place with a risk), expected (close the "
                  "impassable ones, weigh the expected cost of the possible blockages), ignore")
      ->check(CLI::IsMember({"ignore", "impassable", "avoid", "expected"}))
      ->capture_default_str();
  command.add_option("--risk-table", options.table,
                     "The risk table (JSON, docs/formats/risk-table.md); default: the built-in "
                     "one (info --risk-table-out writes it)");
  command
      .add_option("--max-strand-risk", options.max_strand_risk,
                  "The most the plan's computed stranding risk may be, 0..1: the chance of "
                  "meeting a possible blockage whose battery to back out and reach an exit "
                  "another way is not kept (docs/planning.md). 0: every reserve kept; 1: none")
      ->capture_default_str();
}

std::string RiskOptions::strand_risk_error() const {
  if (max_strand_risk >= 0 && max_strand_risk <= 1) return {};
  std::ostringstream out;
  out << "--max-strand-risk: " << max_strand_risk
      << " is not a probability: give a number from 0 to 1";
  return out.str();
}

Result<RiskTable> risk_table(const RiskOptions& options, Diagnostics& diagnostics) {
  if (options.table.empty()) return default_risk_table();
  return read_risk_table(options.table, diagnostics);
}

Result<void> apply_risk(const RiskOptions& options, const SewerMap& map, Mission& mission,
                        Diagnostics& diagnostics, std::ostream& err) {
  Result<RiskTable> table = risk_table(options, diagnostics);
  if (!table.has_value()) return table.error();
  const RiskMode mode = options.risk_mode();
  if (const std::size_t closed = close_findings(map, mission, mode, *table); closed > 0) {
    err << "risk: " << closed << " places closed by inspection findings ("
        << (mode == RiskMode::kAvoid ? "every risk avoided" : "impassable ones") << ")\n";
  }
  if (!mission.hazards.empty()) {
    err << "risk: " << mission.hazards.size()
        << " possible blockages weighed by their expected cost\n";
  }
  return {};
}

}  // namespace sewerplan::cli
