// SPDX-License-Identifier: MIT
// generate_network: seeded synthetic sewer networks, from ten manholes to a million.
//
// Real sewer data is scarce and often not ours to publish, so tests and benchmarks also run on
// generated networks. A generated map is an ordinary SewerMap (sewer_map.h), built and validated
// through MapBuilder (map_builder.h) like every file format, with exactly `manholes` manholes named
// M1..Mn and pipes P1..Pm as in the MAKRO paper (Adria, Streich and Hertzberg 2004). It has no
// inspection points. It is meant to look like a town's sewer to the planner, not to a hydraulics
// engineer.
//
// How it is made:
//   1. Streets. A lattice of R x C street intersections, about 30% of the manholes (at least
//      2 x 2), with every row and column gap drawn from 40-160 m. All streets are axis-aligned, so
//      the turn between two streets at an intersection is exactly 0 or 90 degrees (MAKRO turns at
//      most 90). A quarter, as one might first pick, leaves the tree's three-way manholes at about
//      5%.
//   2. Topology. kTree: a random spanning tree of the lattice (randomised Kruskal: the edges in a
//      shuffled order, kept when they join two parts; Kruskal 1956). It has dead ends, as real
//      sewers do. kMeshed: the tree plus mesh_fraction of the lattice edges it left out (at least
//      one if mesh_fraction > 0), which close loops and keep the network planar.
//   3. Manholes along streets. The manholes that are not intersections go to the chosen streets at
//      random, each street drawing with a probability proportional to its length, and sit at
//      jittered, strictly increasing distances along it. Manholes not next to an intersection are
//      moved sideways by at most tan(2.5 deg) times the distance to their nearer neighbour, which
//      bends the street by at most 10 degrees per manhole and keeps every street inside a thin
//      rhombus between its two intersections, so that no two pipes cross. Pipes that enter an
//      intersection stay axis-aligned. Most manholes therefore have two pipes, intersections 1-4.
//   4. Heights. A smooth ground (a tilted plane plus a gentle wave) less a depth of 2-4 m gives
//      each manhole's floor. The outfall is the intersection with the lowest floor; flow runs along
//      breadth-first distance from it (ties: from the higher to the lower manhole number), so
//      Pipe::ends[0] is upstream. A pipe's outgoing (upstream) end lies at its manhole's floor; its
//      incoming end lies 0-0.20 m above the floor, or with probability high_step_fraction
//      0.35-0.80 m above it: a backdrop higher than the 0.30 m step MAKRO climbs.
//   5. Sizes. Pipes are 0.30-0.60 m, wider the more manholes drain through them; with probability
//      undrivable_pipe_fraction one of 0.20, 0.25, 0.80, 1.00 m, which MAKRO cannot drive.
//      Manholes are 1.0 m wide, 1.2 m with three or more pipes. Three-slot manholes are variant
//      'A' when two of their pipes are within 10 degrees of straight through, else 'B'.
//   6. Slots of a manhole are ordered by azimuth, counter-clockwise from east, in [0, 360).
//      exit_fraction of the manholes, at least one, are exits.
//
// Invariants that do *not* hold: pipes need not fall towards the outfall (the floors follow the
// ground, not a hydraulic gradient); a three-slot manhole is never variant 'B' in practice, since a
// lattice T-junction always has a straight pair.
//
// Determinism: one Rng (rng.h) seeded from `seed`, split into independent streams per stage, and
// only ordered containers. Angles come from an arithmetic arctangent and the ground from a
// polynomial wave instead of the C library's atan2 and sin, whose last bits differ between
// platforms; only IEEE-754 basic operations and sqrt remain, so the same options give the same map
// bit for bit wherever those are not contracted into fused multiply-adds (the build sets
// -ffp-contract=off for GCC and clang alike).
//
// Cost: O(n log n) time and O(n) memory; a million manholes take a few seconds, most of it in
// MapBuilder's validation (bench/core/generator_bench.cc).
//
//   GeneratorOptions options{.manholes = 5000, .seed = 7, .topology = Topology::kMeshed};
//   Result<SewerMap> map = generate_network(options);
//   if (!map.has_value()) return map.error();  // kInvalidArgument: an option out of range
//   ManholeId m = *map->find_manhole("M1");
//
// Thread safety: generate_network is a pure function of its options: call it from any number of
// threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

enum class Topology { kTree, kMeshed };

std::string_view to_string(Topology topology);
// "tree" or "meshed".
std::optional<Topology> topology_from_string(std::string_view name);
// The names topology_from_string reads, "tree, meshed", for messages.
std::string topology_names();

struct GeneratorOptions {
  static constexpr std::size_t kMinManholes = 10;
  static constexpr std::size_t kMaxManholes = 1'000'000;

  std::size_t manholes = 100;  // exactly this many manholes, kMinManholes .. kMaxManholes
  std::uint64_t seed = 1;
  Topology topology = Topology::kTree;
  double mesh_fraction = 0.3;   // kMeshed: share of the lattice edges left out by the tree, 0..1
  double exit_fraction = 0.05;  // share of manholes that are exits (at least one), 0..1
  double undrivable_pipe_fraction = 0.05;  // pipes narrower than 0.30 m or wider than 0.60 m, 0..1
  double high_step_fraction = 0.02;  // incoming pipe ends more than 0.30 m above the floor, 0..1
  // Inspection findings per km of pipe (0..1000), at random offsets: roots BBA 30 %, settled
  // deposits BBC 25 %, attached deposits BBB 15 %, displaced joints BAJ 15 %, obstacles BBE 10 %,
  // collapses BAC 5 %; the cross-section codes take 5 to 40 % of it. A stream of its own: the
  // network is the same as without findings.
  double findings_per_km = 0;
  std::string name;  // empty: "generated-<topology>-<manholes>-<seed>"
};

// A network as described above. Fails with kInvalidArgument, naming the option, if an option is out
// of range. Runtime: O(manholes log manholes).
Result<SewerMap> generate_network(const GeneratorOptions& options);

}  // namespace sewerplan
