// SPDX-License-Identifier: MIT
#include "sewerplan/core/map_queries.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sewerplan {

double ccw_deg(double from_deg, double to_deg) {
  double a = std::fmod(to_deg - from_deg, 360.0);
  if (a < 0) a += 360.0;
  if (a >= 360.0) a -= 360.0;
  return a;
}

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

namespace {

// The root of `m`'s set: the smallest manhole of it, as union() links the larger root under the
// smaller. Halves the path on the way.
std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t m) {
  while (parent[m] != m) {
    parent[m] = parent[parent[m]];
    m = parent[m];
  }
  return m;
}

}  // namespace

// Union-find over the pipes, read in order, then the parts numbered by their smallest manhole:
// the numbering of a walk from each unseen manhole in index order, at a fraction of its cost. The
// walk read a pipe far away for every slot and each manhole's slots in turn; on a
// 1,000,000-manhole map it was a twelfth of reading it (issue 16). A pipe joins its two ends'
// parts; a valid map's slots are the pipes' ends, so the parts are the same.
Components connected_components(const SewerMap& map) {
  const auto n = static_cast<std::uint32_t>(map.manhole_count());
  std::vector<std::uint32_t> parent(n);
  for (std::uint32_t m = 0; m < n; ++m) parent[m] = m;
  for (const Pipe& pipe : map.pipes()) {
    if (!pipe.ends[0].manhole || !pipe.ends[1].manhole) continue;
    const std::uint32_t a = find_root(parent, pipe.ends[0].manhole->value());
    const std::uint32_t b = find_root(parent, pipe.ends[1].manhole->value());
    if (a < b) {
      parent[b] = a;
    } else if (b < a) {
      parent[a] = b;
    }
  }
  Components result;
  result.component_of.resize(n);
  for (std::uint32_t m = 0; m < n; ++m) {
    const std::uint32_t root = find_root(parent, m);
    if (root == m) {
      result.component_of[m] = result.count++;
      result.sizes.push_back(0);
    } else {
      result.component_of[m] = result.component_of[root];  // root < m: numbered already
    }
    ++result.sizes[result.component_of[m]];
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
