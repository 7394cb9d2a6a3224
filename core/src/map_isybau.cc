// SPDX-License-Identifier: MIT
// The ISYBAU XML importer: AbwassertechnischeAnlage objects -> NetworkImport (network_import.h);
// the network's CRS and the pipes' lines are isybau_geometry.h's.
#include "sewerplan/core/map_isybau.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <span>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <pugixml.hpp>

#include "sewerplan/core/crs.h"
#include "sewerplan/core/map_builder.h"

#include "ascii_syntax.h"
#include "condition_isybau.h"
#include "isybau_geometry.h"
#include "isybau_objects.h"
#include "network_import.h"
#include "xml_support.h"

namespace sewerplan {
namespace {

using detail::ImportLink;
using detail::ImportNode;
using XmlNode = pugi::xml_node;

constexpr double kMetresPerMillimetre = 1e-3;

struct Fallbacks {
  std::size_t default_diameter = 0;
  std::size_t shaft_from_unterteil = 0;
  std::size_t shaft_from_aufbau = 0;   // no Unterteil size: the rising shaft's (Aufbau)
  std::size_t size_from_height = 0;    // a profile given by its height only
  std::size_t size_from_one_side = 0;  // a non-circular profile given by one dimension
  std::size_t without_size = 0;        // no Profilbreite or Profilhoehe: left out
  std::size_t length_from_other = 0;   // DMPLaenge, Rohrlaenge
  std::size_t length_from_line = 0;    // the line's, or the nodes' distance
  std::size_t without_length = 0;      // left out
  std::size_t invert_from_node = 0;
  std::size_t without_xy = 0;
  std::size_t without_z = 0;
  std::size_t connection_points = 0;
  std::size_t other_edges = 0;       // laterals and channels
  std::size_t other_objects = 0;     // neither node nor edge
  std::size_t objects_left_out = 0;  // no name, no Knoten or Kante, a Haltung without its nodes
};

// A value written for "unknown" by the exports that have no empty element for it: all nines
// of three digits or more (999, 9999, 999.99): no real Haltung is 9999 m long, no shaft 999 m deep.
bool is_nines(std::string_view t) {
  if (t.starts_with('+')) t.remove_prefix(1);
  const std::size_t point = t.find('.');
  const std::string_view whole = t.substr(0, point);
  const std::string_view fraction =
      point == std::string_view::npos ? std::string_view() : t.substr(point + 1);
  const auto all = [](std::string_view v, std::string_view of) {
    return v.find_first_not_of(of) == std::string_view::npos;
  };
  return whole.size() >= 3 && all(whole, "9") && all(fraction, "09");
}

class IsybauReader {
 public:
  IsybauReader(const std::string& file, const IsybauImportOptions& o, Diagnostics& d)
      : file_(file), options_(o), d_(d) {}

  Result<SewerMap> run(XmlNode root) {
    const Diagnostics::Mark before = d_.mark();
    if (!check_root(root)) return Error{ErrorCode::kParse, d_.error_summary(before)};
    std::vector<XmlNode> inspected;
    const std::vector<XmlNode> objects = detail::isybau_objects(root, &inspected);
    for (XmlNode object : objects) read_object(object);
    net_.crs = detail::read_isybau_crs(root, file_, d_);
    detail::strip_utm_zone_prefix(net_, file_, d_);
    if (d_.has_errors_since(before)) return Error{ErrorCode::kParse, d_.error_summary(before)};
    resolve_pending_edges();
    read_findings(inspected);
    check_not_empty(inspected.size(), objects.size());
    if (d_.has_errors_since(before)) return Error{ErrorCode::kParse, d_.error_summary(before)};
    drop_connection_point_ends();
    report_fallbacks();
    // Records point at their elements through `line`: index + 1 into node_elements_ (manholes)
    // or link_elements_ (pipes and their slots); paths are built only for a diagnostic.
    Locator locate = [this](const RecordRef& ref, std::string_view) {
      if (ref.line == 0) return file_;
      const bool manhole = ref.kind == RecordRef::Kind::kManhole;
      const bool finding = ref.kind == RecordRef::Kind::kFinding;
      const std::vector<XmlNode>& elements = manhole   ? node_elements_
                                             : finding ? finding_elements_
                                                       : link_elements_;
      return ref.line <= elements.size() ? file_ + ":" + xml::path(elements[ref.line - 1]) : file_;
    };
    return detail::assemble_network(std::move(net_), std::filesystem::path(file_).stem().string(),
                                    std::move(locate), file_, d_);
  }

 private:
  std::string at(XmlNode n) const { return file_ + ":" + xml::path(n); }

  // The number in element `name` of `parent`, for a value with a fallback: missing or empty is
  // none (real exports write empty optional elements); not a number is a warning and none.
  std::optional<double> number(XmlNode parent, std::string_view name, const std::string& object) {
    return xml::optional_number(parent, name, object, file_, d_);
  }

  // A size, depth or length of `object` (> 0 when known): as number(), and a value that plainly
  // means "unknown" (0, a negative one, all nines: 9999) is a warning at the element and none, so
  // that the object's fallback applies instead of the network being refused.
  std::optional<double> measure(XmlNode parent, std::string_view name, const std::string& object) {
    const std::optional<double> v = number(parent, name, object);
    if (!v) return std::nullopt;
    const std::string_view t = xml::text(xml::child(parent, name));
    if (*v > 0 && !is_nines(t)) return v;
    d_.warning(at(xml::child(parent, name)),
               object + ": " + std::string(name) + " " + std::string(t) +
                   " stands for unknown (a measure must be positive): ignored");
    return std::nullopt;
  }

  struct ShaftSize {
    std::optional<double> length_m;
    std::optional<double> width_m;
  };
  ShaftSize shaft_size(XmlNode part, std::string_view length, std::string_view width,
                       const std::string& object);
  std::optional<double> shaft_measure(XmlNode part, std::string_view name,
                                      const std::string& object);

  std::optional<std::string> name(XmlNode parent, std::string_view element,
                                  const std::string& object) {
    const std::string_view t = xml::text(xml::child(parent, element));
    if (t.empty()) {
      d_.warning(at(parent), object + ": no " + std::string(element) + ": left out");
      return std::nullopt;
    }
    return std::string(t);
  }

  bool check_root(XmlNode root);
  void read_object(XmlNode object);
  void read_node(XmlNode object, XmlNode knoten, const std::string& name);
  void read_shaft(XmlNode knoten, ImportNode& node);
  void read_node_geometry(XmlNode object, ImportNode& node);
  void read_edge(XmlNode object, XmlNode kante, const std::string& name);
  bool read_profile(XmlNode kante, ImportLink& link);
  void drop_connection_point_ends();
  void resolve_pending_edges();
  void check_not_empty(std::size_t inspected, std::size_t objects);
  void read_findings(std::span<const XmlNode> inspected);
  void report_fallbacks();

  // What a Haltung left open, settled once every node is read.
  struct PendingEdge {
    std::optional<double> from_z;
    std::optional<double> to_z;
    std::optional<double> length;
  };

  const std::string& file_;
  const IsybauImportOptions& options_;
  Diagnostics& d_;
  detail::NetworkImport net_;
  std::vector<XmlNode> node_elements_;
  std::vector<XmlNode> link_elements_;
  std::vector<PendingEdge> pending_edges_;  // one per link
  std::vector<XmlNode> finding_elements_;   // one per finding
  std::unordered_set<std::string> connection_points_;
  Fallbacks fallbacks_;
};

bool IsybauReader::check_root(XmlNode root) {
  const std::string_view name = xml::local_name(root);
  if (name != "Identifikation") {
    d_.error(at(root), std::string(xml::foreign_sewer_format(root).value_or(
                           "not an ISYBAU file: the root element is <" + std::string(name) +
                           ">, not <Identifikation>")));
    return false;
  }
  const std::string_view version = xml::text(xml::child(root, "Version"));
  for (std::string_view known : {"2006", "2013", "2017"}) {
    if (version.starts_with(known)) return true;
    const std::string_view ns = root.attribute("xmlns").value();
    if (version.empty() && ns.find(known) != std::string_view::npos) return true;
  }
  d_.warning(at(root), "unknown ISYBAU version " + ascii_syntax::quoted(version) +
                           " (2006, 2013 or 2017): read as 2017");
  return true;
}

void IsybauReader::read_object(XmlNode object) {
  const std::optional<std::string> object_name = name(object, "Objektbezeichnung", "object");
  const std::string_view kind = xml::text(xml::child(object, "Objektart"));
  if (!object_name) {
    ++fallbacks_.objects_left_out;
    return;
  }
  if (kind == "2") {
    if (XmlNode knoten = xml::child(object, "Knoten"))
      return read_node(object, knoten, *object_name);
    ++fallbacks_.objects_left_out;
    d_.warning(at(object),
               "node " + *object_name + ": Objektart 2 without a Knoten element: left out");
  } else if (kind == "1") {
    if (XmlNode kante = xml::child(object, "Kante")) return read_edge(object, kante, *object_name);
    ++fallbacks_.objects_left_out;
    d_.warning(at(object),
               "edge " + *object_name + ": Objektart 1 without a Kante element: left out");
  } else {
    ++fallbacks_.other_objects;
  }
}

void IsybauReader::read_node(XmlNode object, XmlNode knoten, const std::string& name) {
  const std::string_view type = xml::text(xml::child(knoten, "KnotenTyp"));
  if (type == "1") {  // Anschlusspunkt: no room to turn; pipes end blind there
    ++fallbacks_.connection_points;
    connection_points_.insert(name);
    return;
  }
  if (type != "0" && type != "2") {
    // Pipes name the node: it stays, as a structure that need not have a usable cover.
    d_.warning(at(xml::child(knoten, "KnotenTyp") ? xml::child(knoten, "KnotenTyp") : knoten),
               "node " + name +
                   ": KnotenTyp should be 0 (Schacht), 1 (Anschlusspunkt) or 2 (Bauwerk), got " +
                   ascii_syntax::quoted(type) + ": read as a Bauwerk (not an exit)");
  }
  ImportNode node{.name = name,
                  .diameter_m = options_.manhole_diameter_m,
                  .exit = type == "0",  // a manhole has a cover; a structure may not
                  .line = static_cast<std::uint32_t>(node_elements_.size() + 1)};
  read_shaft(knoten, node);
  read_node_geometry(object, node);
  node_elements_.push_back(object);
  net_.nodes.push_back(std::move(node));
}

// A shaft size (metres in every ISYBAU version). A value of 100 or more, which the schema does not
// allow (decimal, under 100), is millimetres written into the metre field: read as such, with a
// warning at the element, rather than as a shaft 1 km wide.
std::optional<double> IsybauReader::shaft_measure(XmlNode part, std::string_view name,
                                                  const std::string& object) {
  const std::optional<double> v = measure(part, name, object);
  if (!v || *v < 100) return v;
  const double metres = *v * kMetresPerMillimetre;
  if (metres >= 100) {
    d_.warning(at(xml::child(part, name)),
               object + ": " + std::string(name) + " " +
                   std::string(xml::text(xml::child(part, name))) +
                   " is no shaft size, in metres or millimetres: ignored");
    return std::nullopt;
  }
  d_.warning(at(xml::child(part, name)),
             object + ": " + std::string(name) + " " +
                 std::string(xml::text(xml::child(part, name))) +
                 " is not in metres (ISYBAU gives shaft sizes in metres, under 100): read as "
                 "millimetres, " +
                 detail::metres_text(metres));
  return metres;
}

IsybauReader::ShaftSize IsybauReader::shaft_size(XmlNode part, std::string_view length,
                                                 std::string_view width,
                                                 const std::string& object) {
  return {.length_m = shaft_measure(part, length, object),
          .width_m = shaft_measure(part, width, object)};
}

// The shaft's floor plan, in metres in every ISYBAU version (2013 and 2017 only add to 2006):
// Schacht/Unterteil LaengeUnterteil, BreiteUnterteil (the floor where pipes meet; a round shaft
// gives its diameter as the Laenge). Without them, Schacht/Aufbau LaengeAufbau, BreiteAufbau: the
// rising shaft of rings between the cover and the floor, which real exports often give alone; a
// standard manhole's rings and floor share their nominal size (DIN 4034-1), and where they
// differ the floor is the wider, so the rising shaft's size never overstates the room to turn.
// Schachttiefe (metres) is the depth.
void IsybauReader::read_shaft(XmlNode knoten, ImportNode& node) {
  const std::string what = "node " + node.name;
  const XmlNode schacht = xml::child(knoten, "Schacht");
  node.depth_m = measure(schacht, "Schachttiefe", what);
  ShaftSize size =
      shaft_size(xml::child(schacht, "Unterteil"), "LaengeUnterteil", "BreiteUnterteil", what);
  if (!size.length_m && !size.width_m) {
    size = shaft_size(xml::child(schacht, "Aufbau"), "LaengeAufbau", "BreiteAufbau", what);
    if (size.length_m || size.width_m) ++fallbacks_.shaft_from_aufbau;
  }
  if (!size.length_m && !size.width_m) {
    ++fallbacks_.default_diameter;
    return;
  }
  ++fallbacks_.shaft_from_unterteil;
  const double length = size.length_m.value_or(*size.width_m);
  const double width = size.width_m.value_or(length);
  node.diameter_m = std::min(length, width);
  if (width != length) {
    node.shaft_length_m = length;
    node.shaft_width_m = width;
  }
}

// Position from the node's first Punkt; the floor's height from its SMP point (Sohle), else its
// cover (DMP, or the first point) less the Schachttiefe.
void IsybauReader::read_node_geometry(XmlNode object, ImportNode& node) {
  const XmlNode points = xml::descend(object, {"Geometrie", "Geometriedaten", "Knoten"});
  const std::string what = "node " + node.name;
  const XmlNode first = detail::isybau_position_point(object);  // the corrected copy's too
  XmlNode floor;
  XmlNode cover;
  for (XmlNode p = points.first_child(); p; p = p.next_sibling()) {
    if (xml::local_name(p) != "Punkt") continue;
    const std::string_view attribute = xml::text(xml::child(p, "PunktattributAbwasser"));
    if (attribute == "SMP" && !floor) floor = p;
    if (attribute == "DMP" && !cover) cover = p;
  }
  if (!first) {
    ++fallbacks_.without_xy;
    ++fallbacks_.without_z;
    return;
  }
  const std::optional<double> x = number(first, "Rechtswert", what);
  const std::optional<double> y = number(first, "Hochwert", what);
  node.has_xy = x && y;
  if (!node.has_xy) ++fallbacks_.without_xy;
  node.position.x_m = node.has_xy ? *x : 0;
  node.position.y_m = node.has_xy ? *y : 0;
  const std::optional<double> depth = node.depth_m;
  if (const std::optional<double> bottom =
          floor ? number(floor, "Punkthoehe", what) : std::nullopt) {
    node.position.z_m = *bottom;
  } else if (const std::optional<double> top = number(cover ? cover : first, "Punkthoehe", what);
             top && depth) {
    node.position.z_m = *top - *depth;
  } else {
    ++fallbacks_.without_z;
  }
}

void IsybauReader::read_edge(XmlNode object, XmlNode kante, const std::string& name) {
  if (xml::text(xml::child(kante, "KantenTyp")) != "0") {  // Leitung, Rinne: not drivable
    ++fallbacks_.other_edges;
    return;
  }
  const std::string what = "pipe " + name;
  ImportLink link{.name = name, .line = static_cast<std::uint32_t>(link_elements_.size() + 1)};
  const std::size_t errors_before = d_.error_count();
  link.from = this->name(kante, "KnotenZulauf", what);
  link.to = this->name(kante, "KnotenAblauf", what);
  if (!link.from || !link.to) {  // where it leads is unknown: the robot must not enter it
    ++fallbacks_.objects_left_out;
    return;
  }
  PendingEdge pending{.from_z = number(kante, "SohlhoeheZulauf", what),
                      .to_z = number(kante, "SohlhoeheAblauf", what),
                      .length = measure(kante, "Laenge", what)};
  for (std::string_view other : {"Rohrlaenge", "DMPLaenge"}) {
    if (pending.length) break;
    if (const XmlNode n = detail::find_below(kante, other)) {
      pending.length = measure(n.parent(), other, what);
      if (pending.length) ++fallbacks_.length_from_other;
    }
  }
  const bool sized = read_profile(kante, link);
  if (d_.error_count() > errors_before) return;
  if (!sized) {
    ++fallbacks_.without_size;
    return;
  }
  detail::read_isybau_line(object, file_, d_, link);
  link_elements_.push_back(object);
  net_.links.push_back(std::move(link));
  pending_edges_.push_back(pending);
}

// Profilart 0 Kreis (circular), 1 and 6 Ei (egg), 3 and 5 Rechteck (rectangular), others kOther;
// Profilbreite and Profilhoehe in millimetres, both optional in the schema: a circle given by one
// of them, an egg by one (the standard 2:3), another shape by one (taken for both). False if the
// profile gives no size at all (the pipe is left out).
bool IsybauReader::read_profile(XmlNode kante, ImportLink& link) {
  const std::string what = "pipe " + link.name;
  const XmlNode profil = xml::child(kante, "Profil");
  const std::string_view kind = xml::text(xml::child(profil, "Profilart"));
  link.shape = kind.empty() || kind == "0"  ? PipeShape::kCircular
               : kind == "1" || kind == "6" ? PipeShape::kEgg
               : kind == "3" || kind == "5" ? PipeShape::kRectangular
                                            : PipeShape::kOther;
  // Real exports write 0 for a size nobody measured (special profiles, tanks): not a size.
  std::optional<double> width = measure(profil, "Profilbreite", what);
  std::optional<double> height = measure(profil, "Profilhoehe", what);
  if (!width && !height) return false;
  if (!width || !height) {
    const double given = width ? *width : *height;
    const bool egg = link.shape == PipeShape::kEgg;
    if (link.shape == PipeShape::kCircular) {
      if (!width) ++fallbacks_.size_from_height;
    } else {
      ++fallbacks_.size_from_one_side;
    }
    if (!width) width = egg ? given * 2 / 3 : given;
    if (!height) height = egg ? given * 3 / 2 : given;
  }
  link.height_m = *height * kMetresPerMillimetre;
  link.diameter_m = std::min(*width * kMetresPerMillimetre, link.height_m);
  return true;
}

// Inverts from the nodes' floors, lengths from the line (or the nodes' distance); a Haltung with
// no length at all is left out.
void IsybauReader::resolve_pending_edges() {
  std::unordered_map<std::string_view, const ImportNode*> nodes;
  for (const ImportNode& n : net_.nodes) nodes.emplace(n.name, &n);
  auto node = [&](const std::optional<std::string>& name) -> const ImportNode* {
    if (!name) return nullptr;
    auto it = nodes.find(*name);
    return it == nodes.end() ? nullptr : it->second;
  };
  std::vector<ImportLink> kept;
  std::vector<XmlNode> kept_elements;
  for (std::size_t i = 0; i < net_.links.size(); ++i) {
    ImportLink& link = net_.links[i];
    const PendingEdge& pending = pending_edges_[i];
    const ImportNode* from = node(link.from);
    const ImportNode* to = node(link.to);
    std::optional<double> length = pending.length;
    if (!length) length = detail::line_length(link, from, to);
    if (!length) {
      ++fallbacks_.without_length;
      continue;
    }
    if (!pending.length) ++fallbacks_.length_from_line;
    link.length_m = *length;
    auto invert = [&](const std::optional<double>& given, const ImportNode* at,
                      const ImportNode* other) {
      if (given) return *given;
      ++fallbacks_.invert_from_node;
      return at != nullptr ? at->position.z_m : other != nullptr ? other->position.z_m : 0.0;
    };
    link.from_invert_z_m = invert(pending.from_z, from, to);
    link.to_invert_z_m = invert(pending.to_z, to, from);
    link.line = static_cast<std::uint32_t>(kept.size() + 1);
    kept.push_back(std::move(link));
    kept_elements.push_back(link_elements_[i]);
  }
  net_.links = std::move(kept);
  link_elements_ = std::move(kept_elements);
}

// The Zustandsdaten in the map's own file, placed along the Haltungen as read.
void IsybauReader::read_findings(std::span<const XmlNode> inspected) {
  std::unordered_map<std::string_view, double> lengths;
  for (const ImportLink& link : net_.links) lengths.emplace(link.name, link.length_m);
  const detail::PipeLength pipe_length = [&](const std::string& name) -> std::optional<double> {
    auto it = lengths.find(name);
    return it == lengths.end() ? std::nullopt : std::optional(it->second);
  };
  detail::read_condition_records(inspected, file_, d_, pipe_length, net_.findings,
                                 finding_elements_);
}

// A file without a single Haltung holds no sewer: an error that says what the file holds instead.
void IsybauReader::check_not_empty(std::size_t inspected, std::size_t objects) {
  if (!net_.links.empty()) return;
  const std::size_t left_out = fallbacks_.without_size + fallbacks_.without_length;
  std::string why;
  if (objects == 0 && inspected > 0) {
    why = "a Zustandsdaten file (" + std::to_string(inspected) +
          " inspected objects) without Stammdaten: no network to read; give it with "
          "--condition beside the map it belongs to";
  } else if (objects == 0) {
    why = "no AbwassertechnischeAnlage at all";
  } else {
    why = std::to_string(net_.nodes.size()) + " manholes or structures, " +
          std::to_string(fallbacks_.other_edges) + " laterals or channels, " +
          std::to_string(left_out) + " Haltungen without a size or length, but no Haltung to drive";
  }
  d_.error(file_, "no sewer network in this file: " + why);
}

void IsybauReader::drop_connection_point_ends() {
  for (ImportLink& link : net_.links) {
    if (link.from && connection_points_.contains(*link.from)) link.from.reset();
    if (link.to && connection_points_.contains(*link.to)) link.to.reset();
  }
}

void IsybauReader::report_fallbacks() {
  const Fallbacks& f = fallbacks_;
  auto warn = [&](std::size_t n, const std::string& what) {
    detail::warn_counted(d_, file_, n, what);
  };
  const std::string diameter = detail::metres_text(options_.manhole_diameter_m);
  warn(f.default_diameter,
       "manholes have no shaft size (Schacht/Unterteil LaengeUnterteil, BreiteUnterteil, or "
       "Schacht/Aufbau LaengeAufbau, BreiteAufbau): diameter " +
           diameter + " assumed");
  warn(f.shaft_from_aufbau,
       "manholes give no floor size (Unterteil), only the rising shaft's (Aufbau LaengeAufbau, "
       "BreiteAufbau): taken for the floor's");
  warn(f.size_from_height, "circular profiles are given by their height only (Profilhoehe)");
  warn(f.size_from_one_side,
       "non-circular profiles are given by one dimension only: an egg's other one from the "
       "standard 2:3, another shape's taken equal");
  warn(f.without_size,
       "Haltungen have no profile size (Profilbreite, Profilhoehe missing or 0): left out");
  warn(f.length_from_other, "Haltungen have no Laenge: their Rohrlaenge or DMPLaenge is used");
  warn(f.length_from_line,
       "Haltungen have no Laenge, Rohrlaenge or DMPLaenge: the length of their line (or of the "
       "straight line between their nodes) is used");
  warn(f.without_length, "Haltungen have no length and no line to measure: left out");
  warn(f.invert_from_node,
       "pipe ends have no invert (SohlhoeheZulauf, SohlhoeheAblauf): the node's floor is used");
  warn(f.without_xy, "nodes have no point geometry: placed at x = y = 0");
  warn(f.without_z,
       "nodes have neither an SMP point nor a cover height and Schachttiefe: floor "
       "at z = 0");
  warn(f.connection_points,
       "connection points (Anschlusspunkt) are not manholes: pipes end blind there");
  warn(f.other_edges, "laterals or channels (KantenTyp 1, 2) are not drivable: left out");
  warn(f.other_objects, "objects are neither nodes nor edges (Objektart 1, 2): ignored");
  warn(f.objects_left_out,
       "objects are left out for what they lack (a name, their Knoten or Kante, a Haltung's "
       "nodes): each is named in a warning above");
}

}  // namespace

Result<SewerMap> read_map_isybau(std::string_view text, const std::string& file_name,
                                 Diagnostics& diagnostics, const IsybauImportOptions& options) {
  if (!std::isfinite(options.manhole_diameter_m) || options.manhole_diameter_m <= 0) {
    return Error{ErrorCode::kInvalidArgument, "ISYBAU import: manhole diameter must be positive"};
  }
  const Diagnostics::Mark before = diagnostics.mark();
  pugi::xml_document doc;
  if (!xml::load_utf8(doc, text, file_name, diagnostics))
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  return IsybauReader(file_name, options, diagnostics).run(doc.document_element());
}

}  // namespace sewerplan
