// SPDX-License-Identifier: MIT
#include "condition_options.h"

#include <CLI/CLI.hpp>

#include "sewerplan/core/condition.h"
#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/map_io.h"

namespace sewerplan::cli {

void add_condition_option(CLI::App& command, std::string& condition) {
  command.add_option("--condition", condition,
                     "Inspection findings to join to the map by pipe name: an ISYBAU "
                     "Zustandsdaten file (docs/formats/isybau.md)");
}

Result<SewerMap> read_map_with_condition(const std::string& map, const std::string& condition,
                                         Diagnostics& diagnostics) {
  Result<SewerMap> read = read_map(map, diagnostics);
  if (!read.has_value() || condition.empty()) return read;
  return read_condition(std::move(*read), condition, diagnostics);
}

std::size_t close_findings(const SewerMap& map, Mission& mission, RiskMode mode) {
  if (mode == RiskMode::kIgnore) return 0;
  std::vector<FindingRisk> risks = assess_findings(map, mission.profile, default_risk_table());
  if (mode == RiskMode::kAvoid) {
    for (FindingRisk& r : risks) {
      if (r.effect != RiskEffect::kNone) r.effect = RiskEffect::kImpassable;
    }
  }
  const std::vector<Blockage> closed = impassable_blockages(map, risks);
  mission.blockages.insert(mission.blockages.end(), closed.begin(), closed.end());
  return closed.size();
}

}  // namespace sewerplan::cli
