// SPDX-License-Identifier: MIT
// Fitting a risk table from outcomes: what robots met at the findings they drove past.
//
// A risk table (condition_risk.h) says how likely each finding (code, characterisation) stops a
// robot. Robots observe it: each finding a mission drove past safely, or was stopped by, is an
// observation of its rule (the first rule of the prior table that matches it). The fit is Bayesian
// and per rule, with the prior table as the prior:
//   - m, the prior's blockage probability of the findings observed: the mean over them of the
//     prior rule's probability at each finding's quantification (probability + per_percent x q,
//     at most 1);
//   - prior Beta(k m, k (1 - m)): mean m, the weight of k observations (k = prior_strength);
//   - n observations, y of them blockages: posterior Beta(k m + y, k (1 - m) + n - y), its mean
//     (k m + y) / (k + n) and an equal-tailed credible interval at `level`;
//   - the fitted rule is the prior rule scaled by posterior mean / m (probability and
//     probability_per_percent alike, each at most 1): the fit estimates the rule's level and
//     keeps how it grows with the quantification. A rule whose prior predicts 0 for every
//     finding observed gets the posterior mean as its probability.
// Rules no observation matched keep the prior (RiskRuleFit::observations 0). Only kBlockage rules
// are fitted; an observation of a finding the prior table rates otherwise (impassable, a danger,
// nothing, or no rule) is counted in RiskTableFit::unfitted, and the rule is kept as it is.
//
//   std::vector<RiskObservation> seen = {{finding, /*blocked=*/false}, ...};
//   Result<RiskTableFit> fit = fit_risk_table(default_risk_table(), seen, {});
//   write_risk_table_json(fit->table, out);  // with each rule's "fit"
//
// Thread safety: Plain values and pure functions: const access from several threads is safe.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

// One finding a robot drove past or was stopped by, in one mission.
struct RiskObservation {
  Finding finding;  // its code, characterisation and quantification decide its rule
  bool blocked = false;
  friend bool operator==(const RiskObservation&, const RiskObservation&) = default;
};

struct RiskFitOptions {
  // k: how many observations the prior table weighs. 2, as the Replanner's hazard learning
  // (executor ReplannerOptions::hazard_learning.prior_strength): one mission's pass moves a rule
  // as much as it moves a hazard's probability within a mission.
  double prior_strength = 2;
  double level = 0.9;  // of the credible intervals, 0 < level < 1
};

struct RiskTableFit {
  // The prior table with each kBlockage rule fitted and its RiskRule::fit set; other rules as
  // they were.
  RiskTable table;
  std::size_t observations = 0;  // all, fitted or not
  // Observations of findings the prior table does not rate as a possible blockage: not fitted.
  std::size_t unfitted = 0;
};

// The fit described above. Errors (kInvalidArgument): prior_strength not positive and finite,
// level not within (0, 1).
Result<RiskTableFit> fit_risk_table(const RiskTable& prior,
                                    const std::vector<RiskObservation>& seen,
                                    const RiskFitOptions& options);

// The q-quantile of Beta(a, b), 0 <= q <= 1, a, b >= 0 (a = 0: all mass at 0; b = 0: at 1).
// Deterministic bisection on the regularised incomplete beta function, to 1e-12.
double beta_quantile(double a, double b, double q);

}  // namespace sewerplan
