// SPDX-License-Identifier: MIT
// The risk table as JSON (condition_risk.h, docs/formats/risk-table.md).
#include <cmath>
#include <cstdint>

#include <nlohmann/json.hpp>

#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/message_text.h"
#include "sewerplan/core/text_file.h"

#include "risk_effect_names.h"

namespace sewerplan {
namespace {

using Need = JsonFields::Need;

// A fitted rule's evidence ("fit", risk_fit.h): counts, the prior, and the posterior of the mean
// probability of the findings observed with its credible interval.
std::optional<RiskRuleFit> read_fit(JsonFields& rule, const std::string& file, Diagnostics& d) {
  const std::optional<JsonElement> json = rule.member("fit", Need::kOptional);
  if (!json) return std::nullopt;
  JsonFields f(*json, rule.path() + ".fit", file, d);
  if (!f.is_object()) return std::nullopt;
  f.warn_unknown({"observations", "blockages", "prior_strength", "prior_probability", "mean_prior",
                  "mean", "mean_low", "mean_high", "level"});
  RiskRuleFit fit;
  constexpr std::uint64_t kMaxCount = std::uint64_t{1} << 53;
  fit.observations = f.count("observations", kMaxCount).value_or(0);
  fit.blockages = f.count("blockages", kMaxCount).value_or(0);
  if (fit.blockages > fit.observations) {
    f.error("blockages", "more than observations (" + std::to_string(fit.observations) + ")");
  }
  fit.prior_strength = f.number("prior_strength").value_or(0);
  if (!(std::isfinite(fit.prior_strength) && fit.prior_strength > 0)) {
    f.error("prior_strength",
            "must be a positive number, got " + format_double(fit.prior_strength));
  }
  for (auto [key, field] : {std::pair{"prior_probability", &fit.prior_probability},
                            {"mean_prior", &fit.mean_prior},
                            {"mean", &fit.mean},
                            {"mean_low", &fit.mean_low},
                            {"mean_high", &fit.mean_high},
                            {"level", &fit.level}}) {
    const std::optional<double> v = f.number(key);
    if (!v) continue;
    if (!(*v >= 0 && *v <= 1)) {
      f.error(key, "must be a probability from 0 to 1, got " + format_double(*v));
    }
    *field = *v;
  }
  if (!(fit.mean_low <= fit.mean && fit.mean <= fit.mean_high)) {
    f.error("mean", "must lie within mean_low and mean_high (" + format_double(fit.mean_low) +
                        " to " + format_double(fit.mean_high) + "), got " +
                        format_double(fit.mean));
  }
  return fit;
}

std::optional<RiskRule> read_rule(JsonElement json, const std::string& path,
                                  const std::string& file, Diagnostics& d) {
  JsonFields f(json, path, file, d);
  f.warn_unknown({"code", "characterisation", "effect", "cross_section_percent", "probability",
                  "probability_per_percent", "meaning", "fit"});
  const std::size_t errors_before = d.error_count();
  RiskRule rule;
  rule.code = f.string("code").value_or("");
  if (rule.code.empty() && errors_before == d.error_count()) {
    d.error(f.where("code"), "must name a DIN EN 13508-2 code or a prefix of one");
  }
  rule.characterisation = f.string("characterisation", Need::kOptional).value_or("");
  if (auto effect = f.string("effect")) {
    if (const std::optional<RiskEffect> e = detail::value_of(detail::kRiskEffectNames, *effect)) {
      rule.effect = *e;
    } else {
      d.error(f.where("effect"), "unknown effect '" + *effect + "' (" +
                                     detail::names_joined(detail::kRiskEffectNames) + ")");
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
  rule.fit = read_fit(f, file, d);
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
    if (const std::optional<RiskRuleFit>& fit = r.fit) {
      nlohmann::ordered_json e;
      e["observations"] = fit->observations;
      e["blockages"] = fit->blockages;
      e["prior_strength"] = fit->prior_strength;
      e["prior_probability"] = fit->prior_probability;
      e["mean_prior"] = fit->mean_prior;
      e["mean"] = fit->mean;
      e["mean_low"] = fit->mean_low;
      e["mean_high"] = fit->mean_high;
      e["level"] = fit->level;
      j["fit"] = std::move(e);
    }
    rules.push_back(std::move(j));
  }
  nlohmann::ordered_json doc;
  doc["format"] = kRiskTableJsonFormat;
  doc["version"] = kRiskTableJsonVersion;
  doc["rules"] = std::move(rules);
  out << doc.dump(2) << '\n';
}

}  // namespace sewerplan
