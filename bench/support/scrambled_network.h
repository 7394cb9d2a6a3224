// SPDX-License-Identifier: MIT
// A second network generator, of another structure than generate_network (core/generator.h), and
// a copy of any map with its manholes and pipes renumbered and renamed: the benchmarks and
// tests that must not rely on what our own generator happens to give (issue 35).
//
// generate_network numbers its manholes and pipes street by street, so nodes near in the network
// are near in memory, names follow the numbers (M1..Mn), streets are axis-aligned and every
// manhole has two pipes or meets a lattice at right angles. Real networks (a town's ISYBAU or
// SWMM export, QGEP) are numbered by whatever the database did, and named by it. A planner tuned
// on the first may be slow, or wrong, on the second. This one:
//   - places the manholes on a jittered square lattice of spacing 40-80 m (each moved up to a
//     fifth of that), joins them by a random spanning tree of the lattice's edges (randomised
//     Kruskal), then joins each dead end, and a share of the others, to one more neighbour along
//     a lattice edge or a diagonal, never crossing another diagonal of the same cell and never
//     closer than 90 degrees to another pipe of the manhole: degree 1-4 (mostly 2-4), streets at
//     any of eight headings (a pipe leaves a manhole at its lattice heading; the jitter changes
//     lengths), and every passage within MAKRO's 90-degree turn; 1 % of the pipes are 0.20 m,
//     too narrow for MAKRO, the others 0.30-0.60 m;
//   - adds the manholes, the pipes and each manhole's slots in a random order, each pipe's ends
//     in a random direction, and names them by random unique strings ("S-3f9a02c1", "K-...");
//   - makes `exit_fraction` of the manholes exits, at random.
// A mission on it is generate_mission's uniform spread with a battery that does not bound the
// search (scrambled_mission): the tasks lie over the whole network.
//
// shuffle_ids(map, seed) gives the same network with every ID and name permuted: a test that the
// planner's answer does not depend on the numbering, and a benchmark of what the numbering costs.
//
//   SewerMap map = *generate_scrambled_network({.manholes = 10000, .seed = 1});
//   Mission mission = *scrambled_mission(map, 20, 1);
//   ShuffledMap copy = shuffle_ids(map, 7);   // copy.map, copy.manhole_to[old index] = new id
//
// Determinism: one Rng (core/rng.h) from the seed, and only ordered containers: the same options
// give the same map. Runtime: O(n log n).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "sewerplan/core/map_builder.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/rng.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/mission_generator.h"

namespace sewerplan::bench {

struct ScrambledOptions {
  std::size_t manholes = 1000;  // at least 4
  std::uint64_t seed = 1;
  double exit_fraction = 0.02;    // at least one exit
  double extra_edge_share = 0.3;  // of the manholes with 2-3 pipes, the share offered one more
};

namespace detail {

// A random permutation of 0..n-1 (Fisher-Yates).
inline std::vector<std::uint32_t> permutation(std::size_t n, Rng& rng) {
  std::vector<std::uint32_t> p(n);
  std::iota(p.begin(), p.end(), 0U);
  for (std::size_t i = n; i > 1; --i) std::swap(p[i - 1], p[rng.below(i)]);
  return p;
}

// `count` distinct random names "<head>-xxxxxxxx".
inline std::vector<std::string> random_names(std::size_t count, const char* head, Rng& rng) {
  std::set<std::string> used;
  std::vector<std::string> names;
  names.reserve(count);
  while (names.size() < count) {
    std::string name = std::string(head) + "-";
    std::uint64_t bits = rng.next();
    for (int i = 0; i < 8; ++i, bits >>= 4) name += "0123456789abcdef"[bits & 15U];
    if (used.insert(name).second) names.push_back(std::move(name));
  }
  return names;
}

// Azimuth of b seen from a, degrees counter-clockwise from east in [0, 360).
inline double azimuth_deg(const Position& a, const Position& b) {
  const double deg = std::atan2(b.y_m - a.y_m, b.x_m - a.x_m) * 180.0 / 3.14159265358979323846;
  return deg < 0 ? deg + 360.0 : deg;
}

struct Edge {
  std::uint32_t a;
  std::uint32_t b;
  std::uint32_t cell;  // diagonals: the lattice cell they cross; else kNoCell
};
constexpr std::uint32_t kNoCell = 0xffffffffU;

}  // namespace detail

inline Result<SewerMap> generate_scrambled_network(const ScrambledOptions& options) {
  using detail::Edge;
  const std::size_t n = options.manholes;
  if (n < 4) return Error{ErrorCode::kInvalidArgument, "a scrambled network needs 4 manholes"};
  Rng rng(options.seed);
  const auto side = static_cast<std::uint32_t>(std::ceil(std::sqrt(static_cast<double>(n))));
  const double spacing = rng.uniform(40.0, 80.0);
  std::vector<Position> at(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double jitter = spacing / 5;
    at[i] = {.x_m = static_cast<double>(i % side) * spacing + rng.uniform(-jitter, jitter),
             .y_m = static_cast<double>(i / side) * spacing + rng.uniform(-jitter, jitter)};
  }
  // The lattice's edges and both diagonals of each cell, in a random order.
  std::vector<Edge> candidates;
  auto index = [&](std::uint32_t x, std::uint32_t y) { return y * side + x; };
  for (std::uint32_t y = 0; y < side; ++y) {
    for (std::uint32_t x = 0; x < side; ++x) {
      const std::uint32_t i = index(x, y);
      if (i >= n) continue;
      if (x + 1 < side && index(x + 1, y) < n)
        candidates.push_back({i, index(x + 1, y), detail::kNoCell});
      if (index(x, y + 1) < n) candidates.push_back({i, index(x, y + 1), detail::kNoCell});
      if (x + 1 < side && index(x + 1, y + 1) < n) {
        candidates.push_back({i, index(x + 1, y + 1), i});
        candidates.push_back({index(x + 1, y), index(x, y + 1), i});
      }
    }
  }
  for (std::size_t i = candidates.size(); i > 1; --i) {
    std::swap(candidates[i - 1], candidates[rng.below(i)]);
  }
  std::vector<std::uint32_t> part(n);
  std::iota(part.begin(), part.end(), 0U);
  auto find = [&](std::uint32_t v) {
    while (part[v] != v) v = part[v] = part[part[v]];
    return v;
  };
  std::vector<std::uint8_t> degree(n, 0);
  std::vector<bool> cell_used(n, false), taken(candidates.size(), false);
  std::vector<Edge> edges;
  // A manhole's place on the lattice before the jitter: its pipes leave it at the lattice's
  // headings (the jitter changes lengths only), so that right angles stay right.
  auto grid = [&](std::uint32_t m) {
    return Position{.x_m = static_cast<double>(m % side), .y_m = static_cast<double>(m / side)};
  };
  // Each manhole's pipes' azimuths so far: a pipe closer than 90 degrees to another at either
  // end is not taken, so every passage turns at most 90 degrees (MAKRO's limit), and no manhole
  // has more than 4 pipes.
  std::vector<std::vector<double>> azimuths(n);
  auto clear_of = [&](std::uint32_t m, double azimuth) {
    return std::all_of(azimuths[m].begin(), azimuths[m].end(), [&](double other) {
      const double apart = std::abs(other - azimuth);
      return std::min(apart, 360.0 - apart) >= 90.0;
    });
  };
  auto take = [&](std::size_t c) {
    const Edge& e = candidates[c];
    if (taken[c] || degree[e.a] >= 4 || degree[e.b] >= 4) return false;
    if (e.cell != detail::kNoCell && cell_used[e.cell]) return false;
    const double out_a = detail::azimuth_deg(grid(e.a), grid(e.b));
    const double out_b = detail::azimuth_deg(grid(e.b), grid(e.a));
    if (!clear_of(e.a, out_a) || !clear_of(e.b, out_b)) return false;
    azimuths[e.a].push_back(out_a);
    azimuths[e.b].push_back(out_b);
    if (e.cell != detail::kNoCell) cell_used[e.cell] = true;
    ++degree[e.a];
    ++degree[e.b];
    taken[c] = true;
    edges.push_back(e);
    return true;
  };
  // The spanning tree, of the lattice's own edges (any two of them at a manhole are at least 90
  // degrees apart, so it spans); diagonals join in below, where the angles let them.
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (candidates[c].cell != detail::kNoCell) continue;
    const std::uint32_t ra = find(candidates[c].a), rb = find(candidates[c].b);
    if (ra != rb && take(c)) part[ra] = rb;
  }
  for (std::size_t c = 0; c < candidates.size(); ++c) {  // dead ends, and a share of the rest
    const Edge& e = candidates[c];
    const bool dead_end = degree[e.a] == 1 || degree[e.b] == 1;
    if (dead_end || rng.bernoulli(options.extra_edge_share / 4)) take(c);
  }
  // Records in a random order under random names.
  const std::vector<std::uint32_t> manhole_order = detail::permutation(n, rng);
  const std::vector<std::uint32_t> pipe_order = detail::permutation(edges.size(), rng);
  const std::vector<std::string> manhole_names = detail::random_names(n, "S", rng);
  const std::vector<std::string> pipe_names = detail::random_names(edges.size(), "K", rng);
  std::vector<std::vector<std::uint32_t>> pipes_at(n);
  std::vector<bool> flipped(edges.size());
  std::vector<double> diameter(edges.size());
  for (std::size_t p = 0; p < edges.size(); ++p) {
    flipped[p] = rng.bernoulli(0.5);
    diameter[p] = rng.bernoulli(0.01) ? 0.2 : 0.3 + 0.05 * static_cast<double>(rng.below(7));
    pipes_at[edges[p].a].push_back(static_cast<std::uint32_t>(p));
    pipes_at[edges[p].b].push_back(static_cast<std::uint32_t>(p));
  }
  MapBuilder builder("scrambled-" + std::to_string(n) + "-" + std::to_string(options.seed));
  builder.reserve(n, edges.size(), 2 * edges.size());
  for (std::uint32_t m : manhole_order) {
    std::vector<std::uint32_t> mine = pipes_at[m];
    for (std::size_t i = mine.size(); i > 1; --i) std::swap(mine[i - 1], mine[rng.below(i)]);
    ManholeRecord record{.name = manhole_names[m],
                         .position = at[m],
                         .diameter_m = mine.size() >= 3 ? 1.2 : 1.0,
                         .exit = rng.bernoulli(options.exit_fraction) || m == manhole_order[0]};
    for (std::uint32_t p : mine) {
      const std::uint32_t other = edges[p].a == m ? edges[p].b : edges[p].a;
      record.slots.push_back(
          {.pipe = pipe_names[p], .azimuth_deg = detail::azimuth_deg(grid(m), grid(other))});
    }
    builder.add_manhole(std::move(record));
  }
  for (std::uint32_t p : pipe_order) {
    const Edge& e = edges[p];
    const std::uint32_t from = flipped[p] ? e.b : e.a, to = flipped[p] ? e.a : e.b;
    const double length = std::hypot(at[from].x_m - at[to].x_m, at[from].y_m - at[to].y_m);
    builder.add_pipe({.name = pipe_names[p],
                      .from = manhole_names[from],
                      .to = manhole_names[to],
                      .length_m = std::max(length, 1.0),
                      .diameter_m = diameter[p]});
  }
  Diagnostics diagnostics;
  return std::move(builder).build(diagnostics);
}

// A mission of `tasks` tasks spread uniformly over the whole network (generate_mission's uniform
// spread with a battery of 1,000,000 Wh, which bounds no search: a tethered robot).
inline Result<Mission> scrambled_mission(const SewerMap& map, std::size_t tasks,
                                         std::uint64_t seed) {
  return domain::generate_mission(
      map,
      {.tasks = tasks, .seed = seed, .spread = domain::MissionSpread::kUniform, .battery_wh = 1e6});
}

// The same network with its manholes and pipes added in a random order under new names (each
// manhole's slots keep their order; inspection points keep their names; findings are left out).
struct ShuffledMap {
  SewerMap map;
  std::vector<ManholeId> manhole_to;  // by the original's manhole index
  std::vector<PipeId> pipe_to;        // by the original's pipe index
};

inline ShuffledMap shuffle_ids(const SewerMap& map, std::uint64_t seed) {
  Rng rng(seed);
  const std::vector<std::uint32_t> manhole_order = detail::permutation(map.manhole_count(), rng);
  const std::vector<std::uint32_t> pipe_order = detail::permutation(map.pipe_count(), rng);
  const std::vector<std::string> manhole_names =
      detail::random_names(map.manhole_count(), "S", rng);
  const std::vector<std::string> pipe_names = detail::random_names(map.pipe_count(), "K", rng);
  MapBuilder builder(map.name());
  for (std::uint32_t i : manhole_order) {
    const ManholeId m{i};
    const Manhole& manhole = map.manhole(m);
    ManholeRecord record{.name = manhole_names[i],
                         .position = manhole.position,
                         .diameter_m = manhole.diameter_m,
                         .exit = manhole.exit,
                         .variant = manhole.variant,
                         .shaft_length_m = manhole.shaft_length_m,
                         .shaft_width_m = manhole.shaft_width_m,
                         .depth_m = manhole.depth_m};
    for (const Slot& s : map.slots(m)) {
      record.slots.push_back({.pipe = pipe_names[s.pipe.index()],
                              .azimuth_deg = s.azimuth_deg,
                              .invert_z_m = s.invert_z_m});
    }
    builder.add_manhole(std::move(record));
  }
  for (std::uint32_t i : pipe_order) {
    const Pipe& pipe = map.pipe(PipeId{i});
    PipeRecord record{.name = pipe_names[i],
                      .length_m = pipe.length_m,
                      .diameter_m = pipe.diameter_m,
                      .shape = pipe.shape,
                      .height_m = pipe.height_m,
                      .blockage_risk = pipe.blockage_risk};
    if (pipe.ends[0].manhole) record.from = manhole_names[pipe.ends[0].manhole->index()];
    if (pipe.ends[1].manhole) record.to = manhole_names[pipe.ends[1].manhole->index()];
    builder.add_pipe(std::move(record));
  }
  for (const InspectionPoint& point : map.points()) {
    builder.add_point(
        {.name = point.name, .pipe = pipe_names[point.pipe.index()], .offset_m = point.offset_m});
  }
  Diagnostics diagnostics;
  ShuffledMap out{*std::move(builder).build(diagnostics), {}, {}};
  out.manhole_to.resize(map.manhole_count(), ManholeId{0});
  out.pipe_to.resize(map.pipe_count(), PipeId{0});
  for (std::size_t k = 0; k < manhole_order.size(); ++k) {
    out.manhole_to[manhole_order[k]] = ManholeId{static_cast<std::uint32_t>(k)};
  }
  for (std::size_t k = 0; k < pipe_order.size(); ++k) {
    out.pipe_to[pipe_order[k]] = PipeId{static_cast<std::uint32_t>(k)};
  }
  return out;
}

}  // namespace sewerplan::bench
