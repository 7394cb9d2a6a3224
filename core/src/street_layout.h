// SPDX-License-Identifier: MIT
// StreetLayout: the plan view of a generated network, private to core (see generator.h, steps 1-3).
//
// make_street_layout places the manholes on a street lattice and joins them by pipes; the
// generator then adds heights, flow, sizes and slots. Manholes 0 .. intersections-1 are the
// lattice's intersections in row-major order (row 0 south, column 0 west); the others follow
// street by street, in order along each street. Pipes are not yet oriented.
//
//   Rng rng(1);
//   StreetLayout layout = make_street_layout(1000, Topology::kTree, 0.3, rng);
//   double azimuth = direction_deg(layout.positions[0], layout.positions[1]);
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/rng.h"

namespace sewerplan::detail {

struct StreetLayout {
  std::uint32_t intersections = 0;
  std::vector<Eigen::Vector2d> positions;           // per manhole, metres
  std::vector<std::array<std::uint32_t, 2>> pipes;  // per pipe, the manholes it joins
};

// Exactly `manholes` manholes (>= 10), connected and planar. Runtime: O(manholes log manholes).
StreetLayout make_street_layout(std::size_t manholes, Topology topology, double mesh_fraction,
                                Rng& rng);

// The direction from `from` to `to` in degrees, counter-clockwise from +x, in [0, 360); exactly
// 0, 90, 180 or 270 along an axis. Uses IEEE basic operations only, so it is the same on every
// platform; accurate to a few 1e-14 degrees. Precondition: from != to. Runtime: O(1).
double direction_deg(const Eigen::Vector2d& from, const Eigen::Vector2d& to);

}  // namespace sewerplan::detail
