// SPDX-License-Identifier: MIT
// An independent transverse Mercator projection, to check PROJ against: Krüger's series to the
// fourth order in the third flattening n (Karney 2011, "Transverse Mercator with an accuracy of a
// few nanometers", eq. 7 and 35), better than a millimetre within a few degrees of the meridian.
#pragma once

#include <cmath>
#include <numbers>

namespace sewerplan::testing {

struct TransverseMercator {
  double a;             // semi-major axis, m
  double f;             // flattening
  double lon0_deg;      // central meridian
  double k0;            // scale on it
  double false_east_m;  // easting of the meridian
};

inline constexpr TransverseMercator kUtm32{6378137.0, 1 / 298.257222101, 9, 0.9996, 500000};
inline constexpr TransverseMercator kGaussKruger3{6377397.155, 1 / 299.1528128, 9, 1, 3500000};

struct EastNorth {
  double east;
  double north;
};

inline EastNorth transverse_mercator(const TransverseMercator& p, double lon_deg, double lat_deg) {
  const double n = p.f / (2 - p.f);
  const double n2 = n * n;
  const double n3 = n2 * n;
  const double n4 = n3 * n;
  const double big_a = p.a / (1 + n) * (1 + n2 / 4 + n4 / 64);
  const double alpha[4] = {n / 2 - 2 * n2 / 3 + 5 * n3 / 16 + 41 * n4 / 180,
                           13 * n2 / 48 - 3 * n3 / 5 + 557 * n4 / 1440,
                           61 * n3 / 240 - 103 * n4 / 140, 49561 * n4 / 161280};
  const double deg = std::numbers::pi / 180;
  const double phi = lat_deg * deg;
  const double lambda = (lon_deg - p.lon0_deg) * deg;
  const double e = 2 * std::sqrt(n) / (1 + n);  // the eccentricity
  const double t = std::sinh(std::atanh(std::sin(phi)) - e * std::atanh(e * std::sin(phi)));
  const double xi_prime = std::atan2(t, std::cos(lambda));
  const double eta_prime = std::atanh(std::sin(lambda) / std::sqrt(1 + t * t));
  double xi = xi_prime;
  double eta = eta_prime;
  for (int j = 1; j <= 4; ++j) {
    xi += alpha[j - 1] * std::sin(2 * j * xi_prime) * std::cosh(2 * j * eta_prime);
    eta += alpha[j - 1] * std::cos(2 * j * xi_prime) * std::sinh(2 * j * eta_prime);
  }
  return {.east = p.false_east_m + p.k0 * big_a * eta, .north = p.k0 * big_a * xi};
}

}  // namespace sewerplan::testing
