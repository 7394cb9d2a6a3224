// SPDX-License-Identifier: MIT
#include "isybau_geometry.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "condition_isybau.h"
#include "xml_support.h"

namespace sewerplan::detail {
namespace {

using XmlNode = pugi::xml_node;

// The AdV names of the coordinate reference systems German sewer data is surveyed in, as ISYBAU's
// Lagesystem gives them (GeoInfoDok's CRS list), by prefix: "DE_DHDN_3GK3_NW177" is Gauss-Krüger
// zone 3 whatever the state's realisation (the suffix); PROJ transforms it with the national
// datum shift.
constexpr std::array<std::pair<std::string_view, std::uint32_t>, 8> kAdvCrs{{
    {"ETRS89_UTM32", 25832},
    {"ETRS89_UTM33", 25833},
    {"DE_ETRS89_UTM32", 25832},
    {"DE_ETRS89_UTM33", 25833},
    {"DE_DHDN_3GK2", 31466},
    {"DE_DHDN_3GK3", 31467},
    {"DE_DHDN_3GK4", 31468},
    {"DE_DHDN_3GK5", 31469},
}};

// A Lagesystem as a Crs: an AdV name (kAdvCrs), "EPSG:25832", or an EPSG code alone.
std::optional<Crs> crs_of_lagesystem(std::string_view text) {
  for (const auto& [prefix, code] : kAdvCrs) {
    if (text.starts_with(prefix)) return Crs{.authority = "EPSG", .code = code};
  }
  Result<Crs> crs = parse_crs(text);
  if (!crs.has_value()) crs = parse_crs("EPSG:" + std::string(text));
  return crs.has_value() ? std::optional(std::move(*crs)) : std::nullopt;
}

}  // namespace

std::optional<Crs> read_isybau_crs(XmlNode root, const std::string& file, Diagnostics& d) {
  std::vector<XmlNode> found;
  detail::collect(root, "CRSLage", found);
  detail::collect(root, "Lagesystem", found);
  std::optional<Crs> crs;
  for (XmlNode n : found) {
    const std::string_view text = xml::text(n);
    if (text.empty()) continue;
    std::optional<Crs> this_one = crs_of_lagesystem(text);
    if (!this_one) {
      d.warning(file + ":" + xml::path(n),
                std::string(xml::local_name(n)) + " \"" + std::string(text) +
                    "\" is not a reference system sewerplan knows: the map has no CRS "
                    "(give one with --crs EPSG:NNNN)");
      return std::nullopt;
    }
    if (crs && *crs != *this_one) {
      d.warning(file + ":" + xml::path(n),
                std::string(xml::local_name(n)) + " \"" + std::string(text) + "\" differs from " +
                    crs->to_string() +
                    " of the objects before: the map has no CRS (give one with --crs)");
      return std::nullopt;
    }
    crs = std::move(this_one);
  }
  return crs;
}

// German surveys write a UTM Rechtswert with its zone in front: 32570429.702 is easting 570429.702
// in zone 32 (the official ISYBAU samples and most real exports in ETRS89_UTM32 do). With a UTM
// CRS (EPSG:25832, 25833), such a Rechtswert (zone x 10^6 + an easting below 10^6) is read as the
// easting, with one warning; without it the map would hold x values 32 000 km off the zone.
void strip_utm_zone_prefix(NetworkImport& net, const std::string& file, Diagnostics& d) {
  if (!net.crs || net.crs->authority != "EPSG" ||
      (net.crs->code != 25832 && net.crs->code != 25833)) {
    return;
  }
  const double zone = net.crs->code - 25800;
  const double prefix = zone * 1e6;
  std::size_t stripped = 0;
  auto strip = [&](double& x) {
    if (x >= prefix && x < prefix + 1e6) {
      x -= prefix;
      ++stripped;
    }
  };
  for (ImportNode& node : net.nodes) {
    if (node.has_xy) strip(node.position.x_m);
  }
  for (ImportLink& link : net.links) {
    for (std::array<double, 2>& v : link.vertices) strip(v[0]);
  }
  warn_counted(d, file, stripped,
               "Rechtswerte carry the UTM zone number " + std::to_string(static_cast<int>(zone)) +
                   " in front (as 32570429.70 for easting 570429.70): read without it, "
                   "as eastings in " +
                   net.crs->to_string());
}

namespace {

// The points of a chain of segments (Kante elements with Start and Ende) below `parent`: the first
// Start, then every Ende.
void append_segments(XmlNode parent, std::vector<XmlNode>& points) {
  const std::size_t before = points.size();
  for (XmlNode k = parent.first_child(); k; k = k.next_sibling()) {
    if (xml::local_name(k) != "Kante") continue;
    if (points.size() == before) points.push_back(xml::child(k, "Start"));
    points.push_back(xml::child(k, "Ende"));
  }
}

}  // namespace

// The pipe's line. 2013 exports store segments (Kanten/Kante with Start and Ende); the 2017
// samples a polyline (Polygone/Polygon, Polygonart 3) of such segments; 2006 a Polygon of
// Punkte. Closed rings (Polygonart 1, 2: an outline) are not the line. All its points are the
// link's vertices: those at a node are skipped when taking directions, and at a connection point
// (a blind end) the last one gives the direction.
void read_isybau_line(XmlNode object, const std::string& file, Diagnostics& d, ImportLink& link) {
  const XmlNode data = xml::descend(object, {"Geometrie", "Geometriedaten"});
  std::vector<XmlNode> points;
  append_segments(xml::child(data, "Kanten"), points);
  for (XmlNode polygon = xml::child(data, "Polygone").first_child(); polygon && points.empty();
       polygon = polygon.next_sibling()) {
    if (xml::local_name(polygon) != "Polygon") continue;
    const std::string_view kind = xml::text(xml::child(polygon, "Polygonart"));
    if (kind == "1" || kind == "2") continue;  // a ring: an outline, not the pipe's line
    append_segments(polygon, points);
    for (XmlNode p = polygon.first_child(); p; p = p.next_sibling()) {
      if (xml::local_name(p) == "Punkt") points.push_back(p);
    }
  }
  // The 2017 samples mark where the pipe proper begins at each shaft wall (RAP, Rohranfangspunkt):
  // the points before the first and after the last are the channel in the manholes' floors.
  // Lines that give a mouth begin (end) there, and the slot's direction is the pipe's axis.
  std::optional<std::size_t> first_mouth;
  std::size_t last_mouth = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (xml::text(xml::child(points[i], "PunktattributAbwasser")) != "RAP") continue;
    if (!first_mouth) first_mouth = i;
    last_mouth = i;
  }
  if (first_mouth) {
    // One RAP alone (2013 exports mark the mouth at a structure's wall) belongs to the nearer end.
    const bool at_from = last_mouth > *first_mouth || 2 * *first_mouth < points.size();
    const bool at_to = last_mouth > *first_mouth || !at_from;
    const std::size_t begin = at_from ? *first_mouth : 0;
    const std::size_t end = at_to ? last_mouth + 1 : points.size();
    points = std::vector<XmlNode>(points.begin() + static_cast<std::ptrdiff_t>(begin),
                                  points.begin() + static_cast<std::ptrdiff_t>(end));
    link.starts_at_mouth = {at_from, at_to};
  }
  const std::string what = "pipe " + link.name;
  link.vertices_include_ends = true;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::optional<double> x = xml::optional_number(points[i], "Rechtswert", what, file, d);
    const std::optional<double> y = xml::optional_number(points[i], "Hochwert", what, file, d);
    if (x && y) {
      link.vertices.push_back({*x, *y});
    } else {
      d.warning(
          file + ":" + xml::path(points[i]),
          what + ": a point of its line without Rechtswert and Hochwert: left out of the line");
    }
  }
}

std::optional<double> line_length(const ImportLink& link, const ImportNode* from,
                                  const ImportNode* to) {
  std::vector<std::array<double, 2>> points;
  if (from != nullptr && from->has_xy) points.push_back({from->position.x_m, from->position.y_m});
  points.insert(points.end(), link.vertices.begin(), link.vertices.end());
  if (to != nullptr && to->has_xy) points.push_back({to->position.x_m, to->position.y_m});
  double length = 0;
  for (std::size_t k = 1; k < points.size(); ++k) {
    length += std::hypot(points[k][0] - points[k - 1][0], points[k][1] - points[k - 1][1]);
  }
  if (!(length > 0)) return std::nullopt;
  return length;
}

}  // namespace sewerplan::detail
