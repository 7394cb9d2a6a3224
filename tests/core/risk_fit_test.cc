// SPDX-License-Identifier: MIT
// Fitting the risk table from outcomes (core/risk_fit.h, issue 34): known counts give the known
// Beta posterior, a rule nobody observed keeps its prior, the fit is deterministic, and a fitted
// table round-trips through its file with its evidence.
#include "sewerplan/core/risk_fit.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/condition_risk.h"

namespace sewerplan {
namespace {

using ::testing::HasSubstr;

// One rule at 0.2 (no quantification), one at 0.1 + 0.01 per percent, one danger rule.
RiskTable table() {
  return {
      .rules = {
          {.code = "BBA", .effect = RiskEffect::kBlockage, .probability = 0.2, .meaning = "roots"},
          {.code = "BBC",
           .effect = RiskEffect::kBlockage,
           .cross_section_percent = true,
           .probability = 0.1,
           .probability_per_percent = 0.01,
           .meaning = "settled deposits"},
          {.code = "BAJ", .effect = RiskEffect::kDanger, .meaning = "displaced joint"}}};
}

RiskObservation seen(std::string code, bool blocked, std::optional<double> q = std::nullopt) {
  return {.finding = {.code = std::move(code), .quantity1 = q}, .blocked = blocked};
}

std::vector<RiskObservation> repeat(const std::string& code, int passed, int blocked,
                                    std::optional<double> q = std::nullopt) {
  std::vector<RiskObservation> out;
  for (int i = 0; i < passed; ++i) out.push_back(seen(code, false, q));
  for (int i = 0; i < blocked; ++i) out.push_back(seen(code, true, q));
  return out;
}

TEST(BetaQuantile, KnownValues) {
  // Beta(1, 1) is uniform; Beta(2, 1) has CDF x^2; Beta(1, 3) has CDF 1 - (1 - x)^3.
  EXPECT_NEAR(beta_quantile(1, 1, 0.05), 0.05, 1e-9);
  EXPECT_NEAR(beta_quantile(2, 1, 0.25), 0.5, 1e-9);
  EXPECT_NEAR(beta_quantile(1, 3, 0.875), 0.5, 1e-9);
  // Symmetric: the median of Beta(7.5, 7.5) is 0.5.
  EXPECT_NEAR(beta_quantile(7.5, 7.5, 0.5), 0.5, 1e-9);
  // Degenerate ends.
  EXPECT_EQ(beta_quantile(0, 3, 0.5), 0);
  EXPECT_EQ(beta_quantile(3, 0, 0.5), 1);
  // Beta(0.4, 1.6) (a prior of strength 2 at 0.2): CDF at the quantile gives back q, checked
  // against the closed form of Beta(a, 1) on a second, skewed case: x^a.
  EXPECT_NEAR(beta_quantile(0.4, 1, 0.05), std::pow(0.05, 1 / 0.4), 1e-9);
}

TEST(RiskFit, KnownCountsGiveTheBetaPosterior) {
  // BBA: prior mean 0.2, strength 2 -> Beta(0.4, 1.6); 8 passes and 2 blockages -> Beta(2.4, 9.6),
  // mean 2.4 / 12 = 0.2 exactly; 18 passes and 2 -> Beta(2.4, 19.6), mean 0.10909.
  Result<RiskTableFit> fit = fit_risk_table(table(), repeat("BBA", 18, 2), {});
  ASSERT_TRUE(fit.has_value()) << fit.error();
  const RiskRule& roots = fit->table.rules[0];
  ASSERT_TRUE(roots.fit.has_value());
  EXPECT_EQ(roots.fit->observations, 20U);
  EXPECT_EQ(roots.fit->blockages, 2U);
  EXPECT_DOUBLE_EQ(roots.fit->mean_prior, 0.2);
  EXPECT_NEAR(roots.fit->mean, 2.4 / 22, 1e-12);
  EXPECT_NEAR(roots.probability, 2.4 / 22, 1e-12);
  EXPECT_NEAR(roots.fit->mean_low, beta_quantile(2.4, 19.6, 0.05), 1e-12);
  EXPECT_NEAR(roots.fit->mean_high, beta_quantile(2.4, 19.6, 0.95), 1e-12);
  EXPECT_LT(roots.fit->mean_low, roots.fit->mean);
  EXPECT_GT(roots.fit->mean_high, roots.fit->mean);
  EXPECT_DOUBLE_EQ(roots.fit->level, 0.9);
  EXPECT_EQ(fit->observations, 20U);
  EXPECT_EQ(fit->unfitted, 0U);
}

TEST(RiskFit, MoreEvidenceNarrowsTheIntervalAndLeavesThePrior) {
  // The same blockage share, 50 %, with 4 and with 400 observations: the posterior mean moves
  // from near the prior's 0.2 to near 0.5, and the interval narrows.
  Result<RiskTableFit> few = fit_risk_table(table(), repeat("BBA", 2, 2), {});
  Result<RiskTableFit> many = fit_risk_table(table(), repeat("BBA", 200, 200), {});
  ASSERT_TRUE(few.has_value() && many.has_value());
  const RiskRuleFit& a = *few->table.rules[0].fit;
  const RiskRuleFit& b = *many->table.rules[0].fit;
  EXPECT_NEAR(a.mean, (0.4 + 2) / 6, 1e-12);
  EXPECT_NEAR(b.mean, (0.4 + 200) / 402, 1e-12);
  EXPECT_GT(a.mean_high - a.mean_low, 5 * (b.mean_high - b.mean_low));
  EXPECT_LT(b.mean_low, 0.5);
  EXPECT_GT(b.mean_high, 0.5);
}

TEST(RiskFit, NoObservationsKeepThePriorAndSaySo) {
  Result<RiskTableFit> fit = fit_risk_table(table(), repeat("BBA", 3, 0), {});
  ASSERT_TRUE(fit.has_value());
  const RiskRule& deposits = fit->table.rules[1];
  ASSERT_TRUE(deposits.fit.has_value());
  EXPECT_EQ(deposits.fit->observations, 0U);
  EXPECT_DOUBLE_EQ(deposits.probability, 0.1);
  EXPECT_DOUBLE_EQ(deposits.probability_per_percent, 0.01);
  EXPECT_DOUBLE_EQ(deposits.fit->mean, 0.1);
  // The prior's own interval: Beta(0.2, 1.8).
  EXPECT_NEAR(deposits.fit->mean_high, beta_quantile(0.2, 1.8, 0.95), 1e-12);
  // A rule that is not a possible blockage is not fitted and carries no evidence.
  EXPECT_EQ(fit->table.rules[2], table().rules[2]);
  // Nothing observed at all: the prior table, every blockage rule marked unobserved.
  Result<RiskTableFit> none = fit_risk_table(table(), {}, {});
  ASSERT_TRUE(none.has_value());
  for (std::size_t i = 0; i < table().rules.size(); ++i) {
    RiskRule rule = none->table.rules[i];
    EXPECT_EQ(rule.fit.has_value(), rule.effect == RiskEffect::kBlockage);
    if (rule.fit) {
      EXPECT_EQ(rule.fit->observations, 0U);
    }
    rule.fit.reset();
    EXPECT_EQ(rule, table().rules[i]);
  }
}

TEST(RiskFit, QuantifiedRulesAreScaledByTheirObservedLevel) {
  // BBC at q = 10 %: the prior says 0.2 for each finding. 10 observations, 5 blocked: posterior
  // mean (0.4 + 5) / 12 = 0.45, so the rule is scaled by 0.45 / 0.2 = 2.25.
  Result<RiskTableFit> fit = fit_risk_table(table(), repeat("BBC", 5, 5, 10.0), {});
  ASSERT_TRUE(fit.has_value());
  const RiskRule& deposits = fit->table.rules[1];
  EXPECT_DOUBLE_EQ(deposits.fit->mean_prior, 0.2);
  EXPECT_NEAR(deposits.fit->mean, 0.45, 1e-12);
  EXPECT_NEAR(deposits.probability, 0.1 * 2.25, 1e-12);
  EXPECT_NEAR(deposits.probability_per_percent, 0.01 * 2.25, 1e-12);
}

TEST(RiskFit, FindingsNotRatedABlockageAreCountedNotFitted) {
  std::vector<RiskObservation> s = repeat("BBA", 1, 0);
  s.push_back(seen("BAJ", false));  // a danger rule
  s.push_back(seen("BXX", true));   // no rule
  Result<RiskTableFit> fit = fit_risk_table(table(), s, {});
  ASSERT_TRUE(fit.has_value());
  EXPECT_EQ(fit->observations, 3U);
  EXPECT_EQ(fit->unfitted, 2U);
  EXPECT_EQ(fit->table.rules[0].fit->observations, 1U);
}

TEST(RiskFit, IsDeterministicAndOrderFree) {
  std::vector<RiskObservation> s = repeat("BBA", 7, 3);
  const std::vector<RiskObservation> more = repeat("BBC", 4, 1, 25.0);
  s.insert(s.begin() + 4, more.begin(), more.end());
  Result<RiskTableFit> a = fit_risk_table(table(), s, {});
  Result<RiskTableFit> b = fit_risk_table(table(), s, {});
  std::reverse(s.begin(), s.end());
  Result<RiskTableFit> c = fit_risk_table(table(), s, {});
  ASSERT_TRUE(a.has_value() && b.has_value() && c.has_value());
  EXPECT_EQ(a->table, b->table);
  EXPECT_EQ(a->table, c->table);
}

TEST(RiskFit, BadOptionsAreErrors) {
  Result<RiskTableFit> strength = fit_risk_table(table(), {}, {.prior_strength = 0});
  ASSERT_FALSE(strength.has_value());
  EXPECT_THAT(strength.error().message, HasSubstr("prior strength"));
  Result<RiskTableFit> level = fit_risk_table(table(), {}, {.level = 1});
  ASSERT_FALSE(level.has_value());
  EXPECT_THAT(level.error().message, HasSubstr("credible level"));
}

TEST(RiskFit, AFittedTableRoundTripsAndBadEvidenceIsNamed) {
  Result<RiskTableFit> fit = fit_risk_table(table(), repeat("BBA", 18, 2), {});
  ASSERT_TRUE(fit.has_value());
  std::ostringstream out;
  write_risk_table_json(fit->table, out);
  Diagnostics d;
  Result<RiskTable> back = read_risk_table_json(out.str(), "fit.json", d);
  ASSERT_TRUE(back.has_value()) << back.error();
  EXPECT_EQ(*back, fit->table);
  EXPECT_EQ(d.warning_count(), 0U);

  std::string bad = out.str();
  const std::string blockages = "\"blockages\": 2";
  ASSERT_NE(bad.find(blockages), std::string::npos);
  bad.replace(bad.find(blockages), blockages.size(), "\"blockages\": 21");
  Diagnostics e;
  Result<RiskTable> wrong = read_risk_table_json(bad, "fit.json", e);
  ASSERT_FALSE(wrong.has_value());
  EXPECT_THAT(wrong.error().message,
              HasSubstr("fit.json:$.rules[0].fit.blockages: error: more than observations (20)"));
}

}  // namespace
}  // namespace sewerplan
