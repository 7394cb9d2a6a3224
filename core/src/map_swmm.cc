// SPDX-License-Identifier: MIT
// The SWMM 5 importer: sections (swmm_sections.h) -> nodes and conduits -> NetworkImport.
#include "sewerplan/core/map_swmm.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "sewerplan/core/map_builder.h"
#include "sewerplan/core/text_file.h"

#include "network_import.h"
#include "swmm_sections.h"
#include "swmm_xsection.h"

namespace sewerplan {
namespace {

using detail::ImportLink;
using detail::ImportNode;
using detail::parse_swmm_number;
using detail::SwmmRow;
using detail::to_upper;

constexpr double kMetresPerFoot = 0.3048;

// Counts of rows handled by a documented fallback, reported as one warning each.
struct Fallbacks {
  std::size_t default_diameter = 0;
  std::size_t other_links = 0;
  std::size_t undimensioned = 0;
  std::size_t no_clear_size = 0;
  std::size_t multi_barrel = 0;
  std::size_t without_xy = 0;
  std::size_t stray_geometry = 0;
};

class SwmmReader {
 public:
  SwmmReader(const detail::SwmmSections& s, const std::string& file, const SwmmImportOptions& o,
             Diagnostics& d)
      : s_(s), file_(file), options_(o), d_(d) {}

  // `before`: where the diagnostics stood before the file was split into sections.
  Result<SewerMap> run(Diagnostics::Mark before) {
    read_options();
    read_map_units();
    read_nodes("JUNCTIONS", true);
    read_nodes("OUTFALLS", false);
    read_nodes("DIVIDERS", true);
    read_nodes("STORAGE", true);
    read_coordinates();
    read_xsections();
    read_conduits();
    read_vertices();
    count_other_links();
    if (net_.links.empty() && !d_.has_errors_since(before)) {
      d_.error(file_, std::to_string(net_.nodes.size()) +
                          " nodes but no conduit a robot could drive ([CONDUITS] with a "
                          "dimensioned cross-section): not a sewer network");
    }
    if (d_.has_errors_since(before)) return Error{ErrorCode::kParse, d_.error_summary(before)};
    report_fallbacks();
    return detail::assemble_network(std::move(net_), std::filesystem::path(file_).stem().string(),
                                    line_locator(file_), file_, d_);
  }

 private:
  std::string at(const SwmmRow& row) const { return file_ + ":" + std::to_string(row.line); }

  // The field `k` of `row` as a number, or an error naming it.
  std::optional<double> number(const SwmmRow& row, std::size_t k, std::string_view what) {
    const std::optional<double> v = parse_swmm_number(row.fields[k]);
    if (!v) {
      d_.error(at(row), std::string(row.fields[0]) + ": " + std::string(what) +
                            " is not a number: '" + std::string(row.fields[k]) + "'");
    }
    return v;
  }

  bool has_fields(const SwmmRow& row, std::size_t n, std::string_view section,
                  std::string_view expected) {
    if (row.fields.size() >= n) return true;
    d_.error(at(row), "[" + std::string(section) + "] row '" + std::string(row.fields[0]) +
                          "': too few fields, expected " + std::string(expected));
    return false;
  }

  void read_options();
  void read_map_units();
  void read_nodes(std::string_view section, bool exit);
  std::optional<double> storage_diameter(const SwmmRow& row) const;
  void read_coordinates();
  void read_xsections();
  void read_conduits();
  std::optional<double> end_invert(const SwmmRow& row, std::size_t k, const std::string& node);
  void read_vertices();
  void count_other_links();
  void report_fallbacks();

  const detail::SwmmSections& s_;
  const std::string& file_;
  const SwmmImportOptions& options_;
  Diagnostics& d_;
  double metres_per_unit_ = kMetresPerFoot;  // lengths, from FLOW_UNITS
  double coordinate_scale_ = kMetresPerFoot;
  bool offsets_are_elevations_ = false;
  detail::NetworkImport net_;
  std::unordered_map<std::string_view, std::size_t> node_of_;
  std::unordered_map<std::string_view, std::size_t> link_of_;
  std::unordered_map<std::string_view, detail::PipeProfile> profile_of_;
  std::unordered_map<std::string_view, std::uint32_t> xsection_line_;  // every [XSECTIONS] row
  std::unordered_map<std::string_view, std::uint32_t> coordinate_line_;
  Fallbacks fallbacks_;
};

void SwmmReader::read_options() {
  std::optional<std::string> flow_units;
  std::uint32_t flow_line = 0;
  for (const SwmmRow& row : s_.rows("OPTIONS")) {
    if (row.fields.size() < 2) continue;
    const std::string key = to_upper(row.fields[0]);
    const std::string value = to_upper(row.fields[1]);
    if (key == "FLOW_UNITS") {
      if (flow_units && *flow_units != value) {
        d_.error(at(row), "mixed units: FLOW_UNITS " + value + " here, but " + *flow_units +
                              " at line " + std::to_string(flow_line));
        continue;
      }
      if (value == "CFS" || value == "GPM" || value == "MGD") {
        metres_per_unit_ = kMetresPerFoot;
      } else if (value == "CMS" || value == "LPS" || value == "MLD") {
        metres_per_unit_ = 1.0;
      } else {
        d_.error(at(row), "unknown FLOW_UNITS '" + std::string(row.fields[1]) +
                              "' (CFS, GPM, MGD, CMS, LPS or MLD)");
        continue;
      }
      flow_units = value;
      flow_line = row.line;
    } else if (key == "LINK_OFFSETS") {
      if (value != "DEPTH" && value != "ELEVATION") {
        d_.error(at(row),
                 "unknown LINK_OFFSETS '" + std::string(row.fields[1]) + "' (DEPTH or ELEVATION)");
      }
      offsets_are_elevations_ = value == "ELEVATION";
    }
  }
  if (!flow_units) {
    d_.warning(file_, "no [OPTIONS] FLOW_UNITS: SWMM's default CFS assumed, lengths in feet");
  }
  coordinate_scale_ = metres_per_unit_;
}

void SwmmReader::read_map_units() {
  for (const SwmmRow& row : s_.rows("MAP")) {
    if (row.fields.size() < 2 || to_upper(row.fields[0]) != "UNITS") continue;
    const std::string value = to_upper(row.fields[1]);
    if (value == "FEET") {
      coordinate_scale_ = kMetresPerFoot;
    } else if (value == "METERS") {
      coordinate_scale_ = 1.0;
    } else if (value == "DEGREES") {
      coordinate_scale_ = 1.0;
      d_.warning(at(row),
                 "[MAP] UNITS DEGREES: positions are kept in degrees, not metres; "
                 "azimuths are only approximate");
    }
  }
}

void SwmmReader::read_nodes(std::string_view section, bool exit) {
  for (const SwmmRow& row : s_.rows(section)) {
    if (!has_fields(row, 2, section, "name and invert elevation")) continue;
    const std::optional<double> invert = number(row, 1, "invert elevation");
    if (!invert) continue;
    std::optional<double> diameter;
    if (section == "STORAGE") diameter = storage_diameter(row);
    if (!diameter) {
      diameter = options_.manhole_diameter_m;
      ++fallbacks_.default_diameter;
    }
    node_of_.emplace(row.fields[0], net_.nodes.size());
    net_.nodes.push_back({.name = std::string(row.fields[0]),
                          .position = {0, 0, *invert * metres_per_unit_},
                          .diameter_m = *diameter,
                          .exit = exit,
                          .line = row.line});
  }
}

// A storage node's plan area at its floor, as the diameter of a circle of that area: FUNCTIONAL
// (area = A1 x depth^A2 + A0, at depth 0) and the 5.2 shapes with base axes (CYLINDRICAL,
// CONICAL, PYRAMIDAL: the smaller axis). None for TABULAR curves or a zero area.
std::optional<double> SwmmReader::storage_diameter(const SwmmRow& row) const {
  if (row.fields.size() < 7) return std::nullopt;
  const std::string shape = to_upper(row.fields[4]);
  const std::optional<double> a = parse_swmm_number(row.fields[5]);
  const std::optional<double> b = parse_swmm_number(row.fields[6]);
  if (!a || !b) return std::nullopt;
  double d = 0;
  if (shape == "FUNCTIONAL") {
    const std::optional<double> a0 =
        row.fields.size() > 7 ? parse_swmm_number(row.fields[7]) : std::nullopt;
    const double area = (*b == 0 ? *a : 0.0) + a0.value_or(0.0);
    d = std::sqrt(std::max(area, 0.0) * 4 / std::numbers::pi);
  } else if (shape == "CYLINDRICAL" || shape == "CONICAL" || shape == "PYRAMIDAL") {
    d = std::min(*a, *b);
  }
  d *= metres_per_unit_;
  if (!std::isfinite(d) || d <= 0) return std::nullopt;
  return d;
}

void SwmmReader::read_coordinates() {
  for (const SwmmRow& row : s_.rows("COORDINATES")) {
    if (!has_fields(row, 3, "COORDINATES", "node, x, y")) continue;
    auto node = node_of_.find(row.fields[0]);
    if (node == node_of_.end()) {
      ++fallbacks_.stray_geometry;
      continue;
    }
    auto [first, inserted] = coordinate_line_.emplace(row.fields[0], row.line);
    if (!inserted) {
      d_.error(at(row), "node " + std::string(row.fields[0]) +
                            ": coordinates given twice (first at line " +
                            std::to_string(first->second) + ")");
      continue;
    }
    const std::optional<double> x = number(row, 1, "x");
    const std::optional<double> y = number(row, 2, "y");
    if (!x || !y) continue;
    ImportNode& n = net_.nodes[node->second];
    n.position.x_m = *x * coordinate_scale_;
    n.position.y_m = *y * coordinate_scale_;
    n.has_xy = true;
  }
  for (const ImportNode& n : net_.nodes) fallbacks_.without_xy += n.has_xy ? 0 : 1;
}

void SwmmReader::read_xsections() {
  for (const SwmmRow& row : s_.rows("XSECTIONS")) {
    auto [first, inserted] = xsection_line_.emplace(row.fields[0], row.line);
    if (!inserted) {
      d_.error(at(row), "link " + std::string(row.fields[0]) +
                            ": cross-section given twice (first at line " +
                            std::to_string(first->second) + ")");
      continue;
    }
    Result<detail::PipeProfile> p = detail::swmm_profile(row.fields, metres_per_unit_);
    if (!p.has_value()) {
      if (p.error().code == ErrorCode::kUnsupportedFormat) {
        ++fallbacks_.undimensioned;
      } else {
        d_.error(at(row), "link " + std::string(row.fields[0]) + ": " + p.error().message);
      }
      continue;
    }
    if (p->no_clear_size) {
      ++fallbacks_.no_clear_size;
      continue;
    }
    profile_of_.emplace(row.fields[0], *p);
  }
}

std::optional<double> SwmmReader::end_invert(const SwmmRow& row, std::size_t k,
                                             const std::string& node) {
  auto it = node_of_.find(node);
  const double node_invert = it == node_of_.end() ? 0.0 : net_.nodes[it->second].position.z_m;
  if (row.fields[k] == "*") return node_invert;
  const std::optional<double> offset = number(row, k, k == 5 ? "inlet offset" : "outlet offset");
  if (!offset) return std::nullopt;
  const double metres = *offset * metres_per_unit_;
  return offsets_are_elevations_ ? metres : node_invert + metres;
}

void SwmmReader::read_conduits() {
  for (const SwmmRow& row : s_.rows("CONDUITS")) {
    if (!has_fields(row, 7, "CONDUITS",
                    "name, from node, to node, length, roughness, inlet and outlet offsets")) {
      continue;
    }
    auto profile = profile_of_.find(row.fields[0]);
    if (profile == profile_of_.end()) {
      if (!xsection_line_.contains(row.fields[0])) {
        d_.error(at(row), "conduit " + std::string(row.fields[0]) + ": no [XSECTIONS] row");
      }
      continue;  // an undimensioned shape (counted) or a bad row (reported)
    }
    const std::optional<double> length = number(row, 3, "length");
    ImportLink link{.name = std::string(row.fields[0]),
                    .from = std::string(row.fields[1]),
                    .to = std::string(row.fields[2]),
                    .length_m = length.value_or(0) * metres_per_unit_,
                    .diameter_m = profile->second.diameter_m,
                    .height_m = profile->second.height_m,
                    .shape = profile->second.shape,
                    .line = row.line};
    const std::optional<double> in = end_invert(row, 5, *link.from);
    const std::optional<double> out = end_invert(row, 6, *link.to);
    if (!length || !in || !out) continue;
    link.from_invert_z_m = *in;
    link.to_invert_z_m = *out;
    if (profile->second.barrels > 1) ++fallbacks_.multi_barrel;
    link_of_.emplace(row.fields[0], net_.links.size());
    net_.links.push_back(std::move(link));
  }
}

void SwmmReader::read_vertices() {
  for (const SwmmRow& row : s_.rows("VERTICES")) {
    if (!has_fields(row, 3, "VERTICES", "link, x, y")) continue;
    auto link = link_of_.find(row.fields[0]);
    if (link == link_of_.end()) continue;  // a pump's, a weir's, or a left-out conduit's
    const std::optional<double> x = number(row, 1, "x");
    const std::optional<double> y = number(row, 2, "y");
    if (!x || !y) continue;
    net_.links[link->second].vertices.push_back({*x * coordinate_scale_, *y * coordinate_scale_});
  }
}

void SwmmReader::count_other_links() {
  for (std::string_view section : {"PUMPS", "ORIFICES", "WEIRS", "OUTLETS"}) {
    for (const SwmmRow& row : s_.rows(section)) {
      ++fallbacks_.other_links;
      if (link_of_.contains(row.fields[0])) {
        d_.error(at(row),
                 "duplicate link name '" + std::string(row.fields[0]) + "': also a conduit");
      }
    }
  }
}

void SwmmReader::report_fallbacks() {
  const Fallbacks& f = fallbacks_;
  auto warn = [&](std::size_t n, const std::string& what) {
    detail::warn_counted(d_, file_, n, what);
  };
  const std::string diameter = detail::metres_text(options_.manhole_diameter_m);
  warn(f.default_diameter, "nodes have no size in SWMM: manhole diameter " + diameter + " assumed");
  warn(f.other_links, "pumps, orifices, weirs or outlets are not drivable: left out");
  warn(f.undimensioned,
       "conduits with an IRREGULAR, CUSTOM, STREET or DUMMY cross-section (no dimensions): left "
       "out");
  warn(f.no_clear_size,
       "conduits have a cross-section of no clear size (a V-shaped channel of bottom width 0, or "
       "a zero Geom): no robot fits, left out");
  warn(f.multi_barrel, "conduits have several barrels: each imported as one pipe");
  warn(f.without_xy, "nodes have no [COORDINATES]: placed at x = y = 0");
  warn(f.stray_geometry, "[COORDINATES] rows name no node: ignored");
}

}  // namespace

Result<SewerMap> read_map_swmm(std::string_view text, const std::string& file_name,
                               Diagnostics& diagnostics, const SwmmImportOptions& options) {
  if (!std::isfinite(options.manhole_diameter_m) || options.manhole_diameter_m <= 0) {
    return Error{ErrorCode::kInvalidArgument, "SWMM import: manhole diameter must be positive"};
  }
  const Diagnostics::Mark before = diagnostics.mark();
  TextDecoding how;
  Result<std::string> utf8 = text_to_utf8(text, "", file_name, how);
  if (!utf8.has_value()) return utf8.error();
  warn_about_decoding(how, file_name, diagnostics);
  const detail::SwmmSections sections = detail::split_swmm_sections(*utf8, file_name, diagnostics);
  if (!sections.header_line("JUNCTIONS") && !sections.header_line("OUTFALLS") &&
      !sections.header_line("STORAGE") && !sections.header_line("DIVIDERS") &&
      !diagnostics.has_errors_since(before)) {
    diagnostics.error(file_name,
                      "no [JUNCTIONS], [OUTFALLS], [STORAGE] or [DIVIDERS] section: "
                      "not a SWMM network");
  }
  return SwmmReader(sections, file_name, options, diagnostics).run(before);
}

}  // namespace sewerplan
