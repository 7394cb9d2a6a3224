// SPDX-License-Identifier: MIT
#include "sewerplan/fusion/manhole_geometry.h"

#include <cmath>
#include <numbers>

#include "sewerplan/core/map_queries.h"

#include "plan_numbers.h"

namespace sewerplan::fusion {
namespace {

using detail::kDegToRad;

// Inside the strip of half-width `half_width_m` along the unit direction at `azimuth_deg`,
// from the axis outwards.
bool in_strip(double x, double y, double azimuth_deg, double half_width_m) {
  if (half_width_m < 0) return false;
  const double cx = std::cos(azimuth_deg * kDegToRad);
  const double cy = std::sin(azimuth_deg * kDegToRad);
  const double along = x * cx + y * cy;
  const double across = -x * cy + y * cx;
  return along >= 0 && std::abs(across) <= half_width_m;
}

}  // namespace

double RobotBody::min_turn_radius_m() const {
  return segment_length_m / (2 * std::sin(yaw_max_deg * kDegToRad / 2));
}

double RobotBody::bend_margin_m() const {
  const double r = min_turn_radius_m();
  return r - std::sqrt(r * r - segment_length_m * segment_length_m / 4);
}

double RobotBody::max_climb_m() const {
  return segment_length_m * std::sin(pitch_max_deg * kDegToRad);
}

RobotBody robot_body(const RobotProfile& p) {
  return RobotBody{.segment_count = p.segment_count,
                   .segment_length_m = p.length_m / p.segment_count,
                   .width_m = p.body_width_m,
                   .yaw_max_deg = p.joint_yaw_max_deg,
                   .pitch_max_deg = p.joint_pitch_max_deg};
}

std::ostream& operator<<(std::ostream& os, const PassageGeometry& g) {
  return os << "manhole " << g.manhole_diameter_m << " m, turn " << g.turn_deg << " deg, pipes "
            << g.from_diameter_m << " -> " << g.to_diameter_m << " m, step " << g.step_m << " m";
}

PassageGeometry passage_geometry(const SewerMap& map, ManholeId m, SlotIndex from, SlotIndex to,
                                 bool* mirrored) {
  const Slot& a = map.slot(m, from);
  const Slot& b = map.slot(m, to);
  // The to-pipe's azimuth with the from-pipe's at 180 degrees, in (-180, 180].
  const double relative = normalize_deg(b.azimuth_deg - a.azimuth_deg + 180.0);
  PassageGeometry g{.manhole_diameter_m = map.manhole(m).diameter_m,
                    .turn_deg = std::abs(relative),
                    .from_diameter_m = map.pipe(a.pipe).diameter_m,
                    .to_diameter_m = map.pipe(b.pipe).diameter_m,
                    .step_m = passage_step_m(map, m, from, to)};
  if (mirrored != nullptr) *mirrored = relative < 0;
  return quantised(g);
}

PassageGeometry quantised(const PassageGeometry& g) {
  auto mm = [](double v) { return std::round(v * 1000.0) / 1000.0; };
  return PassageGeometry{.manhole_diameter_m = mm(g.manhole_diameter_m),
                         .turn_deg = std::round(g.turn_deg * 10.0) / 10.0,
                         .from_diameter_m = mm(g.from_diameter_m),
                         .to_diameter_m = mm(g.to_diameter_m),
                         .step_m = mm(g.step_m)};
}

PassageKey passage_key(const PassageGeometry& g) {
  auto i = [](double v, double scale) {
    return static_cast<std::int64_t>(std::llround(v * scale));
  };
  return PassageKey{i(g.manhole_diameter_m, 1000), i(g.turn_deg, 10), i(g.from_diameter_m, 1000),
                    i(g.to_diameter_m, 1000), i(g.step_m, 1000)};
}

bool in_free_space(const PassageGeometry& g, double x_m, double y_m, double clearance_m) {
  return in_free_space(g, x_m, y_m, clearance_m, clearance_m);
}

bool in_free_space(const PassageGeometry& g, double x_m, double y_m, double clearance_m,
                   double pipe_clearance_m) {
  const double r = g.manhole_diameter_m / 2 - clearance_m;
  if (r >= 0 && x_m * x_m + y_m * y_m <= r * r) return true;
  if (in_strip(x_m, y_m, 180.0, g.from_diameter_m / 2 - pipe_clearance_m)) return true;
  return in_strip(x_m, y_m, g.turn_deg, g.to_diameter_m / 2 - pipe_clearance_m);
}

}  // namespace sewerplan::fusion
