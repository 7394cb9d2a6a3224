// SPDX-License-Identifier: MIT
// The risk table as JSON (condition_risk.h, docs/formats/risk-table.md).
#include <nlohmann/json.hpp>

#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/message_text.h"
#include "sewerplan/core/text_file.h"

namespace sewerplan {
namespace {

using Need = JsonFields::Need;

constexpr RiskEffect kEffects[] = {RiskEffect::kNone, RiskEffect::kDanger, RiskEffect::kBlockage,
                                   RiskEffect::kImpassable};

std::optional<RiskRule> read_rule(JsonElement json, const std::string& path,
                                  const std::string& file, Diagnostics& d) {
  JsonFields f(json, path, file, d);
  f.warn_unknown({"code", "characterisation", "effect", "cross_section_percent", "probability",
                  "probability_per_percent", "meaning"});
  const std::size_t errors_before = d.error_count();
  RiskRule rule;
  rule.code = f.string("code").value_or("");
  if (rule.code.empty() && errors_before == d.error_count()) {
    d.error(f.where("code"), "must name a DIN EN 13508-2 code or a prefix of one");
  }
  rule.characterisation = f.string("characterisation", Need::kOptional).value_or("");
  if (auto effect = f.string("effect")) {
    bool known = false;
    for (RiskEffect e : kEffects) {
      if (to_string(e) == *effect) {
        rule.effect = e;
        known = true;
      }
    }
    if (!known) {
      d.error(f.where("effect"),
              "unknown effect '" + *effect + "' (none, danger, blockage, impassable)");
    }
  }
  rule.cross_section_percent = f.boolean("cross_section_percent", Need::kOptional).value_or(false);
  auto share = [&](std::string_view key) {
    const double v = f.number(key, Need::kOptional).value_or(0);
    if (!(v >= 0 && v <= 1)) {
      d.error(f.where(key), "must be a probability from 0 to 1, got " + format_double(v));
    }
    return v;
  };
  rule.probability = share("probability");
  rule.probability_per_percent = share("probability_per_percent");
  rule.meaning = f.string("meaning", Need::kOptional).value_or(rule.code);
  if (d.error_count() > errors_before) return std::nullopt;
  return rule;
}

}  // namespace

Result<RiskTable> read_risk_table_json(std::string_view text, const std::string& file_name,
                                       Diagnostics& diagnostics) {
  const Diagnostics::Mark before = diagnostics.mark();
  auto doc = JsonDocument::parse(text, file_name, diagnostics);
  if (!doc) return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  JsonFields root(doc->root(), "$", file_name, diagnostics);
  root.warn_unknown({"format", "version", "rules"});
  if (auto format = root.string("format"); format && *format != kRiskTableJsonFormat) {
    diagnostics.error(root.where("format"), "expected \"" + std::string(kRiskTableJsonFormat) +
                                                "\", got " + input_quoted(*format));
  }
  if (auto version = root.number("version"); version && *version != kRiskTableJsonVersion) {
    diagnostics.error(root.where("version"), "unsupported version " + format_double(*version));
  }
  RiskTable table;
  if (auto rules = root.array("rules")) {
    std::size_t i = 0;
    for (JsonElement r : *rules) {
      if (auto rule = read_rule(r, indexed("$.rules", i++), file_name, diagnostics)) {
        table.rules.push_back(std::move(*rule));
      }
    }
  }
  if (diagnostics.has_errors_since(before))
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  return table;
}

Result<RiskTable> read_risk_table(const std::filesystem::path& path, Diagnostics& diagnostics) {
  Result<std::string> text = read_text_file(path);
  if (!text.has_value()) return text.error();
  return read_risk_table_json(*text, path.string(), diagnostics);
}

void write_risk_table_json(const RiskTable& table, std::ostream& out) {
  nlohmann::ordered_json rules = nlohmann::ordered_json::array();
  for (const RiskRule& r : table.rules) {
    nlohmann::ordered_json j;
    j["code"] = r.code;
    if (!r.characterisation.empty()) j["characterisation"] = r.characterisation;
    j["effect"] = to_string(r.effect);
    if (r.cross_section_percent) j["cross_section_percent"] = true;
    if (r.probability != 0) j["probability"] = r.probability;
    if (r.probability_per_percent != 0) j["probability_per_percent"] = r.probability_per_percent;
    j["meaning"] = r.meaning;
    rules.push_back(std::move(j));
  }
  nlohmann::ordered_json doc;
  doc["format"] = kRiskTableJsonFormat;
  doc["version"] = kRiskTableJsonVersion;
  doc["rules"] = std::move(rules);
  out << doc.dump(2) << '\n';
}

}  // namespace sewerplan
