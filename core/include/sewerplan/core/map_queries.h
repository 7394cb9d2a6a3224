// SPDX-License-Identifier: MIT
// Queries on a SewerMap: geometry of passages through manholes, connectivity, statistics.
//
// Free functions over the immutable map (map_builder.h builds it). A passage is the robot's way
// through a manhole from one slot's pipe into another's; its turn is the deviation from driving
// straight through (0 degrees when the two pipes are opposite, 90 for a right angle) and its step
// is the height it climbs (negative: descends) from one pipe end's invert to the other's.
//
//   double turn = passage_turn_deg(map, m, SlotIndex{2}, SlotIndex{3});
//   Components parts = connected_components(map);
//
// Thread safety: Pure functions of a const SewerMap: call them from any number of threads.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

// An angle folded into (-180, 180]. Runtime: O(1).
double normalize_deg(double angle_deg);

// The counter-clockwise angle from `from_deg` to `to_deg`, in [0, 360) (a map's slot directions
// may be in (-180, 180], as an import's atan2 gives them). Runtime: O(1).
double ccw_deg(double from_deg, double to_deg);

// The deviation from straight through when passing `m` from slot `from` into slot `to`, in
// [0, 180] degrees. Runtime: O(1).
double passage_turn_deg(const SewerMap& map, ManholeId m, SlotIndex from, SlotIndex to);

// The height climbed passing `m` from slot `from` into slot `to`: to's invert minus from's.
// Runtime: O(1).
double passage_step_m(const SewerMap& map, ManholeId m, SlotIndex from, SlotIndex to);

// The end of `pipe` that is not `end` (0 or 1). Runtime: O(1).
const PipeEnd& opposite_end(const SewerMap& map, PipeId pipe, std::size_t end);

// Which end of `pipe` lies in manhole `m`, if either. Runtime: O(1).
std::optional<std::size_t> end_in_manhole(const SewerMap& map, PipeId pipe, ManholeId m);

struct Components {
  std::uint32_t count = 0;
  std::vector<std::uint32_t> component_of;  // per manhole
  std::vector<std::uint32_t> sizes;         // manholes per component
};

// Connected parts of the network, ignoring robot limits, numbered in the order of their first
// manhole. Runtime: O(manholes + pipes) (a union-find, near linear).
Components connected_components(const SewerMap& map);

struct MapStatistics {
  std::size_t manholes = 0;
  std::size_t pipes = 0;
  std::size_t inspection_points = 0;
  std::size_t exits = 0;
  std::size_t blind_pipe_ends = 0;
  std::map<std::uint16_t, std::size_t> manholes_by_type;  // slot count -> manholes
  double total_length_m = 0;
  double min_pipe_diameter_m = 0;
  double max_pipe_diameter_m = 0;
  double min_manhole_diameter_m = 0;
  double max_manhole_diameter_m = 0;
  std::uint32_t components = 0;
  std::array<double, 2> min_xy_m{};  // bounding box of the manholes
  std::array<double, 2> max_xy_m{};
};

// Runtime: O(manholes + pipes).
MapStatistics map_statistics(const SewerMap& map);

}  // namespace sewerplan
