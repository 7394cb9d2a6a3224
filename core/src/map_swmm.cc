// SPDX-License-Identifier: MIT
// The SWMM 5 importer: sections (swmm_sections.h) -> nodes and conduits -> NetworkImport.
#include "sewerplan/core/map_swmm.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "sewerplan/core/limits.h"
#include "sewerplan/core/map_builder.h"
#include "sewerplan/core/message_text.h"
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
  std::size_t bad_barrels = 0;
};

// A [STORAGE] unit wider than any manhole (kMaxDiameter_m): a pond or a treatment tank, which no
// robot enters. It is left out of the map; the conduits that end in it end blind there.
struct LeftOutStorage {
  double invert_z_m = 0;
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
    fit_schematic();
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
      d_.error(at(row), input_text(row.fields[0]) + ": " + std::string(what) +
                            " is not a number: " + input_quoted(row.fields[k]));
    }
    return v;
  }

  bool has_fields(const SwmmRow& row, std::size_t n, std::string_view section,
                  std::string_view expected) {
    if (row.fields.size() >= n) return true;
    d_.error(at(row), "[" + std::string(section) + "] row " + input_quoted(row.fields[0]) +
                          ": too few fields, expected " + std::string(expected));
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
  void fit_schematic();
  std::optional<std::string> link_end(const SwmmRow& row, std::size_t k);
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
  std::unordered_map<std::string_view, LeftOutStorage> left_out_storage_;
  std::optional<std::uint32_t> schematic_line_;  // [MAP] UNITS NONE
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
        d_.error(at(row), "unknown FLOW_UNITS " + input_quoted(row.fields[1]) +
                              " (CFS, GPM, MGD, CMS, LPS or MLD)");
        continue;
      }
      flow_units = value;
      flow_line = row.line;
    } else if (key == "LINK_OFFSETS") {
      if (value != "DEPTH" && value != "ELEVATION") {
        d_.error(at(row),
                 "unknown LINK_OFFSETS " + input_quoted(row.fields[1]) + " (DEPTH or ELEVATION)");
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
    } else if (value == "NONE") {
      schematic_line_ = row.line;
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
    } else if (*diameter > kMaxDiameter_m) {
      const LimitText t = limit_text(*diameter, kMaxDiameter_m);
      d_.warning(at(row), "storage unit " + input_text(row.fields[0]) + " is " + t.value +
                              " m across, more than the " + t.limit +
                              " m of the widest manhole: a pond or tank no robot enters; left "
                              "out, its conduits end blind there");
      left_out_storage_.emplace(row.fields[0], LeftOutStorage{*invert * metres_per_unit_});
      continue;
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
      if (!left_out_storage_.contains(row.fields[0])) ++fallbacks_.stray_geometry;
      continue;
    }
    auto [first, inserted] = coordinate_line_.emplace(row.fields[0], row.line);
    if (!inserted) {
      d_.error(at(row), "node " + input_text(row.fields[0]) +
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
      d_.error(at(row), "link " + input_text(row.fields[0]) +
                            ": cross-section given twice (first at line " +
                            std::to_string(first->second) + ")");
      continue;
    }
    Result<detail::PipeProfile> p = detail::swmm_profile(row.fields, metres_per_unit_);
    if (!p.has_value()) {
      if (p.error().code == ErrorCode::kUnsupportedFormat) {
        ++fallbacks_.undimensioned;
      } else {
        d_.error(at(row), "link " + input_text(row.fields[0]) + ": " + p.error().message);
      }
      continue;
    }
    if (p->no_clear_size) {
      ++fallbacks_.no_clear_size;
      continue;
    }
    if (!p->barrels_read) ++fallbacks_.bad_barrels;
    profile_of_.emplace(row.fields[0], *p);
  }
}

std::optional<double> SwmmReader::end_invert(const SwmmRow& row, std::size_t k,
                                             const std::string& node) {
  auto it = node_of_.find(node);
  auto storage = left_out_storage_.find(node);
  const double node_invert = it != node_of_.end() ? net_.nodes[it->second].position.z_m
                             : storage != left_out_storage_.end() ? storage->second.invert_z_m
                                                                  : 0.0;
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
        d_.error(at(row), "conduit " + input_text(row.fields[0]) + ": no [XSECTIONS] row");
      }
      continue;  // an undimensioned shape (counted) or a bad row (reported)
    }
    if (profile->second.diameter_m > kMaxDiameter_m) {
      const LimitText t = limit_text(profile->second.diameter_m, kMaxDiameter_m);
      d_.warning(at(row), "conduit " + input_text(row.fields[0]) + " is " + t.value +
                              " m wide and high, more than the " + t.limit +
                              " m of the largest pipe: a channel no robot drives; left out");
      continue;
    }
    const std::optional<double> length = number(row, 3, "length");
    const std::optional<std::string> from = link_end(row, 1);
    const std::optional<std::string> to = link_end(row, 2);
    if (!from && !to) {
      d_.warning(at(row), "conduit " + input_text(row.fields[0]) +
                              " joins two storage units that are left out: left out too");
      continue;
    }
    ImportLink link{.name = std::string(row.fields[0]),
                    .from = from,
                    .to = to,
                    .length_m = length.value_or(0) * metres_per_unit_,
                    .diameter_m = profile->second.diameter_m,
                    .height_m = profile->second.height_m,
                    .shape = profile->second.shape,
                    .line = row.line};
    const std::optional<double> in = end_invert(row, 5, std::string(row.fields[1]));
    const std::optional<double> out = end_invert(row, 6, std::string(row.fields[2]));
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

// A conduit's end node (field `k` of its row), or none where it is a storage unit left out.
std::optional<std::string> SwmmReader::link_end(const SwmmRow& row, std::size_t k) {
  if (left_out_storage_.contains(row.fields[k])) return std::nullopt;
  return std::string(row.fields[k]);
}

// [MAP] UNITS NONE: the coordinates are a drawing (a schematic of the network), not a survey. The
// map has no coordinate system; pipe lengths come from [CONDUITS] as always; the positions are
// kept only as the drawing, which gives the pipes' directions in each manhole. A drawing may lie
// anywhere on its canvas: one beyond kMaxCoordinate_m is moved, and shrunk if it is wider than
// that, to fit, keeping its shape and so every direction.
void SwmmReader::fit_schematic() {
  if (!schematic_line_) return;
  std::array<double, 2> low{0, 0};
  std::array<double, 2> high{0, 0};
  bool any = false;
  auto extend = [&](double x, double y) {
    low = any ? std::array{std::min(low[0], x), std::min(low[1], y)} : std::array{x, y};
    high = any ? std::array{std::max(high[0], x), std::max(high[1], y)} : std::array{x, y};
    any = true;
  };
  for (const ImportNode& n : net_.nodes) {
    if (n.has_xy) extend(n.position.x_m, n.position.y_m);
  }
  for (const ImportLink& l : net_.links) {
    for (const std::array<double, 2>& v : l.vertices) extend(v[0], v[1]);
  }
  const std::string where = file_ + ":" + std::to_string(*schematic_line_);
  const std::string what =
      "[MAP] UNITS NONE: the coordinates are a schematic drawing, not a survey: no coordinate "
      "system, pipe lengths from [CONDUITS], positions kept only as the drawing";
  const double reach =
      std::max({std::abs(low[0]), std::abs(low[1]), std::abs(high[0]), std::abs(high[1])});
  if (!any || reach <= kMaxCoordinate_m) {
    d_.warning(where, what);
    return;
  }
  const double extent = std::max(high[0] - low[0], high[1] - low[1]);
  const double scale = extent > kMaxCoordinate_m ? kMaxCoordinate_m / extent : 1.0;
  auto fit = [&](double& x, double& y) {
    x = (x - low[0]) * scale;
    y = (y - low[1]) * scale;
  };
  for (ImportNode& n : net_.nodes) {
    if (n.has_xy) fit(n.position.x_m, n.position.y_m);
  }
  for (ImportLink& l : net_.links) {
    for (std::array<double, 2>& v : l.vertices) fit(v[0], v[1]);
  }
  const LimitText t = limit_text(reach, kMaxCoordinate_m);
  d_.warning(where, what + "; the drawing reaches " + t.value + " m, beyond the " + t.limit +
                        " m a map may, so it is moved to start at (0, 0)" +
                        (scale < 1 ? " and shrunk by a factor of " + number_text(1 / scale)
                                   : std::string()));
}

void SwmmReader::count_other_links() {
  for (std::string_view section : {"PUMPS", "ORIFICES", "WEIRS", "OUTLETS"}) {
    std::string kind(section.substr(0, section.size() - 1));
    std::transform(kind.begin(), kind.end(), kind.begin(),
                   [](char c) { return static_cast<char>(std::tolower(c)); });
    for (const SwmmRow& row : s_.rows(section)) {
      ++fallbacks_.other_links;
      if (link_of_.contains(row.fields[0])) {
        d_.error(at(row),
                 "duplicate link name " + input_quoted(row.fields[0]) + ": also a conduit");
      } else if (row.fields.size() >= 3 && row.fields[1] == row.fields[2]) {
        d_.warning(at(row), kind + " " + input_text(row.fields[0]) + " joins node " +
                                input_text(row.fields[1]) +
                                " to itself (it is left out like every " + kind + ")");
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
  warn(f.bad_barrels,
       "conduits have a Barrels field that is not a whole number from 1 to 100: one barrel "
       "assumed (each conduit is imported as one pipe anyway)");
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
