// SPDX-License-Identifier: MIT
#include "sewerplan/core/risk_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sewerplan/core/json_fields.h"

namespace sewerplan {
namespace {

// The continued fraction of the regularised incomplete beta function I_x(a, b) (its even and odd
// terms d_2m = m (b - m) x / ((a + 2m - 1)(a + 2m)), d_2m+1 = -(a + m)(a + b + m) x / ((a + 2m)
// (a + 2m + 1))), evaluated by the modified Lentz method; converges fast for x < (a + 1) /
// (a + b + 2).
double beta_fraction(double a, double b, double x) {
  constexpr double kTiny = 1e-300;
  constexpr double kEpsilon = 1e-15;
  double c = 1;
  double d = 1 - (a + b) * x / (a + 1);
  if (std::abs(d) < kTiny) d = kTiny;
  d = 1 / d;
  double f = d;
  for (int m = 1; m <= 1000; ++m) {
    const double even = m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m));
    d = 1 + even * d;
    c = 1 + even / c;
    if (std::abs(d) < kTiny) d = kTiny;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1 / d;
    f *= d * c;
    const double odd = -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1));
    d = 1 + odd * d;
    c = 1 + odd / c;
    if (std::abs(d) < kTiny) d = kTiny;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1 / d;
    const double step = d * c;
    f *= step;
    if (std::abs(step - 1) < kEpsilon) break;
  }
  return f;
}

// I_x(a, b) for a, b > 0.
double regularised_beta(double a, double b, double x) {
  if (x <= 0) return 0;
  if (x >= 1) return 1;
  const double log_front =
      std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  const double front = std::exp(log_front);
  if (x < (a + 1) / (a + b + 2)) return front * beta_fraction(a, b, x) / a;
  return 1 - front * beta_fraction(b, a, 1 - x) / b;
}

// The prior rule's probability at a finding: probability + per_percent x q, 0..1.
double rule_probability(const RiskRule& rule, const Finding& finding) {
  const double q = finding.quantity1.value_or(0);
  return std::clamp(rule.probability + rule.probability_per_percent * q, 0.0, 1.0);
}

struct Counts {
  std::size_t n = 0;
  std::size_t blocked = 0;
  double prior_sum = 0;  // of the prior's probability at each finding observed
};

}  // namespace

double beta_quantile(double a, double b, double q) {
  if (a <= 0) return 0;
  if (b <= 0) return 1;
  if (q <= 0) return 0;
  if (q >= 1) return 1;
  double lo = 0;
  double hi = 1;
  // I_x is increasing in x; 60 halvings leave an interval below 1e-18.
  for (int i = 0; i < 60 && hi - lo > 1e-12; ++i) {
    const double mid = (lo + hi) / 2;
    (regularised_beta(a, b, mid) < q ? lo : hi) = mid;
  }
  return (lo + hi) / 2;
}

Result<RiskTableFit> fit_risk_table(const RiskTable& prior,
                                    const std::vector<RiskObservation>& seen,
                                    const RiskFitOptions& options) {
  const double k = options.prior_strength;
  if (!(std::isfinite(k) && k > 0)) {
    return Error{ErrorCode::kInvalidArgument,
                 "the prior strength must be a positive number, got " + format_double(k)};
  }
  if (!(options.level > 0 && options.level < 1)) {
    return Error{ErrorCode::kInvalidArgument,
                 "the credible level must be between 0 and 1, got " + format_double(options.level)};
  }
  RiskTableFit fit{.table = prior, .observations = seen.size(), .unfitted = 0};
  std::vector<Counts> counts(prior.rules.size());
  for (const RiskObservation& o : seen) {
    const std::optional<std::size_t> rule = matching_rule(prior, o.finding);
    if (!rule || prior.rules[*rule].effect != RiskEffect::kBlockage) {
      ++fit.unfitted;
      continue;
    }
    Counts& c = counts[*rule];
    ++c.n;
    if (o.blocked) ++c.blocked;
    c.prior_sum += rule_probability(prior.rules[*rule], o.finding);
  }
  const double tail = (1 - options.level) / 2;
  for (std::size_t i = 0; i < prior.rules.size(); ++i) {
    const RiskRule& before = prior.rules[i];
    if (before.effect != RiskEffect::kBlockage) continue;
    RiskRule& rule = fit.table.rules[i];
    const Counts& c = counts[i];
    const double n = static_cast<double>(c.n);
    const double y = static_cast<double>(c.blocked);
    const double m = c.n > 0 ? c.prior_sum / n : std::clamp(before.probability, 0.0, 1.0);
    const double a = k * m + y;
    const double b = k * (1 - m) + (n - y);
    const double mean = a / (a + b);
    if (c.n > 0) {
      if (m > 0) {
        const double scale = mean / m;
        rule.probability = std::min(1.0, before.probability * scale);
        rule.probability_per_percent = std::min(1.0, before.probability_per_percent * scale);
      } else {
        rule.probability = mean;
      }
    }
    rule.fit = RiskRuleFit{.observations = c.n,
                           .blockages = c.blocked,
                           .prior_strength = k,
                           .prior_probability = before.probability,
                           .mean_prior = m,
                           .mean = mean,
                           .mean_low = beta_quantile(a, b, tail),
                           .mean_high = beta_quantile(a, b, 1 - tail),
                           .level = options.level};
  }
  return fit;
}

}  // namespace sewerplan
