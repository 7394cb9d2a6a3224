// SPDX-License-Identifier: MIT
// The ISYBAU XML importer: AbwassertechnischeAnlage objects -> NetworkImport (network_import.h).
#include "sewerplan/core/map_isybau.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <unordered_set>
#include <vector>

#include <pugixml.hpp>

#include "sewerplan/core/map_builder.h"

#include "ascii_syntax.h"
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
  std::size_t without_xy = 0;
  std::size_t without_z = 0;
  std::size_t connection_points = 0;
  std::size_t other_edges = 0;    // laterals and channels
  std::size_t other_objects = 0;  // neither node nor edge
};

// Every AbwassertechnischeAnlage of the document, in document order.
std::vector<XmlNode> objects_of(XmlNode root) {
  std::vector<XmlNode> objects;
  std::vector<XmlNode> stack{root};
  while (!stack.empty()) {
    const XmlNode n = stack.back();
    stack.pop_back();
    if (xml::local_name(n) == "AbwassertechnischeAnlage") {
      objects.push_back(n);
      continue;
    }
    std::vector<XmlNode> children;
    for (XmlNode c = n.first_child(); c; c = c.next_sibling()) {
      if (c.type() == pugi::node_element) children.push_back(c);
    }
    stack.insert(stack.end(), children.rbegin(), children.rend());
  }
  return objects;
}

class IsybauReader {
 public:
  IsybauReader(const std::string& file, const IsybauImportOptions& o, Diagnostics& d)
      : file_(file), options_(o), d_(d) {}

  Result<SewerMap> run(XmlNode root) {
    const std::size_t errors_before = d_.error_count();
    check_root(root);
    for (XmlNode object : objects_of(root)) read_object(object);
    if (d_.error_count() > errors_before) return Error{ErrorCode::kParse, d_.error_summary()};
    drop_connection_point_ends();
    report_fallbacks();
    // Records point at their elements through `line`: index + 1 into node_elements_ (manholes)
    // or link_elements_ (pipes and their slots); paths are built only for a diagnostic.
    Locator locate = [this](const RecordRef& ref, std::string_view) {
      if (ref.line == 0) return file_;
      const bool manhole = ref.kind == RecordRef::Kind::kManhole;
      const std::vector<XmlNode>& elements = manhole ? node_elements_ : link_elements_;
      return ref.line <= elements.size() ? file_ + ":" + xml::path(elements[ref.line - 1]) : file_;
    };
    return detail::assemble_network(std::move(net_), std::filesystem::path(file_).stem().string(),
                                    std::move(locate), file_, d_);
  }

 private:
  std::string at(XmlNode n) const { return file_ + ":" + xml::path(n); }

  // The number in element `name` of `parent`; an error naming the element if it is missing
  // (when required) or not a number.
  std::optional<double> number(XmlNode parent, std::string_view name, const std::string& object,
                               bool required = true) {
    const XmlNode n = xml::child(parent, name);
    if (!n) {
      if (required) d_.error(at(parent), object + ": no " + std::string(name));
      return std::nullopt;
    }
    double v = 0;
    const std::string_view t = xml::text(n);
    if (ascii_syntax::parse_number(t, v) != ascii_syntax::NumberError::kNone) {
      d_.error(at(n),
               object + ": " + std::string(name) + " is not a number: " + ascii_syntax::quoted(t));
      return std::nullopt;
    }
    return v;
  }

  std::optional<std::string> name(XmlNode parent, std::string_view element,
                                  const std::string& object) {
    const std::string_view t = xml::text(xml::child(parent, element));
    if (t.empty()) {
      d_.error(at(parent), object + ": no " + std::string(element));
      return std::nullopt;
    }
    return std::string(t);
  }

  void check_root(XmlNode root);
  void read_object(XmlNode object);
  void read_node(XmlNode object, XmlNode knoten, const std::string& name);
  void read_node_geometry(XmlNode object, XmlNode knoten, ImportNode& node);
  void read_edge(XmlNode object, XmlNode kante, const std::string& name);
  bool read_profile(XmlNode kante, ImportLink& link);
  void read_edge_geometry(XmlNode object, ImportLink& link);
  void drop_connection_point_ends();
  void report_fallbacks();

  const std::string& file_;
  const IsybauImportOptions& options_;
  Diagnostics& d_;
  detail::NetworkImport net_;
  std::vector<XmlNode> node_elements_;
  std::vector<XmlNode> link_elements_;
  std::unordered_set<std::string> connection_points_;
  Fallbacks fallbacks_;
};

void IsybauReader::check_root(XmlNode root) {
  if (xml::local_name(root) != "Identifikation") {
    d_.error(at(root), "not an ISYBAU file: the root element is <" +
                           std::string(xml::local_name(root)) + ">, not <Identifikation>");
    return;
  }
  const std::string_view version = xml::text(xml::child(root, "Version"));
  for (std::string_view known : {"2006", "2013", "2017"}) {
    if (version.starts_with(known)) return;
    const std::string_view ns = root.attribute("xmlns").value();
    if (version.empty() && ns.find(known) != std::string_view::npos) return;
  }
  d_.warning(at(root), "unknown ISYBAU version " + ascii_syntax::quoted(version) +
                           " (2006, 2013 or 2017): read as 2017");
}

void IsybauReader::read_object(XmlNode object) {
  const std::optional<std::string> object_name = name(object, "Objektbezeichnung", "object");
  const std::string_view kind = xml::text(xml::child(object, "Objektart"));
  if (!object_name) return;
  if (kind == "2") {
    if (XmlNode knoten = xml::child(object, "Knoten"))
      return read_node(object, knoten, *object_name);
    d_.error(at(object), "node " + *object_name + ": Objektart 2 without a Knoten element");
  } else if (kind == "1") {
    if (XmlNode kante = xml::child(object, "Kante")) return read_edge(object, kante, *object_name);
    d_.error(at(object), "edge " + *object_name + ": Objektart 1 without a Kante element");
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
    d_.error(at(xml::child(knoten, "KnotenTyp") ? xml::child(knoten, "KnotenTyp") : knoten),
             "node " + name +
                 ": KnotenTyp must be 0 (Schacht), 1 (Anschlusspunkt) or 2 "
                 "(Bauwerk), got " +
                 ascii_syntax::quoted(type));
    return;
  }
  ImportNode node{.name = name,
                  .diameter_m = options_.manhole_diameter_m,
                  .exit = type == "0",  // a manhole has a cover; a structure may not
                  .line = static_cast<std::uint32_t>(node_elements_.size() + 1)};
  ++fallbacks_.default_diameter;
  read_node_geometry(object, knoten, node);
  node_elements_.push_back(object);
  net_.nodes.push_back(std::move(node));
}

// Position from the node's first Punkt; the floor's height from its SMP point (Sohle), else its
// cover (DMP, or the first point) less the Schachttiefe.
void IsybauReader::read_node_geometry(XmlNode object, XmlNode knoten, ImportNode& node) {
  const XmlNode points = xml::descend(object, {"Geometrie", "Geometriedaten", "Knoten"});
  const std::string what = "node " + node.name;
  XmlNode first;
  XmlNode floor;
  XmlNode cover;
  for (XmlNode p = points.first_child(); p; p = p.next_sibling()) {
    if (xml::local_name(p) != "Punkt") continue;
    if (!first) first = p;
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
  node.position.x_m = x.value_or(0);
  node.position.y_m = y.value_or(0);
  const std::optional<double> depth =
      number(xml::child(knoten, "Schacht"), "Schachttiefe", what, false);
  if (floor) {
    node.position.z_m = number(floor, "Punkthoehe", what).value_or(0);
  } else if (const std::optional<double> top =
                 number(cover ? cover : first, "Punkthoehe", what, false);
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
  link.from = this->name(kante, "KnotenZulauf", what);
  link.to = this->name(kante, "KnotenAblauf", what);
  const std::optional<double> from_z = number(kante, "SohlhoeheZulauf", what);
  const std::optional<double> to_z = number(kante, "SohlhoeheAblauf", what);
  const std::optional<double> length = number(kante, "Laenge", what);
  if (!read_profile(kante, link) || !link.from || !link.to || !from_z || !to_z || !length) return;
  link.from_invert_z_m = *from_z;
  link.to_invert_z_m = *to_z;
  link.length_m = *length;
  read_edge_geometry(object, link);
  link_elements_.push_back(object);
  net_.links.push_back(std::move(link));
}

// Profilart 0 Kreis (circular), 1 Ei (egg), 3 Rechteck (rectangular), others kOther; Profilbreite
// and Profilhoehe in millimetres (the height defaults to the width).
bool IsybauReader::read_profile(XmlNode kante, ImportLink& link) {
  const std::string what = "pipe " + link.name;
  const XmlNode profil = xml::child(kante, "Profil");
  if (!profil) {
    d_.error(at(kante), what + ": no Profil");
    return false;
  }
  const std::string_view kind = xml::text(xml::child(profil, "Profilart"));
  link.shape = kind.empty() || kind == "0" ? PipeShape::kCircular
               : kind == "1"               ? PipeShape::kEgg
               : kind == "3"               ? PipeShape::kRectangular
                                           : PipeShape::kOther;
  const std::optional<double> width = number(profil, "Profilbreite", what);
  const std::optional<double> height = number(profil, "Profilhoehe", what, false);
  if (!width) return false;
  link.height_m = height.value_or(*width) * kMetresPerMillimetre;
  link.diameter_m = std::min(*width * kMetresPerMillimetre, link.height_m);
  return true;
}

// The pipe's line: 2013 and 2017 store segments (Kanten/Kante with Start and Ende), 2006 a
// Polygon of Punkte. All its points are the link's vertices: those at a node are skipped when
// taking directions, and at a connection point (a blind end) the last one gives the direction.
void IsybauReader::read_edge_geometry(XmlNode object, ImportLink& link) {
  const XmlNode data = xml::descend(object, {"Geometrie", "Geometriedaten"});
  std::vector<XmlNode> points;
  for (XmlNode k = xml::child(data, "Kanten").first_child(); k; k = k.next_sibling()) {
    if (xml::local_name(k) != "Kante") continue;
    if (points.empty()) points.push_back(xml::child(k, "Start"));
    points.push_back(xml::child(k, "Ende"));
  }
  const XmlNode polygon = xml::descend(data, {"Polygone", "Polygon"});
  for (XmlNode p = polygon.first_child(); p; p = p.next_sibling()) {
    if (xml::local_name(p) == "Punkt") points.push_back(p);
  }
  const std::string what = "pipe " + link.name;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::optional<double> x = number(points[i], "Rechtswert", what);
    const std::optional<double> y = number(points[i], "Hochwert", what);
    if (x && y) link.vertices.push_back({*x, *y});
  }
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
  warn(f.default_diameter, "manholes: shaft size not read, diameter " + diameter + " assumed");
  warn(f.without_xy, "nodes have no point geometry: placed at x = y = 0");
  warn(f.without_z,
       "nodes have neither an SMP point nor a cover height and Schachttiefe: floor "
       "at z = 0");
  warn(f.connection_points,
       "connection points (Anschlusspunkt) are not manholes: pipes end blind there");
  warn(f.other_edges, "laterals or channels (KantenTyp 1, 2) are not drivable: left out");
  warn(f.other_objects, "objects are neither nodes nor edges (Objektart 1, 2): ignored");
}

}  // namespace

Result<SewerMap> read_map_isybau(std::string_view text, const std::string& file_name,
                                 Diagnostics& diagnostics, const IsybauImportOptions& options) {
  if (!std::isfinite(options.manhole_diameter_m) || options.manhole_diameter_m <= 0) {
    return Error{ErrorCode::kInvalidArgument, "ISYBAU import: manhole diameter must be positive"};
  }
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_buffer(text.data(), text.size());
  if (!parsed) {
    diagnostics.error(file_name + ":" + std::to_string(xml::line_of_offset(text, parsed.offset)),
                      std::string("XML is not well-formed: ") + parsed.description());
    return Error{ErrorCode::kParse, diagnostics.error_summary()};
  }
  return IsybauReader(file_name, options, diagnostics).run(doc.document_element());
}

}  // namespace sewerplan
