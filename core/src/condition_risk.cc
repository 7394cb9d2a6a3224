// SPDX-License-Identifier: MIT
#include "sewerplan/core/condition_risk.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "sewerplan/core/message_text.h"

#include "risk_effect_names.h"

namespace sewerplan {
namespace {

const RiskRule* match(const RiskTable& table, const Finding& f) {
  const std::optional<std::size_t> i = matching_rule(table, f);
  return i ? &table.rules[*i] : nullptr;
}

}  // namespace

std::optional<std::size_t> matching_rule(const RiskTable& table, const Finding& finding) {
  for (std::size_t i = 0; i < table.rules.size(); ++i) {
    const RiskRule& r = table.rules[i];
    if (finding.code.starts_with(r.code) &&
        finding.characterisation.starts_with(r.characterisation)) {
      return i;
    }
  }
  return std::nullopt;
}

std::string_view to_string(RiskEffect effect) {
  return detail::name_of(detail::kRiskEffectNames, effect);
}

RiskTable default_risk_table() {
  using E = RiskEffect;
  return {
      .rules = {
          // DIN EN 13508-2 tells a break from a collapse by the characterisation: A the
          // pipe's pieces displaced but all there, B pieces of the wall missing (soil and
          // shards can fall in), C the structure destroyed. A BAC without one is taken as
          // the worst.
          {.code = "BAC", .characterisation = "C", .effect = E::kImpassable, .meaning = "collapse"},
          {.code = "BAC",
           .characterisation = "B",
           .effect = E::kBlockage,
           .probability = 0.5,
           .meaning = "break, wall pieces missing"},
          {.code = "BAC", .characterisation = "A", .effect = E::kDanger, .meaning = "break"},
          {.code = "BAC", .effect = E::kImpassable, .meaning = "break or collapse"},
          {.code = "BAA",
           .effect = E::kDanger,
           .cross_section_percent = true,
           .meaning = "deformation"},
          {.code = "BBA",
           .effect = E::kBlockage,
           .cross_section_percent = true,
           .probability = 0.2,
           .probability_per_percent = 0.01,
           .meaning = "roots"},
          {.code = "BBB",
           .effect = E::kBlockage,
           .cross_section_percent = true,
           .probability = 0.05,
           .probability_per_percent = 0.005,
           .meaning = "attached deposits"},
          {.code = "BBC",
           .effect = E::kBlockage,
           .cross_section_percent = true,
           .probability = 0.1,
           .probability_per_percent = 0.01,
           .meaning = "settled deposits"},
          {.code = "BBE",
           .effect = E::kBlockage,
           .cross_section_percent = true,
           .probability = 0.3,
           .probability_per_percent = 0.01,
           .meaning = "obstacle"},
          {.code = "BAG",
           .effect = E::kDanger,
           .cross_section_percent = true,
           .meaning = "intruding connection"},
          {.code = "BAJ", .effect = E::kDanger, .meaning = "displaced joint"},
          {.code = "BAH", .effect = E::kDanger, .meaning = "defective connection"},
          {.code = "BAI", .effect = E::kDanger, .meaning = "intruding sealing material"},
      }};
}

std::vector<FindingRisk> assess_findings(const SewerMap& map, const RobotProfile& profile,
                                         const RiskTable& table) {
  std::vector<FindingRisk> risks;
  const std::span<const Finding> findings = map.findings();
  risks.reserve(findings.size());
  for (std::size_t i = 0; i < findings.size(); ++i) {
    const Finding& f = findings[i];
    FindingRisk risk{.finding = i};
    const RiskRule* rule = match(table, f);
    if (rule == nullptr) {
      risks.push_back(std::move(risk));
      continue;
    }
    risk.effect = rule->effect;
    risk.reason = f.code + " " + rule->meaning;
    const double q = f.quantity1.value_or(0);
    if (rule->cross_section_percent && f.quantity1) {
      const double left = map.pipe(f.pipe).diameter_m * (1 - std::clamp(q, 0.0, 100.0) / 100);
      if (left < profile.body_width_m) {
        risk.effect = RiskEffect::kImpassable;
        const LimitText t = limit_text(left, profile.body_width_m);
        risk.reason += " leaves " + t.value + " m, less than the robot's " + t.limit + " m";
      }
    }
    switch (risk.effect) {
      case RiskEffect::kImpassable:
        risk.blockage_probability = 1;
        break;
      case RiskEffect::kBlockage:
        risk.blockage_probability =
            std::clamp(rule->probability + rule->probability_per_percent * q, 0.0, 1.0);
        break;
      case RiskEffect::kNone:
      case RiskEffect::kDanger:
        break;
    }
    risks.push_back(std::move(risk));
  }
  return risks;
}

std::vector<Blockage> impassable_blockages(const SewerMap& map,
                                           const std::vector<FindingRisk>& risks) {
  std::vector<Blockage> out;
  for (const FindingRisk& r : risks) {
    if (r.effect != RiskEffect::kImpassable) continue;
    const Finding& f = map.findings()[r.finding];
    out.push_back({.pipe = f.pipe, .offset_m = f.offset_m});
  }
  return out;
}

std::vector<Hazard> blockage_hazards(const SewerMap& map, const std::vector<FindingRisk>& risks) {
  std::vector<Hazard> out;
  for (const FindingRisk& r : risks) {
    if (r.effect != RiskEffect::kBlockage || r.blockage_probability <= 0) continue;
    const Finding& f = map.findings()[r.finding];
    out.push_back({.pipe = f.pipe,
                   .offset_m = f.offset_m,
                   .probability = r.blockage_probability,
                   .reason = r.reason});
  }
  return out;
}

std::optional<RiskMode> risk_mode_from_string(std::string_view name) {
  if (name == "ignore") return RiskMode::kIgnore;
  if (name == "impassable") return RiskMode::kImpassable;
  if (name == "avoid") return RiskMode::kAvoid;
  if (name == "expected") return RiskMode::kExpected;
  return std::nullopt;
}

std::string_view to_string(FindingUse use) {
  switch (use) {
    case FindingUse::kIgnored:
      return "ignored";
    case FindingUse::kClosed:
      return "closed";
    case FindingUse::kWeighed:
      return "weighed";
  }
  return "ignored";
}

FindingUse finding_use(const FindingRisk& risk, RiskMode mode) {
  switch (mode) {
    case RiskMode::kIgnore:
      return FindingUse::kIgnored;
    case RiskMode::kImpassable:
      return risk.effect == RiskEffect::kImpassable ? FindingUse::kClosed : FindingUse::kIgnored;
    case RiskMode::kAvoid:
      return risk.effect != RiskEffect::kNone ? FindingUse::kClosed : FindingUse::kIgnored;
    case RiskMode::kExpected:
      if (risk.effect == RiskEffect::kImpassable) return FindingUse::kClosed;
      return risk.effect == RiskEffect::kBlockage && risk.blockage_probability > 0
                 ? FindingUse::kWeighed
                 : FindingUse::kIgnored;
  }
  return FindingUse::kIgnored;
}

std::size_t close_findings(const SewerMap& map, Mission& mission, RiskMode mode,
                           const RiskTable& table) {
  if (mode == RiskMode::kIgnore) return 0;
  std::size_t closed = 0;
  for (const FindingRisk& r : assess_findings(map, mission.profile, table)) {
    const Finding& f = map.findings()[r.finding];
    switch (finding_use(r, mode)) {
      case FindingUse::kClosed:
        mission.blockages.push_back({.pipe = f.pipe, .offset_m = f.offset_m});
        ++closed;
        break;
      case FindingUse::kWeighed:
        mission.hazards.push_back({.pipe = f.pipe,
                                   .offset_m = f.offset_m,
                                   .probability = r.blockage_probability,
                                   .reason = r.reason});
        break;
      case FindingUse::kIgnored:
        break;
    }
  }
  return closed;
}

}  // namespace sewerplan
