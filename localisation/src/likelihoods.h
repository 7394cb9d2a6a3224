// SPDX-License-Identifier: MIT
// The filter's likelihoods: Gaussians along a pipe, and what a manhole the map lacks, or a
// detection of nothing, is likely to look like (docs/localisation.md, "Alternatives").
//
// compare() (core/manhole_signature.h) scores a signature against the map's as a sum of
// -z^2/2 - log(sigma) per measurement, leaving out each Gaussian's -log(sqrt(2 pi)). The densities
// here leave it out the same way, so that their log-likelihoods are comparable with compare()'s:
// a measurement of which nothing is known is uniform over its range, log(1/range) + log(sqrt(2
// pi)).
#pragma once

#include <cmath>
#include <limits>
#include <optional>

#include "sewerplan/core/manhole_signature.h"

namespace sewerplan::localisation::detail {

using sewerplan::kLogSqrtTwoPi;
inline constexpr double kNegativeInfinity = -std::numeric_limits<double>::infinity();
// Variances below this are taken as this (a place known to 1 cm), so that a Gaussian stays finite.
inline constexpr double kMinVarianceM2 = 1e-4;

// log N(x; mean, var), the true density (per metre).
double log_normal(double x, double mean, double var);
// log P(X <= x) for X ~ N(0, 1), finite down to far in the tail.
double log_phi(double z);
// The robot's place along a pipe against where the map puts a mouth: a Gaussian of the odometry's
// variance plus the map's (its pipe lengths', LocalisationOptions::length_sd_fraction), and with
// `share` of the weight the odometry's part `scale` times as wide: a drive may slip far more than
// its standard deviation (a wet pipe), a map's length is off by a bounded share
// (LocalisationOptions::odometry_outlier_share). Before, the tails widened the map's part too, and
// a mapped manhole 25 m beyond where a 15 m drive stopped in a 40 m pipe stayed as likely as a
// junction there.
struct OdometryTails {
  double share = 0;
  double scale = 1;
};
struct PlaceSpread {
  double odometry_var = 0;
  double map_var = 0;
  OdometryTails tails;
};
// The density of the place at `x` about `mean`, and the log-probability that the place lies
// at most `distance` beyond the mean (the lower tail at -distance: log P(X - mean <= distance)).
double log_normal(double x, double mean, const PlaceSpread& spread);
double log_phi_within(double distance, const PlaceSpread& spread);
// log(1 - exp(a)) for a <= 0.
double log1m_exp(double a);
// log(exp(a) + exp(b)).
double log_add(double a, double b);

// The Gaussian term compare() uses: -z^2/2 - log(sigma).
double gaussian_term(double difference, double sigma);

// The log-likelihood of `observed` if it is a manhole the map lacks in a pipe of clear size
// `pipe_diameter_m`: the arrival mouth and one mouth straight on (within the direction noise) are
// that pipe's; every other mouth and each step are unknown; the shaft is a manhole's, at least
// `min_shaft_m` wide (uniform from there up to the largest shaft, a Gaussian tail below). Needs two
// mouths or more (a junction in a pipe continues it): kNegativeInfinity with fewer.
double unmapped_junction_log_likelihood(const ManholeSignature& observed, double pipe_diameter_m,
                                        double min_shaft_m, const SignatureNoise& noise);

// The log-density (per degree) of a turn the robot's joints measured at `measured_deg` where the
// hypothesis's map has `mapped_deg` between the two mouths: the joints' Gaussian (`sd_deg`); with
// `off_share` of the map's slots off by up to `off_max_deg`, either of the two mouths off (uniform
// within that, widened by 3 sd); and a floor for a turn nothing on the map explains
// (kTurnOutlierShare, uniform over 360 degrees), so that no hypothesis is ruled out by one angle.
struct TurnModel {
  double sd_deg = 1;
  double off_share = 0;
  double off_max_deg = 0;
};
inline constexpr double kTurnOutlierShare = 1e-3;
double turn_log_likelihood(double measured_deg, double mapped_deg, const TurnModel& model);

// The log-likelihood of `observed` if the detection saw nothing real (the pipe widening, a joint):
// every measurement unknown, but the shaft no wider than a manhole's smallest (`min_shaft_m`), a
// wider one penalised as a Gaussian in the shaft's noise: a man-entry shaft seen is a manhole. (On
// AIS, 200 runs of the realistic world, a junction the map lacks with a 1 m shaft, in a pipe
// narrower than mapped, was taken for a false detection; sure it was still in the pipe, the robot
// was called stuck at the junction.)
double false_detection_log_likelihood(const ManholeSignature& observed, double min_shaft_m,
                                      const SignatureNoise& noise);

}  // namespace sewerplan::localisation::detail
