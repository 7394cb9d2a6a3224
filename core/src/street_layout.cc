// SPDX-License-Identifier: MIT
#include "street_layout.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "sewerplan/core/check.h"

namespace sewerplan::detail {
namespace {

constexpr double kMinGapM = 40;
constexpr double kMaxGapM = 160;
// Street positions of the manholes along a street are cumulative gaps drawn from [0.6, 1.4) times
// the mean gap, so no pipe is shorter than 0.6 / 1.4 of the street's mean spacing.
constexpr double kMinWeight = 0.6;
constexpr double kMaxWeight = 1.4;
// tan(2.5 deg): sideways offsets up to this times the nearer gap keep each pipe within 5 degrees
// of its street's axis, hence a bend of at most 10 degrees at a manhole.
constexpr double kTanHalfBend = 0.04366094290851206;

// R x C intersections at columns x_m and rows y_m. Node (r, c) is r * cols + c. Edges: first the
// horizontal ones, (r, c)-(r, c+1) at r * (cols-1) + c, then the vertical ones, (r, c)-(r+1, c).
struct Lattice {
  std::uint32_t rows = 0;
  std::uint32_t cols = 0;
  std::vector<double> x_m;
  std::vector<double> y_m;

  std::uint32_t nodes() const { return rows * cols; }
  std::uint32_t horizontal_edges() const { return rows * (cols - 1); }
  std::uint32_t edges() const { return horizontal_edges() + (rows - 1) * cols; }
  bool is_horizontal(std::uint32_t e) const { return e < horizontal_edges(); }
  // The edge's west or south end first.
  std::array<std::uint32_t, 2> ends(std::uint32_t e) const {
    if (is_horizontal(e)) {
      const std::uint32_t node = e / (cols - 1) * cols + e % (cols - 1);
      return {node, node + 1};
    }
    const std::uint32_t node = e - horizontal_edges();
    return {node, node + cols};
  }
  Eigen::Vector2d position(std::uint32_t node) const {
    return {x_m[node % cols], y_m[node / cols]};
  }
  double length_m(std::uint32_t e) const {
    const auto [a, b] = ends(e);
    return is_horizontal(e) ? x_m[b % cols] - x_m[a % cols] : y_m[b / cols] - y_m[a / cols];
  }
};

std::vector<double> cumulative_gaps(std::uint32_t count, Rng& rng) {
  std::vector<double> at;
  at.reserve(count);
  double sum_m = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    at.push_back(sum_m);
    if (i + 1 < count) sum_m += rng.uniform(kMinGapM, kMaxGapM);
  }
  return at;
}

Lattice make_lattice(std::size_t manholes, Rng& rng) {
  // About 30% of the manholes are intersections; rows * cols <= that, and at least 2 x 2.
  const std::size_t target = std::max<std::size_t>(4, (manholes * 3 + 5) / 10);
  Lattice lattice;
  lattice.rows = std::max<std::uint32_t>(
      2, static_cast<std::uint32_t>(std::lround(std::sqrt(static_cast<double>(target)))));
  lattice.cols = std::max<std::uint32_t>(2, static_cast<std::uint32_t>(target / lattice.rows));
  lattice.x_m = cumulative_gaps(lattice.cols, rng);
  lattice.y_m = cumulative_gaps(lattice.rows, rng);
  return lattice;
}

class DisjointSets {
 public:
  explicit DisjointSets(std::uint32_t n) : parent_(n), size_(n, 1) {
    std::iota(parent_.begin(), parent_.end(), 0U);
  }
  // Joins the sets of a and b; false if they were one set already.
  bool unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
    return true;
  }

 private:
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];  // path halving
    return x;
  }
  std::vector<std::uint32_t> parent_;
  std::vector<std::uint32_t> size_;
};

// The lattice edges that become streets, in ascending order.
std::vector<std::uint32_t> choose_streets(const Lattice& lattice, Topology topology,
                                          double mesh_fraction, Rng& rng) {
  std::vector<std::uint32_t> order(lattice.edges());
  std::iota(order.begin(), order.end(), 0U);
  for (std::size_t i = order.size() - 1; i > 0; --i) std::swap(order[i], order[rng.below(i + 1)]);
  DisjointSets parts(lattice.nodes());
  std::vector<std::uint32_t> streets;
  std::vector<std::uint32_t> left_out;
  streets.reserve(order.size());
  for (std::uint32_t e : order) {
    const auto [a, b] = lattice.ends(e);
    (parts.unite(a, b) ? streets : left_out).push_back(e);
  }
  if (topology == Topology::kMeshed && mesh_fraction > 0 && !left_out.empty()) {
    // left_out is in shuffled order, so its prefix is a random subset.
    const auto wanted = static_cast<std::size_t>(
        std::llround(mesh_fraction * static_cast<double>(left_out.size())));
    const std::size_t loops = std::clamp<std::size_t>(wanted, 1, left_out.size());
    streets.insert(streets.end(), left_out.begin(),
                   left_out.begin() + static_cast<std::ptrdiff_t>(loops));
  }
  std::sort(streets.begin(), streets.end());
  return streets;
}

// How many non-intersection manholes each street gets: each picks a street with probability
// proportional to its length.
std::vector<std::uint32_t> manholes_per_street(const Lattice& lattice,
                                               const std::vector<std::uint32_t>& streets,
                                               std::size_t manholes, Rng& rng) {
  std::vector<double> cumulative_m(streets.size());
  double total_m = 0;
  for (std::size_t k = 0; k < streets.size(); ++k) {
    total_m += lattice.length_m(streets[k]);
    cumulative_m[k] = total_m;
  }
  std::vector<std::uint32_t> count(streets.size(), 0);
  for (std::size_t i = 0; i < manholes; ++i) {
    const double at_m = rng.uniform(0, total_m);
    const auto k = static_cast<std::size_t>(
        std::upper_bound(cumulative_m.begin(), cumulative_m.end(), at_m) - cumulative_m.begin());
    ++count[std::min(k, streets.size() - 1)];
  }
  return count;
}

// Adds `count` manholes between intersections a and b (a west or south of b) and the count + 1
// pipes joining a, them and b in order. `along_m` is scratch space.
void lay_street(std::uint32_t a, std::uint32_t b, bool horizontal, std::uint32_t count,
                StreetLayout& layout, std::vector<double>& along_m, Rng& rng) {
  const Eigen::Vector2d from = layout.positions[a];
  const Eigen::Vector2d to = layout.positions[b];
  const Eigen::Vector2d axis = horizontal ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1);
  const Eigen::Vector2d side(-axis.y(), axis.x());
  const double length_m = horizontal ? to.x() - from.x() : to.y() - from.y();
  along_m.resize(count + 2);
  along_m[0] = 0;
  for (std::uint32_t i = 1; i <= count + 1; ++i) {
    along_m[i] = along_m[i - 1] + rng.uniform(kMinWeight, kMaxWeight);
  }
  const double scale = length_m / along_m[count + 1];
  for (double& s : along_m) s *= scale;
  std::uint32_t previous = a;
  for (std::uint32_t i = 1; i <= count; ++i) {
    double offset_m = 0;
    if (i > 1 && i < count) {
      const double gap_m = std::min(along_m[i] - along_m[i - 1], along_m[i + 1] - along_m[i]);
      offset_m = rng.uniform(-1, 1) * kTanHalfBend * gap_m;
    }
    const auto id = static_cast<std::uint32_t>(layout.positions.size());
    layout.positions.emplace_back(from + along_m[i] * axis + offset_m * side);
    layout.pipes.push_back({previous, id});
    previous = id;
  }
  layout.pipes.push_back({previous, b});
}

// atan(t) in radians for |t| <= 1. Above tan(15 deg) the argument is reduced by 30 degrees,
// atan(t) = pi/6 + atan((sqrt(3) t - 1) / (sqrt(3) + t)), leaving |u| <= tan(15 deg) = 0.268, where
// the Taylor series to u^33 is exact to below 1e-20.
double small_atan(double t) {
  constexpr double kTan15 = 0.2679491924311228;
  constexpr double kSqrt3 = 1.7320508075688772;
  constexpr double kPiOver6 = 0.5235987755982988;
  double base = 0;
  if (t > kTan15) {
    t = (kSqrt3 * t - 1) / (kSqrt3 + t);
    base = kPiOver6;
  }
  const double t2 = t * t;
  double series = 0;
  for (int k = 33; k >= 1; k -= 2) series = 1.0 / static_cast<double>(k) - t2 * series;
  return base + t * series;
}

}  // namespace

StreetLayout make_street_layout(std::size_t manholes, Topology topology, double mesh_fraction,
                                Rng& rng) {
  Rng lattice_rng = rng.split();
  Rng street_rng = rng.split();
  const Lattice lattice = make_lattice(manholes, lattice_rng);
  const std::vector<std::uint32_t> streets =
      choose_streets(lattice, topology, mesh_fraction, lattice_rng);
  const std::size_t along_streets = manholes - lattice.nodes();
  const std::vector<std::uint32_t> count =
      manholes_per_street(lattice, streets, along_streets, street_rng);

  StreetLayout layout;
  layout.intersections = lattice.nodes();
  layout.positions.reserve(manholes);
  layout.pipes.reserve(along_streets + streets.size());
  for (std::uint32_t node = 0; node < lattice.nodes(); ++node) {
    layout.positions.push_back(lattice.position(node));
  }
  std::vector<double> along_m;
  for (std::size_t k = 0; k < streets.size(); ++k) {
    const auto [a, b] = lattice.ends(streets[k]);
    lay_street(a, b, lattice.is_horizontal(streets[k]), count[k], layout, along_m, street_rng);
  }
  SEWER_CHECK(layout.positions.size() == manholes, "street layout lost manholes");
  return layout;
}

double direction_deg(const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
  constexpr double kDegPerRad = 57.29577951308232;
  const double dx = to.x() - from.x();
  const double dy = to.y() - from.y();
  if (dy == 0) return dx > 0 ? 0.0 : 180.0;
  if (dx == 0) return dy > 0 ? 90.0 : 270.0;
  const double ax = std::abs(dx);
  const double ay = std::abs(dy);
  double deg =
      ay <= ax ? small_atan(ay / ax) * kDegPerRad : 90.0 - small_atan(ax / ay) * kDegPerRad;
  if (dx < 0) deg = 180.0 - deg;
  if (dy < 0) deg = 360.0 - deg;
  return deg < 360.0 ? deg : 0.0;
}

}  // namespace sewerplan::detail
