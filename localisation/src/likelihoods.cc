// SPDX-License-Identifier: MIT
#include "likelihoods.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "sewerplan/core/map_queries.h"

namespace sewerplan::localisation::detail {
namespace {

// The ranges of what is unknown (core's, and a shaft of 0.8-2.8 m: docs/localisation.md).
constexpr double kDirectionRangeDeg = kUnknownDirectionRangeDeg;
constexpr double kStepRangeM = kUnknownStepRangeM;
constexpr double kDiameterRangeM = kUnknownDiameterRangeM;
constexpr double kShaftRangeM = 2.0;

double unknown(double range) { return unknown_log_likelihood(range); }

double unknown_slot() { return unknown_mouth_log_likelihood(); }

}  // namespace

double log_normal(double x, double mean, double var) {
  const double v = std::max(var, kMinVarianceM2);
  const double d = x - mean;
  return -0.5 * d * d / v - 0.5 * std::log(v) - kLogSqrtTwoPi;
}

double log_phi(double z) {
  if (z > -30) return std::log(0.5 * std::erfc(-z / std::sqrt(2.0)));
  // Mills' ratio: Phi(z) ~ phi(z) / |z| far in the lower tail.
  return -0.5 * z * z - std::log(-z) - kLogSqrtTwoPi;
}

namespace {

// The two variances of a spread: the usual one, and the outliers'.
std::pair<double, double> variances(const PlaceSpread& spread) {
  const double scale2 = spread.tails.scale * spread.tails.scale;
  return {std::max(spread.odometry_var + spread.map_var, kMinVarianceM2),
          std::max(scale2 * spread.odometry_var + spread.map_var, kMinVarianceM2)};
}

}  // namespace

double log_normal(double x, double mean, const PlaceSpread& spread) {
  const auto [usual, wide] = variances(spread);
  if (spread.tails.share <= 0) return log_normal(x, mean, usual);
  return log_add(std::log1p(-spread.tails.share) + log_normal(x, mean, usual),
                 std::log(spread.tails.share) + log_normal(x, mean, wide));
}

double log_phi_within(double distance, const PlaceSpread& spread) {
  const auto [usual, wide] = variances(spread);
  if (spread.tails.share <= 0) return log_phi(distance / std::sqrt(usual));
  return log_add(std::log1p(-spread.tails.share) + log_phi(distance / std::sqrt(usual)),
                 std::log(spread.tails.share) + log_phi(distance / std::sqrt(wide)));
}

double log1m_exp(double a) {
  if (a >= 0) return kNegativeInfinity;
  return a > -0.693 ? std::log(-std::expm1(a)) : std::log1p(-std::exp(a));
}

double log_add(double a, double b) {
  if (a == kNegativeInfinity) return b;
  if (b == kNegativeInfinity) return a;
  const double hi = std::max(a, b);
  return hi + std::log1p(std::exp(std::min(a, b) - hi));
}

double gaussian_term(double difference, double sigma) {
  const double z = difference / sigma;
  return -0.5 * z * z - std::log(sigma);
}

double unmapped_junction_log_likelihood(const ManholeSignature& observed, double pipe_diameter_m,
                                        double min_shaft_m, const SignatureNoise& noise) {
  const std::size_t n = observed.slots.size();
  if (n < 2) return kNegativeInfinity;
  double best_straight = kNegativeInfinity;
  for (std::size_t i = 1; i < n; ++i) {
    const SlotSighting& s = observed.slots[i];
    const double straight =
        gaussian_term(normalize_deg(s.relative_deg - 180.0), noise.direction_deg) +
        unknown(kStepRangeM) + gaussian_term(s.diameter_m - pipe_diameter_m, noise.diameter_m);
    best_straight = std::max(best_straight, straight);
  }
  // A shaft below a manhole's is a widening of the pipe, not a manhole (a false detection).
  const double narrower_m = std::max(0.0, min_shaft_m - observed.shaft_diameter_m);
  const double shaft = unknown(std::max(kShaftRangeM - min_shaft_m, noise.shaft_m)) -
                       0.5 * (narrower_m / noise.shaft_m) * (narrower_m / noise.shaft_m);
  return gaussian_term(observed.slots[0].diameter_m - pipe_diameter_m, noise.diameter_m) +
         best_straight + static_cast<double>(n - 2) * unknown_slot() + shaft;
}

double turn_log_likelihood(double measured_deg, double mapped_deg, const TurnModel& model) {
  const double off = normalize_deg(measured_deg - mapped_deg);
  // Either of the two mouths off the map's azimuth.
  const double either_off = 1 - (1 - model.off_share) * (1 - model.off_share);
  const double right = (1 - either_off - kTurnOutlierShare) *
                       std::exp(log_normal(off, 0, model.sd_deg * model.sd_deg));
  const double half_width = model.off_max_deg + 3 * model.sd_deg;
  const double wrong = std::abs(off) <= half_width ? either_off / (2 * half_width) : 0.0;
  return std::log(right + wrong + kTurnOutlierShare / kDirectionRangeDeg);
}

double false_detection_log_likelihood(const ManholeSignature& observed, double min_shaft_m,
                                      const SignatureNoise& noise) {
  const auto n = static_cast<double>(observed.slots.size());
  const double wider_m = std::max(0.0, observed.shaft_diameter_m - min_shaft_m);
  const double shaft = unknown(std::max(min_shaft_m, noise.shaft_m)) -
                       0.5 * (wider_m / noise.shaft_m) * (wider_m / noise.shaft_m);
  return unknown(kDiameterRangeM) + (n - 1) * unknown_slot() + shaft;
}

}  // namespace sewerplan::localisation::detail
