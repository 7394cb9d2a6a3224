// SPDX-License-Identifier: MIT
#include "network_import.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace sewerplan::detail {
namespace {

// Points closer than this to the node give no direction at all.
constexpr double kSamePointM = 1e-9;

struct PendingSlot {
  std::uint32_t node;
  std::size_t slot;  // index in that manhole's slot records
};

struct Direction {
  std::array<double, 2> origin;  // where the pipe's end lies in the manhole
  std::array<double, 2> point;   // the point it heads for
  bool skipped_inside = false;   // points inside the manhole were passed over to find it
};

// Closer than this to where the pipe's end lies, a point says nothing about its direction (survey
// noise: two points a few centimetres apart).
constexpr double kDirectionMinM = 0.1;

// Where the pipe leaves the node at `end` and the point it heads for. A pipe's line often ends at
// the manhole's floor point (ISYBAU: SMP), 5 to 20 cm off the cover point that gives the node's
// position; the direction between cover and floor says nothing about the pipe, and neither does
// the one from the cover to a point just outside the shaft (the 2017 samples mark the pipe's start
// at the shaft wall, RAP, 0.5 m from the floor point: seen from the cover 20 deg off). So where
// the line's own end lies inside the shaft (`vertices_include_ends`), that is the origin; the
// direction is to the first point along the line farther than kDirectionMinM from it and outside
// the shaft, the far node counting as the last point. If there is none, the farthest distinct one.
// Where the line marks the pipe's mouth at the wall (`starts_at_mouth`), the direction is the
// pipe's axis from there: the channel from the floor point to the wall may bend 20 degrees.
std::optional<Direction> next_point(const ImportLink& link, std::size_t end, const ImportNode& node,
                                    const ImportNode* far) {
  std::vector<std::array<double, 2>> along;
  const std::size_t n = link.vertices.size();
  for (std::size_t k = 0; k < n; ++k) along.push_back(link.vertices[end == 0 ? k : n - 1 - k]);
  if (far != nullptr && far->has_xy) along.push_back({far->position.x_m, far->position.y_m});
  const double radius = node.diameter_m / 2;
  const std::array<double, 2> centre{node.position.x_m, node.position.y_m};
  auto distance = [](const std::array<double, 2>& a, const std::array<double, 2>& b) {
    return std::hypot(a[0] - b[0], a[1] - b[1]);
  };
  std::array<double, 2> origin = centre;
  bool skipped = false;
  if (link.starts_at_mouth[end] && n > 0) {  // the pipe's axis from its mouth at the wall
    for (const std::array<double, 2>& p : along) {
      if (distance(p, along.front()) > kDirectionMinM) return Direction{along.front(), p, false};
    }
  }
  if (link.vertices_include_ends && n > 0) {
    const double d = distance(along.front(), centre);
    if (d > kSamePointM && d <= radius) {
      origin = along.front();
      skipped = true;
    }
  }
  std::optional<std::array<double, 2>> farthest;
  double farthest_m = kSamePointM;
  for (const std::array<double, 2>& p : along) {
    const double from_origin = distance(p, origin);
    if (from_origin > kDirectionMinM && distance(p, centre) > radius) {
      return Direction{origin, p, skipped};
    }
    if (distance(p, centre) > kSamePointM) skipped = true;
    if (from_origin > farthest_m) {
      farthest_m = from_origin;
      farthest = p;
    }
  }
  if (farthest) return Direction{origin, *farthest, skipped};
  return std::nullopt;
}

}  // namespace

void warn_counted(Diagnostics& diagnostics, const std::string& where, std::size_t count,
                  const std::string& what) {
  if (count > 0) diagnostics.warning(where, std::to_string(count) + " " + what);
}

std::string metres_text(double metres) {
  std::ostringstream out;
  out << metres << " m";
  return out.str();
}

double azimuth_deg(double x0, double y0, double x1, double y1) {
  const double deg = std::atan2(y1 - y0, x1 - x0) * 180.0 / std::numbers::pi;
  return deg == -180.0 ? 180.0 : deg;
}

Result<SewerMap> assemble_network(NetworkImport network, std::string map_name, Locator locator,
                                  const std::string& where, Diagnostics& diagnostics) {
  std::unordered_map<std::string_view, std::uint32_t> node_index;
  node_index.reserve(network.nodes.size());
  for (std::uint32_t i = 0; i < network.nodes.size(); ++i) {
    node_index.emplace(network.nodes[i].name,
                       i);  // a duplicate keeps the first; MapBuilder says so
  }
  std::vector<std::vector<SlotRecord>> slots(network.nodes.size());
  std::vector<std::vector<std::optional<double>>> slot_order(network.nodes.size());
  std::vector<PendingSlot> pending;
  std::size_t inside = 0;  // pipe ends whose line begins inside the manhole
  auto find = [&](const std::optional<std::string>& name) -> const ImportNode* {
    if (!name) return nullptr;
    auto it = node_index.find(*name);
    return it == node_index.end() ? nullptr : &network.nodes[it->second];
  };
  for (const ImportLink& link : network.links) {
    for (std::size_t end = 0; end < 2; ++end) {
      const std::optional<std::string>& name = end == 0 ? link.from : link.to;
      if (!name) continue;  // a blind end
      auto it = node_index.find(*name);
      if (it == node_index.end()) continue;  // MapBuilder reports the unknown manhole
      const ImportNode& node = network.nodes[it->second];
      SlotRecord slot{.pipe = link.name,
                      .invert_z_m = end == 0 ? link.from_invert_z_m : link.to_invert_z_m,
                      .line = link.line};
      const std::optional<Direction> p =
          node.has_xy && !link.azimuth_deg[end]
              ? next_point(link, end, node, find(end == 0 ? link.to : link.from))
              : std::nullopt;
      if (link.azimuth_deg[end]) {
        slot.azimuth_deg = *link.azimuth_deg[end];
      } else if (p) {
        slot.azimuth_deg = azimuth_deg(p->origin[0], p->origin[1], p->point[0], p->point[1]);
        if (p->skipped_inside) ++inside;
      } else {
        pending.push_back({it->second, slots[it->second].size()});
      }
      slots[it->second].push_back(std::move(slot));
      slot_order[it->second].push_back(link.slot_index[end]);
    }
  }
  // Slots numbered by the source: in that order when the numbers are 0..k-1, each once.
  std::size_t misnumbered = 0;
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const std::vector<std::optional<double>>& order = slot_order[i];
    if (std::ranges::none_of(order, [](const auto& o) { return o.has_value(); })) continue;
    std::vector<std::optional<std::size_t>> at(order.size());
    bool valid = true;
    for (std::size_t s = 0; s < order.size() && valid; ++s) {
      const std::optional<double>& o = order[s];
      valid = o && *o >= 0 && *o < static_cast<double>(order.size()) && *o == std::floor(*o) &&
              !at[static_cast<std::size_t>(*o)];
      if (valid) at[static_cast<std::size_t>(*o)] = s;
    }
    if (!valid) {
      ++misnumbered;
      continue;
    }
    std::vector<SlotRecord> sorted;
    sorted.reserve(order.size());
    for (const std::optional<std::size_t>& s : at) sorted.push_back(std::move(slots[i][*s]));
    // The pending fallbacks refer to positions in the old order.
    for (PendingSlot& p : pending) {
      if (p.node != i) continue;
      for (std::size_t k = 0; k < at.size(); ++k) {
        if (*at[k] == p.slot) {
          p.slot = k;
          break;
        }
      }
    }
    slots[i] = std::move(sorted);
  }
  warn_counted(diagnostics, where, misnumbered,
               "manholes have slot numbers that are not 0..k-1, each once: their slots are in the "
               "order of the pipes");
  // Fallback: spread each manhole's slots of unknown direction evenly around it.
  std::vector<std::uint32_t> unknown(network.nodes.size(), 0);
  for (const PendingSlot& s : pending) ++unknown[s.node];
  std::vector<std::uint32_t> placed(network.nodes.size(), 0);
  for (const PendingSlot& s : pending) {
    slots[s.node][s.slot].azimuth_deg = 360.0 * placed[s.node]++ / unknown[s.node];
  }
  if (!pending.empty()) {
    diagnostics.warning(where,
                        std::to_string(pending.size()) +
                            " pipe ends have no known direction (a node without "
                            "coordinates); their azimuths are spread evenly in each manhole");
  }
  warn_counted(diagnostics, where, inside,
               "pipe ends begin inside their manhole (their line ends at a point within the "
               "shaft, such as the floor point, a few centimetres from the node's position): "
               "their direction is taken from the pipe's next point outside the shaft");
  MapBuilder builder(std::move(map_name), std::move(locator));
  builder.reserve(network.nodes.size(), network.links.size());
  builder.set_crs(std::move(network.crs));
  for (std::size_t i = 0; i < network.nodes.size(); ++i) {
    ImportNode& n = network.nodes[i];
    builder.add_manhole({.name = std::move(n.name),
                         .position = n.position,
                         .diameter_m = n.diameter_m,
                         .exit = n.exit,
                         .variant = n.variant,
                         .shaft_length_m = n.shaft_length_m,
                         .shaft_width_m = n.shaft_width_m,
                         .depth_m = n.depth_m,
                         .slots = std::move(slots[i]),
                         .line = n.line});
  }
  for (ImportLink& l : network.links) {
    builder.add_pipe({.name = std::move(l.name),
                      .from = std::move(l.from),
                      .to = std::move(l.to),
                      .length_m = l.length_m,
                      .diameter_m = l.diameter_m,
                      .shape = l.shape,
                      .height_m = l.height_m,
                      .blockage_risk = l.blockage_risk,
                      .line = l.line});
  }
  for (FindingRecord& f : network.findings) builder.add_finding(std::move(f));
  for (PointRecord& p : network.points) builder.add_point(std::move(p));
  return std::move(builder).build(diagnostics);
}

}  // namespace sewerplan::detail
