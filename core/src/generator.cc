// SPDX-License-Identifier: MIT
#include "sewerplan/core/generator.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "sewerplan/core/check.h"
#include "sewerplan/core/enum_names.h"
#include "sewerplan/core/map_builder.h"
#include "sewerplan/core/map_queries.h"
#include "sewerplan/core/rng.h"

#include "street_layout.h"

namespace sewerplan {
namespace {

constexpr detail::EnumNames<Topology, 2> kTopologies{{
    {Topology::kTree, "tree"},
    {Topology::kMeshed, "meshed"},
}};
static_assert(detail::distinct(kTopologies));

using detail::StreetLayout;

constexpr double kMaxSmallDropM = 0.20;
constexpr double kMinHighDropM = 0.35;
constexpr double kMaxHighDropM = 0.80;
constexpr double kStraightThroughDeg = 10;

Result<void> check_fraction(double value, std::string_view option) {
  if (value >= 0 && value <= 1) return {};
  std::ostringstream msg;
  msg << "GeneratorOptions." << option << " must be between 0 and 1, got " << value;
  return Error{ErrorCode::kInvalidArgument, msg.str()};
}

Result<void> check_options(const GeneratorOptions& options) {
  if (options.manholes < GeneratorOptions::kMinManholes ||
      options.manholes > GeneratorOptions::kMaxManholes) {
    std::ostringstream msg;
    msg << "GeneratorOptions.manholes must be between " << GeneratorOptions::kMinManholes << " and "
        << GeneratorOptions::kMaxManholes << ", got " << options.manholes;
    return Error{ErrorCode::kInvalidArgument, msg.str()};
  }
  const std::array<std::pair<double, std::string_view>, 4> fractions{{
      {options.mesh_fraction, "mesh_fraction"},
      {options.exit_fraction, "exit_fraction"},
      {options.undrivable_pipe_fraction, "undrivable_pipe_fraction"},
      {options.high_step_fraction, "high_step_fraction"},
  }};
  if (!(options.findings_per_km >= 0 && options.findings_per_km <= 1000)) {
    return Error{ErrorCode::kInvalidArgument, "findings_per_km must be from 0 to 1000"};
  }
  for (const auto& [value, option] : fractions) {
    Result<void> checked = check_fraction(value, option);
    if (!checked.has_value()) return checked;
  }
  return {};
}

// A smooth periodic bump of period 1 and amplitude 1, like sin(2 pi u) but polynomial: 6 sqrt(3)
// f (1 - f) (1 - 2 f) with f the fractional part of u, so the same on every platform.
double wave(double u) {
  constexpr double kScale = 10.392304845413264;  // 6 sqrt(3)
  const double f = u - std::floor(u);
  return kScale * f * (1 - f) * (1 - 2 * f);
}

// Ground height: a tilted plane plus a gentle wave in each direction.
struct Ground {
  explicit Ground(Rng& rng)
      : slope_x(rng.uniform(-0.004, 0.004)),
        slope_y(rng.uniform(-0.004, 0.004)),
        amplitude_m(rng.uniform(0.5, 2.0)),
        wavelength_x_m(rng.uniform(300, 900)),
        wavelength_y_m(rng.uniform(300, 900)),
        phase_x(rng.uniform01()),
        phase_y(rng.uniform01()) {}
  double height_m(const Eigen::Vector2d& p) const {
    return slope_x * p.x() + slope_y * p.y() +
           amplitude_m *
               (wave(p.x() / wavelength_x_m + phase_x) + wave(p.y() / wavelength_y_m + phase_y));
  }
  double slope_x, slope_y, amplitude_m, wavelength_x_m, wavelength_y_m, phase_x, phase_y;
};

// The layout with everything the records need. Raw indices: manholes and pipes from 0.
struct Network {
  StreetLayout layout;  // pipes oriented after orient_flow(): [0] upstream, [1] downstream
  std::vector<std::uint32_t> first_incident;  // CSR: pipes of manhole m are incident[first[m]..]
  std::vector<std::uint32_t> incident;
  std::vector<double> floor_z_m;         // per manhole
  std::vector<std::uint32_t> bfs_order;  // from the outfall
  std::vector<std::uint32_t> distance;   // pipes from the outfall, per manhole
  std::vector<double> pipe_diameter_m;   // per pipe
  std::vector<double> drop_m;            // per pipe: its downstream end above the floor
  std::vector<bool> exit;                // per manhole
};

void build_incidence(Network& net) {
  const std::size_t n = net.layout.positions.size();
  net.first_incident.assign(n + 1, 0);
  for (const auto& [a, b] : net.layout.pipes) {
    ++net.first_incident[a + 1];
    ++net.first_incident[b + 1];
  }
  for (std::size_t m = 0; m < n; ++m) net.first_incident[m + 1] += net.first_incident[m];
  net.incident.resize(2 * net.layout.pipes.size());
  std::vector<std::uint32_t> fill(net.first_incident.begin(), net.first_incident.end() - 1);
  for (std::uint32_t p = 0; p < net.layout.pipes.size(); ++p) {
    for (std::uint32_t m : net.layout.pipes[p]) net.incident[fill[m]++] = p;
  }
}

std::uint32_t other_end(const Network& net, std::uint32_t pipe, std::uint32_t m) {
  const auto& ends = net.layout.pipes[pipe];
  return ends[0] == m ? ends[1] : ends[0];
}

void place_floors(Network& net, Rng& rng) {
  const Ground ground(rng);
  net.floor_z_m.reserve(net.layout.positions.size());
  for (const Eigen::Vector2d& at : net.layout.positions) {
    net.floor_z_m.push_back(ground.height_m(at) - rng.uniform(2.0, 4.0));
  }
}

// Breadth-first from the lowest intersection, then every pipe points down the distance.
void orient_flow(Network& net) {
  const std::size_t n = net.layout.positions.size();
  const auto intersections = net.floor_z_m.begin() + net.layout.intersections;
  const auto outfall = static_cast<std::uint32_t>(
      std::min_element(net.floor_z_m.begin(), intersections) - net.floor_z_m.begin());
  constexpr std::uint32_t kUnseen = 0xffffffff;
  net.distance.assign(n, kUnseen);
  net.bfs_order.reserve(n);
  net.bfs_order.push_back(outfall);
  net.distance[outfall] = 0;
  for (std::size_t head = 0; head < net.bfs_order.size(); ++head) {
    const std::uint32_t m = net.bfs_order[head];
    for (std::uint32_t i = net.first_incident[m]; i < net.first_incident[m + 1]; ++i) {
      const std::uint32_t next = other_end(net, net.incident[i], m);
      if (net.distance[next] != kUnseen) continue;
      net.distance[next] = net.distance[m] + 1;
      net.bfs_order.push_back(next);
    }
  }
  SEWER_CHECK(net.bfs_order.size() == n, "generated network is not connected");
  for (auto& ends : net.layout.pipes) {
    const auto key = [&](std::uint32_t m) { return std::pair(net.distance[m], m); };
    if (key(ends[0]) < key(ends[1])) std::swap(ends[0], ends[1]);
  }
}

// A drivable size from the number of manholes draining through the pipe.
double drivable_diameter_m(std::uint32_t catchment) {
  if (catchment < 30) return 0.30;
  if (catchment < 300) return 0.40;
  if (catchment < 3000) return 0.50;
  return 0.60;
}

void size_pipes(Network& net, const GeneratorOptions& options, Rng& rng) {
  // Catchment along the breadth-first tree: each manhole drains into its first pipe towards the
  // outfall.
  std::vector<std::uint32_t> catchment(net.layout.positions.size(), 1);
  for (auto it = net.bfs_order.rbegin(); it != net.bfs_order.rend(); ++it) {
    const std::uint32_t m = *it;
    for (std::uint32_t i = net.first_incident[m]; i < net.first_incident[m + 1]; ++i) {
      const std::uint32_t next = other_end(net, net.incident[i], m);
      if (net.distance[next] + 1 == net.distance[m]) {
        catchment[next] += catchment[m];
        break;
      }
    }
  }
  constexpr std::array<double, 4> kUndrivable{0.20, 0.25, 0.80, 1.00};
  const std::size_t pipes = net.layout.pipes.size();
  net.pipe_diameter_m.resize(pipes);
  net.drop_m.resize(pipes);
  for (std::size_t p = 0; p < pipes; ++p) {
    net.pipe_diameter_m[p] = rng.bernoulli(options.undrivable_pipe_fraction)
                                 ? kUndrivable[rng.below(kUndrivable.size())]
                                 : drivable_diameter_m(catchment[net.layout.pipes[p][0]]);
    net.drop_m[p] = rng.bernoulli(options.high_step_fraction)
                        ? rng.uniform(kMinHighDropM, kMaxHighDropM)
                        : rng.uniform(0, kMaxSmallDropM);
  }
}

// Exactly max(1, round(fraction * n)) exits, by Floyd's sampling without replacement.
void choose_exits(Network& net, double fraction, Rng& rng) {
  const std::size_t n = net.layout.positions.size();
  const auto wanted = static_cast<std::size_t>(std::llround(fraction * static_cast<double>(n)));
  const std::size_t exits = std::clamp<std::size_t>(wanted, 1, n);
  net.exit.assign(n, false);
  for (std::size_t j = n - exits; j < n; ++j) {
    const std::size_t t = rng.below(j + 1);
    net.exit[net.exit[t] ? j : t] = true;
  }
}

// "M7" for index 6. (Not "M" + std::to_string: GCC 12 -O3 warns falsely about it, -Wrestrict.)
std::string numbered_name(char prefix, std::uint32_t index) {
  std::array<char, 16> buffer{prefix};
  const auto end = std::to_chars(buffer.data() + 1, buffer.data() + buffer.size(), index + 1).ptr;
  return std::string(buffer.data(), end);
}
std::string manhole_name(std::uint32_t m) { return numbered_name('M', m); }
std::string pipe_name(std::uint32_t p) { return numbered_name('P', p); }

std::optional<char> variant_of(const std::vector<SlotRecord>& slots) {
  if (slots.size() != 3) return std::nullopt;
  for (std::size_t a = 0; a < 3; ++a) {
    for (std::size_t b = a + 1; b < 3; ++b) {
      const double turn = normalize_deg(slots[b].azimuth_deg - slots[a].azimuth_deg - 180.0);
      if (std::abs(turn) <= kStraightThroughDeg) return 'A';
    }
  }
  return 'B';
}

ManholeRecord manhole_record(const Network& net, std::uint32_t m) {
  ManholeRecord record;
  record.name = manhole_name(m);
  const Eigen::Vector2d& at = net.layout.positions[m];
  record.position = {at.x(), at.y(), net.floor_z_m[m]};
  record.exit = net.exit[m];
  record.slots.reserve(net.first_incident[m + 1] - net.first_incident[m]);
  for (std::uint32_t i = net.first_incident[m]; i < net.first_incident[m + 1]; ++i) {
    const std::uint32_t p = net.incident[i];
    const bool downstream_end = net.layout.pipes[p][1] == m;
    record.slots.push_back(
        {.pipe = pipe_name(p),
         .azimuth_deg = detail::direction_deg(at, net.layout.positions[other_end(net, p, m)]),
         .invert_z_m = net.floor_z_m[m] + (downstream_end ? net.drop_m[p] : 0.0)});
  }
  std::sort(record.slots.begin(), record.slots.end(),
            [](const SlotRecord& x, const SlotRecord& y) { return x.azimuth_deg < y.azimuth_deg; });
  record.diameter_m = record.slots.size() >= 3 ? 1.2 : 1.0;
  record.variant = variant_of(record.slots);
  return record;
}

PipeRecord pipe_record(const Network& net, std::uint32_t p) {
  const auto [from, to] = net.layout.pipes[p];
  return {.name = pipe_name(p),
          .from = manhole_name(from),
          .to = manhole_name(to),
          .length_m = (net.layout.positions[from] - net.layout.positions[to]).norm(),
          .diameter_m = net.pipe_diameter_m[p]};
}

std::string default_name(const GeneratorOptions& options) {
  std::ostringstream name;
  name << "generated-" << to_string(options.topology) << '-' << options.manholes << '-'
       << options.seed;
  return name.str();
}

Result<SewerMap> build_map(const Network& net, const GeneratorOptions& options) {
  MapBuilder builder(options.name.empty() ? default_name(options) : options.name,
                     line_locator("<generator>"));
  const auto manholes = static_cast<std::uint32_t>(net.layout.positions.size());
  const auto pipes = static_cast<std::uint32_t>(net.layout.pipes.size());
  builder.reserve(manholes, pipes);
  for (std::uint32_t m = 0; m < manholes; ++m) builder.add_manhole(manhole_record(net, m));
  for (std::uint32_t p = 0; p < pipes; ++p) builder.add_pipe(pipe_record(net, p));
  Diagnostics diagnostics;
  return std::move(builder).build(diagnostics);
}

}  // namespace

std::string_view to_string(Topology topology) { return detail::name_of(kTopologies, topology); }

std::optional<Topology> topology_from_string(std::string_view name) {
  return detail::value_of(kTopologies, name);
}

std::string topology_names() { return detail::names_joined(kTopologies); }

namespace {

// GeneratorOptions::findings_per_km: random findings, each pipe's number drawn from its length.
SewerMap add_random_findings(SewerMap map, double per_km, Rng& rng) {
  struct Kind {
    const char* code;
    double weight;
    bool cross_section;
  };
  static constexpr std::array<Kind, 6> kKinds{{{"BBA", 0.30, true},
                                               {"BBC", 0.25, true},
                                               {"BBB", 0.15, true},
                                               {"BAJ", 0.15, false},
                                               {"BBE", 0.10, true},
                                               {"BAC", 0.05, false}}};
  std::vector<FindingRecord> findings;
  for (const Pipe& pipe : map.pipes()) {
    const double expected = pipe.length_m / 1000 * per_km;
    auto count = static_cast<std::size_t>(expected);
    if (rng.bernoulli(expected - static_cast<double>(count))) ++count;
    for (std::size_t i = 0; i < count; ++i) {
      double pick = rng.uniform01();
      const Kind* kind = &kKinds.back();
      for (const Kind& k : kKinds) {
        if (pick < k.weight) {
          kind = &k;
          break;
        }
        pick -= k.weight;
      }
      FindingRecord f{
          .pipe = pipe.name, .code = kind->code, .station_m = rng.uniform(0.0, pipe.length_m)};
      if (kind->cross_section) f.quantity1 = std::round(rng.uniform(5.0, 40.0));
      findings.push_back(std::move(f));
    }
  }
  Diagnostics ignored;  // every finding names a pipe of the map, on it
  return MapBuilder::add_findings(std::move(map), std::move(findings), line_locator("<generator>"),
                                  ignored);
}

}  // namespace

Result<SewerMap> generate_network(const GeneratorOptions& options) {
  Result<void> checked = check_options(options);
  if (!checked.has_value()) return checked.error();
  Rng rng(options.seed);
  Rng layout_rng = rng.split();
  Rng height_rng = rng.split();
  Rng pipe_rng = rng.split();
  Rng exit_rng = rng.split();
  Network net;
  net.layout = detail::make_street_layout(options.manholes, options.topology, options.mesh_fraction,
                                          layout_rng);
  build_incidence(net);
  place_floors(net, height_rng);
  orient_flow(net);
  size_pipes(net, options, pipe_rng);
  choose_exits(net, options.exit_fraction, exit_rng);
  Rng finding_rng = rng.split();
  Result<SewerMap> map = build_map(net, options);
  if (!map.has_value() || options.findings_per_km <= 0) return map;
  return add_random_findings(std::move(*map), options.findings_per_km, finding_rng);
}

}  // namespace sewerplan
