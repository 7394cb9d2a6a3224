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
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

enum class RiskEffect { kNone, kDanger, kBlockage, kImpassable };

std::string_view to_string(RiskEffect effect);

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
  std::string meaning;  // "roots", for reasons
  friend bool operator==(const RiskRule&, const RiskRule&) = default;
};

struct RiskTable {
  std::vector<RiskRule> rules;
  friend bool operator==(const RiskTable&, const RiskTable&) = default;
};

// The defaults of docs/formats/isybau.md.
RiskTable default_risk_table();

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

// The kImpassable findings as mission blockages, in the map's order of findings.
std::vector<Blockage> impassable_blockages(const SewerMap& map,
                                           const std::vector<FindingRisk>& risks);

}  // namespace sewerplan
