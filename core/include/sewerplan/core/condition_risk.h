// SPDX-License-Identifier: MIT
// The risk table: what each inspection finding (condition.h) means for a robot.
//
// MAKRO's paper names what stops it: "ingrown roots or parts from damaged pipes may block the
// robot's path" (Adria, Streich and Hertzberg 2004, section 2.1). A RiskTable turns each finding
// of a map, for one robot profile, into one of
//   - kImpassable: the robot cannot pass that place (a collapse; a deformation, deposit, root
//     mass or obstacle leaving less clear size than the robot's body width). Planning treats it
//     as a blockage at the finding's offset (mission.h): the robot may drive up to it, not across;
//   - kBlockage: it may stop the robot there, with a probability (roots, deposits, obstacles
//     that leave room);
//   - kDanger: passable, but a place to pass with care (displaced joints, intruding connections);
//   - kNone: no effect on driving (cracks, surface damage, the inspection's own markers).
// Rules are matched in order, the first whose code (and characterisation prefix, if given)
// matches wins. The defaults, and why: docs/formats/isybau.md, "Risk table".
//
//   std::vector<FindingRisk> risks = assess_findings(map, profile, default_risk_table());
//   std::vector<Blockage> closed = impassable_blockages(map, risks);  // add to the mission
//
// Thread safety: Plain values and pure functions: const access from several threads is safe.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

enum class RiskEffect { kNone, kDanger, kBlockage, kImpassable };

std::string_view to_string(RiskEffect effect);

// How a fitted table's rule was estimated from observed outcomes (risk_fit.h, fit_risk_table;
// docs/formats/risk-table.md, "fit"). A table written by hand has none; planning ignores it.
struct RiskRuleFit {
  std::size_t observations = 0;  // findings of this rule robots passed or were stopped by
  std::size_t blockages = 0;     // of those, the ones that stopped a robot
  double prior_strength = 0;     // the prior's weight, in pseudo-observations (k)
  double prior_probability = 0;  // the prior table's `probability` for this rule
  // The blockage probability of the findings observed (their mean): the prior's (m, from the
  // prior table at each finding's quantification), the posterior mean, and its equal-tailed
  // credible interval at `level`. With no observation: the prior rule's `probability`, and the
  // interval of the prior alone.
  double mean_prior = 0;
  double mean = 0;
  double mean_low = 0;
  double mean_high = 0;
  double level = 0.9;
  friend bool operator==(const RiskRuleFit&, const RiskRuleFit&) = default;
};

struct RiskRule {
  std::string code;              // a DIN EN 13508-2 main code ("BAC"), or a prefix of one ("BA")
  std::string characterisation;  // a prefix of the finding's characterisation; empty: any
  RiskEffect effect = RiskEffect::kNone;
  // Quantification 1 is the share of the cross-section taken, in percent (DIN EN 13508-2 for
  // BAA, BBA, BBB, BBC, BBE, BAG): where the clear size left, diameter x (1 - q / 100), is less
  // than the robot's body width, the finding is kImpassable whatever `effect` says.
  bool cross_section_percent = false;
  // For kBlockage: the probability that the robot is stopped there, base + per_percent x q
  // (quantification 1), at most 1.
  double probability = 0;
  double probability_per_percent = 0;
  std::string meaning;             // "roots", for reasons
  std::optional<RiskRuleFit> fit;  // a fitted table's evidence for this rule; not for planning
  friend bool operator==(const RiskRule&, const RiskRule&) = default;
};

struct RiskTable {
  std::vector<RiskRule> rules;
  friend bool operator==(const RiskTable&, const RiskTable&) = default;
};

// The defaults of docs/formats/isybau.md.
RiskTable default_risk_table();

// The kind of a risk table file, and its version (docs/formats/risk-table.md).
inline constexpr std::string_view kRiskTableJsonFormat = "sewerplan-risk-table";
inline constexpr int kRiskTableJsonVersion = 1;

// Reads a risk table (plan --risk-table FILE). Each problem is an error naming the file and the
// JSON path ("table.json:$.rules[2].effect: ..."): an unknown effect, a probability outside 0..1,
// an empty code; unknown fields are warnings. Never throws.
Result<RiskTable> read_risk_table_json(std::string_view text, const std::string& file_name,
                                       Diagnostics& diagnostics);
// The same for a file; an unreadable file is a kIo error naming it.
Result<RiskTable> read_risk_table(const std::filesystem::path& path, Diagnostics& diagnostics);
// The table in the form read_risk_table_json reads (`info --risk-table-out` writes the defaults).
void write_risk_table_json(const RiskTable& table, std::ostream& out);

struct FindingRisk {
  std::size_t finding = 0;  // index into SewerMap::findings()
  RiskEffect effect = RiskEffect::kNone;
  double blockage_probability = 0;  // 1 when kImpassable, 0 when kNone or kDanger
  std::string reason;  // "BAC collapse", "BAA deformation leaves 0.18 m, less than 0.22 m"
  friend bool operator==(const FindingRisk&, const FindingRisk&) = default;
};

// One FindingRisk per finding of `map`, in the map's order. Runtime: O(findings x rules).
std::vector<FindingRisk> assess_findings(const SewerMap& map, const RobotProfile& profile,
                                         const RiskTable& table);

// The index of the rule that decides `finding` (the first whose code and characterisation match),
// or none. Runtime: O(rules).
std::optional<std::size_t> matching_rule(const RiskTable& table, const Finding& finding);

// The kImpassable findings as mission blockages, in the map's order of findings.
std::vector<Blockage> impassable_blockages(const SewerMap& map,
                                           const std::vector<FindingRisk>& risks);

// What risk-aware planning needs of the findings: each kBlockage finding as a Hazard (mission.h)
// with its probability and reason, in the map's order of findings.
std::vector<Hazard> blockage_hazards(const SewerMap& map, const std::vector<FindingRisk>& risks);

// What planning makes of the findings (the CLI's --risk, the Python campaign's risk=):
// kIgnore none; kImpassable (the default) closes the places the risk table finds impassable for
// the mission's robot; kAvoid closes every place with a risk at all (impassable, blockage or
// danger); kExpected closes the impassable ones and weighs the others' blockage probabilities
// (Mission::hazards, domain::RiskCosts).
enum class RiskMode { kIgnore, kImpassable, kAvoid, kExpected };

// "ignore", "impassable", "avoid", "expected"; empty for another name.
std::optional<RiskMode> risk_mode_from_string(std::string_view name);

// What planning in `mode` makes of one assessed finding: kClosed, a blockage (the robot may drive
// up to it, not across); kWeighed, a hazard whose blockage probability the risk-aware planner
// weighs (kExpected, a kBlockage with a probability over 0); kIgnored, nothing. close_findings
// applies exactly this; the operator station draws it (docs/operator-station.md).
enum class FindingUse { kIgnored, kClosed, kWeighed };

// "ignored", "closed", "weighed".
std::string_view to_string(FindingUse use);

FindingUse finding_use(const FindingRisk& risk, RiskMode mode);

// Adds a blockage to `mission` at every finding `mode` closes and, for kExpected, a hazard at
// every possible blockage (finding_use); returns how many places it closed.
std::size_t close_findings(const SewerMap& map, Mission& mission, RiskMode mode,
                           const RiskTable& table);

}  // namespace sewerplan
