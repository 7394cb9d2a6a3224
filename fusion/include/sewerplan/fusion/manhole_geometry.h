// SPDX-License-Identifier: MIT
// Geometric models of the robot and of a manhole passage, for planning turns (docs/motion.md).
//
// RobotBody is MAKRO as a chain: segment_count rigid segments of length_m / segment_count, each
// body_width_m wide, joined by joints that bend at most joint_yaw_max_deg sideways and
// joint_pitch_max_deg up or down (robot_profile.h). PassageGeometry is one passage in a canonical
// frame: the manhole's axis at the origin, the robot arriving from the pipe that leaves at azimuth
// 180 degrees (so it heads east, +x) and leaving into the pipe at azimuth turn_deg (mirrored so
// that the turn is to the left, 0..180 degrees; 0 is straight through). The floor is the lower of
// the two pipes' inverts (the bench the robot drives on); step_m is the climb from the from-pipe's
// invert to the to-pipe's. Passage geometries are quantised (0.1 degree, 1 mm), so that equal
// passages of a map share one plan (the cache of passage_precompute.h).
//
// Free space, seen from above: the manhole's disk, and each of the two pipes as a strip of its
// diameter along its azimuth from the axis outwards. in_free_space() asks whether a disk of a given
// clearance around a point fits; it is conservative where disk and strip meet.
//
//   RobotBody body = robot_body(*builtin_profile("makro-1.1"));
//   PassageGeometry g = passage_geometry(map, m, SlotIndex{0}, SlotIndex{2});
//   bool ok = in_free_space(g, 0.1, -0.2, body.width_m / 2);
//
// Thread safety: Plain values and pure functions: const access from several threads is safe.
#pragma once

#include <cstdint>
#include <ostream>
#include <tuple>

#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::fusion {

struct RobotBody {
  int segment_count = 6;
  double segment_length_m = 2.0 / 6;
  double width_m = 0.22;
  double yaw_max_deg = 45;
  double pitch_max_deg = 70;
  double length_m() const { return segment_length_m * segment_count; }
  // The smallest radius of a path whose chords of one segment length bend each joint at most
  // yaw_max_deg: L / (2 sin(yaw / 2)).
  double min_turn_radius_m() const;
  // How far such a chord lies inside its arc (the sagitta): the body's extra clearance on bends.
  double bend_margin_m() const;
  // The highest step two lifted segments reach: L x sin(pitch) (docs/motion.md).
  double max_climb_m() const;
  friend bool operator==(const RobotBody&, const RobotBody&) = default;
};

RobotBody robot_body(const RobotProfile& profile);

struct PassageGeometry {
  double manhole_diameter_m = 1.0;
  double turn_deg = 0;  // 0..180, to the left
  double from_diameter_m = 0.6;
  double to_diameter_m = 0.6;
  double step_m = 0;  // to-pipe invert minus from-pipe invert
  friend bool operator==(const PassageGeometry&, const PassageGeometry&) = default;
};

std::ostream& operator<<(std::ostream& os, const PassageGeometry& g);

// A passage of the map in the canonical frame, quantised; `mirrored` (optional) tells whether the
// real turn is to the right. The manhole frame is the canonical one rotated by
// `from azimuth - 180` degrees (after mirroring y when mirrored).
PassageGeometry passage_geometry(const SewerMap& map, ManholeId m, SlotIndex from, SlotIndex to,
                                 bool* mirrored = nullptr);

// Rounds to the cache's resolution: 0.1 degree and 1 mm.
PassageGeometry quantised(const PassageGeometry& g);

// A cache key: the quantised geometry as integers (mm, 0.1 degree).
struct PassageKey {
  std::int64_t manhole_mm, turn_decideg, from_mm, to_mm, step_mm;
  friend auto operator<=>(const PassageKey&, const PassageKey&) = default;
};
PassageKey passage_key(const PassageGeometry& g);

// Whether a disk of radius clearance_m around (x, y) lies in the passage's free space.
bool in_free_space(const PassageGeometry& g, double x_m, double y_m, double clearance_m);
// The same with another clearance in the pipes (the planner's head needs room to bend only in the
// manhole; the chain check then verifies the body everywhere).
bool in_free_space(const PassageGeometry& g, double x_m, double y_m, double clearance_m,
                   double pipe_clearance_m);

}  // namespace sewerplan::fusion
