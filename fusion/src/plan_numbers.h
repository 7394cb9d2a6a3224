// SPDX-License-Identifier: MIT
// The angle unit and the rounding of the numbers fusion's motion plans carry, private to fusion.
//
// Robot profiles and maps give angles in degrees, the geometry computes in radians: kDegToRad
// converts. Waypoints and durations are rounded (rounded(v, 1e4): 0.1 mm) before they are
// stored, so that a plan prints the same short numbers on every machine and a cached plan equals a
// fresh one (passage_precompute.h).
#pragma once

#include <cmath>
#include <numbers>

namespace sewerplan::fusion::detail {

inline constexpr double kDegToRad = std::numbers::pi / 180.0;

// Rounded to 1 / scale, dividing by the exact scale so that 0.495 prints as 0.495.
inline double rounded(double v, double scale) { return std::round(v * scale) / scale; }

}  // namespace sewerplan::fusion::detail
