// SPDX-License-Identifier: MIT
#include "sewerplan/core/map_queries.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sewerplan {

double normalize_deg(double angle_deg) {
  double a = std::fmod(angle_deg, 360.0);
  if (a <= -180.0) a += 360.0;
  if (a > 180.0) a -= 360.0;
  return a;
}

double passage_turn_deg(const SewerMap& map, ManholeId m, SlotIndex from, SlotIndex to) {
  // Entering through `from`, the robot heads opposite to the direction in which that pipe leaves
  // the manhole; it leaves heading along `to`'s azimuth.
  const double heading_in = map.slot(m, from).azimuth_deg + 180.0;
  const double heading_out = map.slot(m, to).azimuth_deg;
  return std::abs(normalize_deg(heading_out - heading_in));
}

double passage_step_m(const SewerMap& map, ManholeId m, SlotIndex from, SlotIndex to) {
  return map.slot(m, to).invert_z_m - map.slot(m, from).invert_z_m;
}

const PipeEnd& opposite_end(const SewerMap& map, PipeId pipe, std::size_t end) {
  return map.pipe(pipe).ends[1 - end];
}

std::optional<std::size_t> end_in_manhole(const SewerMap& map, PipeId pipe, ManholeId m) {
  const Pipe& p = map.pipe(pipe);
  if (p.ends[0].manhole == m) return 0;
  if (p.ends[1].manhole == m) return 1;
  return std::nullopt;
}

Components connected_components(const SewerMap& map) {
  constexpr std::uint32_t kUnseen = std::numeric_limits<std::uint32_t>::max();
  Components result;
  result.component_of.assign(map.manhole_count(), kUnseen);
  std::vector<ManholeId> stack;
  for (ManholeId root : map.manhole_ids()) {
    if (result.component_of[root.index()] != kUnseen) continue;
    const std::uint32_t c = result.count++;
    std::uint32_t size = 0;
    result.component_of[root.index()] = c;
    stack.push_back(root);
    while (!stack.empty()) {
      const ManholeId m = stack.back();
      stack.pop_back();
      ++size;
      for (const Slot& slot : map.slots(m)) {
        const PipeEnd& far = opposite_end(map, slot.pipe, slot.pipe_end);
        if (far.manhole && result.component_of[far.manhole->index()] == kUnseen) {
          result.component_of[far.manhole->index()] = c;
          stack.push_back(*far.manhole);
        }
      }
    }
    result.sizes.push_back(size);
  }
  return result;
}

MapStatistics map_statistics(const SewerMap& map) {
  MapStatistics s;
  s.manholes = map.manhole_count();
  s.pipes = map.pipe_count();
  s.inspection_points = map.point_count();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  s.min_pipe_diameter_m = s.min_manhole_diameter_m = kInf;
  s.max_pipe_diameter_m = s.max_manhole_diameter_m = -kInf;
  s.min_xy_m = {kInf, kInf};
  s.max_xy_m = {-kInf, -kInf};
  for (const Manhole& m : map.manholes()) {
    s.exits += m.exit ? 1 : 0;
    ++s.manholes_by_type[m.slot_count];
    s.min_manhole_diameter_m = std::min(s.min_manhole_diameter_m, m.diameter_m);
    s.max_manhole_diameter_m = std::max(s.max_manhole_diameter_m, m.diameter_m);
    s.min_xy_m = {std::min(s.min_xy_m[0], m.position.x_m), std::min(s.min_xy_m[1], m.position.y_m)};
    s.max_xy_m = {std::max(s.max_xy_m[0], m.position.x_m), std::max(s.max_xy_m[1], m.position.y_m)};
  }
  for (const Pipe& p : map.pipes()) {
    s.total_length_m += p.length_m;
    s.min_pipe_diameter_m = std::min(s.min_pipe_diameter_m, p.diameter_m);
    s.max_pipe_diameter_m = std::max(s.max_pipe_diameter_m, p.diameter_m);
    s.blind_pipe_ends += (p.ends[0].manhole ? 0U : 1U) + (p.ends[1].manhole ? 0U : 1U);
  }
  if (map.pipe_count() == 0) s.min_pipe_diameter_m = s.max_pipe_diameter_m = 0;
  if (map.manhole_count() == 0) {
    s.min_manhole_diameter_m = s.max_manhole_diameter_m = 0;
    s.min_xy_m = s.max_xy_m = {0, 0};
  }
  s.components = connected_components(map).count;
  return s;
}

}  // namespace sewerplan
