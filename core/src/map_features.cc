// SPDX-License-Identifier: MIT
// GIS features to a SewerMap: manholes from points, pipes from lines, joined by the from/to fields
// or by the nearest manhole to a line's end.
#include "sewerplan/core/map_features.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "sewerplan/core/ascii_case.h"

#include "network_import.h"

namespace sewerplan {
namespace {

// A Shapefile's field names are cut to this many characters.
constexpr std::size_t kShapefileFieldChars = 10;

struct Field {
  std::size_t index = 0;
  double scale = 1;
  std::string name;
};

std::optional<Field> resolve(const GisLayer& layer, const std::vector<GisFieldCandidate>& wanted) {
  for (const GisFieldCandidate& c : wanted) {
    const std::string want = ascii_lower(c.field);
    for (std::size_t i = 0; i < layer.fields.size(); ++i) {
      if (ascii_lower(layer.fields[i]) == want)
        return Field{i, c.to_metres.value_or(layer.unit_m), layer.fields[i]};
    }
    if (want.size() <= kShapefileFieldChars) continue;
    std::optional<std::size_t> cut;
    std::size_t hits = 0;
    for (std::size_t i = 0; i < layer.fields.size(); ++i) {
      if (layer.fields[i].size() == kShapefileFieldChars &&
          want.starts_with(ascii_lower(layer.fields[i]))) {
        cut = i;
        ++hits;
      }
    }
    if (hits == 1) return Field{*cut, c.to_metres.value_or(layer.unit_m), layer.fields[*cut]};
  }
  return std::nullopt;
}

std::string tried(const std::vector<GisFieldCandidate>& wanted) {
  std::string out;
  for (const GisFieldCandidate& c : wanted) out += (out.empty() ? "" : ", ") + c.field;
  return out.empty() ? "none configured" : "tried " + out;
}

std::string number_text(double v) {
  std::ostringstream out;
  if (v == std::floor(v) && std::abs(v) < 1e15) {
    out << static_cast<long long>(v);
  } else {
    out.precision(15);
    out << v;
  }
  return out.str();
}

double distance(const std::array<double, 3>& a, double x, double y) {
  return std::hypot(a[0] - x, a[1] - y);
}

// Reads one layer's fields, reporting problems at "source:layer: feature FID".
class FeatureFields {
 public:
  FeatureFields(const GisLayer& layer, const std::string& source, Diagnostics& d)
      : layer_(layer), source_(source), d_(d) {}

  std::string where(const GisFeature& f) const {
    return source_ + ":" + layer_.name + ": feature " + std::to_string(f.fid);
  }

  // Null, an empty text or no such field: nullopt. A text that is no number: an error.
  std::optional<double> number(const GisFeature& f, const std::optional<Field>& field) {
    if (!field || field->index >= f.values.size()) return std::nullopt;
    const GisValue& v = f.values[field->index];
    if (const double* n = std::get_if<double>(&v)) {
      if (std::isfinite(*n)) return *n * field->scale;
      d_.error(where(f), "field " + field->name + ": not a finite number");
      return std::nullopt;
    }
    const std::string* t = std::get_if<std::string>(&v);
    if (t == nullptr) return std::nullopt;
    std::string_view s(*t);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    if (s.empty()) return std::nullopt;
    double n = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), n);
    if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(n)) {
      d_.error(where(f), "field " + field->name + ": '" + *t + "' is not a number");
      return std::nullopt;
    }
    return n * field->scale;
  }

  std::optional<std::string> text(const GisFeature& f, const std::optional<Field>& field) const {
    if (!field || field->index >= f.values.size()) return std::nullopt;
    const GisValue& v = f.values[field->index];
    if (const double* n = std::get_if<double>(&v)) return number_text(*n);
    const std::string* t = std::get_if<std::string>(&v);
    if (t == nullptr || t->empty()) return std::nullopt;
    return *t;
  }

  // A required field the layer lacks: one error for the layer.
  std::optional<Field> require(const std::vector<GisFieldCandidate>& wanted,
                               std::string_view what) {
    std::optional<Field> f = resolve(layer_, wanted);
    if (!f) {
      d_.error(source_ + ":" + layer_.name, "no field for the " + std::string(what) + " (" +
                                                tried(wanted) +
                                                "; name it in a field mapping file, docs/gis.md)");
    }
    return f;
  }

  Diagnostics& diagnostics() { return d_; }

 private:
  const GisLayer& layer_;
  const std::string& source_;
  Diagnostics& d_;
};

// The manholes' points in square cells of the tolerance's size: the nearest within the tolerance is
// in the 3 x 3 cells around a point.
class NearestManhole {
 public:
  NearestManhole(const std::vector<detail::ImportNode>& nodes, double tolerance_m)
      : nodes_(nodes), tolerance_m_(tolerance_m), cell_m_(std::max(tolerance_m, 1e-3)) {
    for (std::uint32_t i = 0; i < nodes.size(); ++i) {
      cells_[key(cell(nodes[i].position.x_m), cell(nodes[i].position.y_m))].push_back(i);
    }
  }

  // The nearest node within the tolerance (the first added on a tie), and the distance.
  std::optional<std::uint32_t> find(double x, double y) const {
    std::optional<std::uint32_t> best;
    double best_m = tolerance_m_;
    const std::int64_t cx = cell(x);
    const std::int64_t cy = cell(y);
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        auto it = cells_.find(key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (std::uint32_t i : it->second) {
          const double d = std::hypot(nodes_[i].position.x_m - x, nodes_[i].position.y_m - y);
          if (d < best_m || (d == best_m && (!best || i < *best))) {
            best_m = d;
            best = i;
          }
        }
      }
    }
    return best;
  }

 private:
  // Clamped to +-2^40 cells (and NaN to 0), so that a wild coordinate in a feature (found by
  // fuzz/gis_features_fuzz.cc: -6.5e307) converts without overflow; the distance test in find()
  // still decides, so far-off points sharing the edge cell change nothing.
  std::int64_t cell(double v) const {
    constexpr double kLimit = 1099511627776.0;  // 2^40
    const double c = std::floor(v / cell_m_);
    if (std::isnan(c)) return 0;
    return static_cast<std::int64_t>(std::clamp(c, -kLimit, kLimit));
  }
  static std::uint64_t key(std::int64_t x, std::int64_t y) {
    return (static_cast<std::uint64_t>(x) << 32) ^ static_cast<std::uint32_t>(y);
  }
  const std::vector<detail::ImportNode>& nodes_;
  double tolerance_m_;
  double cell_m_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

bool truthy(const GisValue& v) {
  if (const double* n = std::get_if<double>(&v)) return *n != 0;
  if (const std::string* t = std::get_if<std::string>(&v)) {
    const std::string s = ascii_lower(*t);
    return s == "1" || s == "true" || s == "t" || s == "yes" || s == "y" || s == "ja";
  }
  return false;
}

struct Counts {
  std::size_t default_diameter = 0;
  std::size_t no_level = 0;
  std::size_t reversed = 0;
};

struct Manholes {
  std::string describe_key;  // "identifier of layer manholes", for messages
  std::vector<std::string> where;
  std::unordered_map<std::string, std::uint32_t> by_key;
  std::unordered_set<std::string> rejected;  // keys of manholes left out for an error
};

// The manhole layer's fields besides the name, resolved once.
struct ManholeFields {
  ManholeFields(const GisLayer& layer, const GisFieldMapping& m)
      : id(resolve(layer, m[ManholeField::kId])),
        type(resolve(layer, m[ManholeField::kType])),
        exit(resolve(layer, m[ManholeField::kExit])),
        cover(resolve(layer, m[ManholeField::kCoverLevel])),
        invert(resolve(layer, m[ManholeField::kInvertLevel])),
        depth(resolve(layer, m[ManholeField::kDepth])),
        dim1(resolve(layer, m[ManholeField::kDimension1])),
        dim2(resolve(layer, m[ManholeField::kDimension2])),
        variant(resolve(layer, m[ManholeField::kVariant])) {
    for (const std::string& t : m.exit_types) exit_types.push_back(ascii_lower(t));
  }
  std::optional<Field> id, type, exit, cover, invert, depth, dim1, dim2, variant;
  std::vector<std::string> exit_types;  // lower case
};

// The invert (z): its field, else the cover level less the depth, else the point's z, else 0
// (counted); the depth: its field, else the cover level less the invert. A cover below the invert
// is an error.
void read_levels(FeatureFields& ff, const GisFeature& f, const ManholeFields& fields,
                 const std::string& where, detail::ImportNode& node, Counts& counts,
                 Diagnostics& d) {
  const std::optional<double> c = ff.number(f, fields.cover);
  std::optional<double> z = ff.number(f, fields.invert);
  node.depth_m = ff.number(f, fields.depth);
  if (!z && c && node.depth_m) z = *c - *node.depth_m;
  if (!z && f.has_z) z = f.points[0][2];
  if (!z) ++counts.no_level;
  node.position.z_m = z.value_or(0);
  if (!node.depth_m && c && z) node.depth_m = *c - *z;
  if (node.depth_m && *node.depth_m < 0) {
    d.error(where, "manhole " + node.name + ": its cover lies below its invert (depth " +
                       detail::metres_text(*node.depth_m) + ")");
  }
}

// The shaft: a round one's diameter, or a rectangular one's length and width (two different
// dimensions; its diameter the smaller); neither: `default_diameter_m` (counted).
void read_shaft(FeatureFields& ff, const GisFeature& f, const ManholeFields& fields,
                double default_diameter_m, const std::string& where, detail::ImportNode& node,
                Counts& counts, Diagnostics& d) {
  const std::optional<double> d1 = ff.number(f, fields.dim1);
  const std::optional<double> d2 = ff.number(f, fields.dim2);
  if ((d1 && *d1 <= 0) || (d2 && *d2 <= 0)) {
    d.error(where, "manhole " + node.name + ": field " +
                       (d1 && *d1 <= 0 ? fields.dim1->name : fields.dim2->name) +
                       ": a shaft dimension must be positive");
  }
  if (d1 && d2 && *d1 != *d2) {
    node.shaft_length_m = *d1;
    node.shaft_width_m = *d2;
  }
  node.diameter_m = d1 ? std::min(*d1, d2.value_or(*d1)) : d2.value_or(0);
  if (node.diameter_m <= 0) {
    node.diameter_m = default_diameter_m;
    ++counts.default_diameter;
  }
}

// Its exit field when the feature has a value there, else its type among the exit types; with
// neither field every manhole is an exit.
bool is_exit(FeatureFields& ff, const GisFeature& f, const ManholeFields& fields) {
  if (fields.exit && fields.exit->index < f.values.size() &&
      !std::holds_alternative<std::monostate>(f.values[fields.exit->index])) {
    return truthy(f.values[fields.exit->index]);
  }
  if (!fields.type) return true;
  const std::optional<std::string> t = ff.text(f, fields.type);
  return t && std::ranges::find(fields.exit_types, ascii_lower(*t)) != fields.exit_types.end();
}

Manholes read_manholes(const GisLayer& layer, const GisFieldMapping& m, const std::string& source,
                       detail::NetworkImport& net, Counts& counts, Diagnostics& d) {
  FeatureFields ff(layer, source, d);
  Manholes out;
  const std::optional<Field> name = ff.require(m[ManholeField::kName], "manhole name");
  if (!name) return out;
  const ManholeFields fields(layer, m);
  out.describe_key = (fields.id ? fields.id->name : name->name) + " of layer " + layer.name;
  for (const GisFeature& f : layer.features) {
    const std::string where = ff.where(f);
    std::optional<std::string> n = ff.text(f, name);
    if (!n) {
      d.error(where, "field " + name->name + ": empty: every manhole needs a name");
      continue;
    }
    const std::string key = ff.text(f, fields.id).value_or(*n);
    const std::size_t errors = d.error_count();
    if (f.geometry != GisGeometry::kPoint || f.points.empty()) {
      d.error(where, f.geometry == GisGeometry::kNone
                         ? "no geometry: a manhole is a point"
                         : "the geometry is a " + f.geometry_name + ": a manhole is a point");
      out.rejected.insert(key);
      continue;
    }
    detail::ImportNode node{.name = *n, .has_xy = true};
    node.position.x_m = f.points[0][0];
    node.position.y_m = f.points[0][1];
    read_levels(ff, f, fields, where, node, counts, d);
    read_shaft(ff, f, fields, m.default_manhole_diameter_m, where, node, counts, d);
    node.exit = is_exit(ff, f, fields);
    if (const std::optional<std::string> v = ff.text(f, fields.variant)) {
      if (v->size() == 1 && (*v)[0] >= 'A' && (*v)[0] <= 'Z') {
        node.variant = (*v)[0];
      } else {
        d.error(where, "manhole " + node.name + ": field " + fields.variant->name + ": '" + *v +
                           "' is no variant (one letter A..Z)");
      }
    }
    if (d.error_count() > errors) {
      out.rejected.insert(key);
      continue;
    }
    if (!out.by_key.emplace(key, static_cast<std::uint32_t>(net.nodes.size())).second &&
        fields.id) {  // a duplicate name is MapBuilder's to report
      d.error(where,
              "field " + fields.id->name + ": '" + key + "' is the key of an earlier manhole too");
      continue;
    }
    node.line = static_cast<std::uint32_t>(out.where.size() + 1);
    out.where.push_back(where);
    net.nodes.push_back(std::move(node));
  }
  return out;
}

double line_length(const GisFeature& f) {
  double length = 0;
  for (std::size_t i = 1; i < f.points.size(); ++i) {
    const auto& a = f.points[i - 1];
    const auto& b = f.points[i];
    length += f.has_z ? std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2])
                      : std::hypot(b[0] - a[0], b[1] - a[1]);
  }
  return length;
}

// One end of a pipe: the manhole its field names, else the nearest to the line's end point.
struct EndJoin {
  std::optional<std::uint32_t> node;
  bool failed = false;
};

// The pipe layer's fields, resolved once, and what a feature needs to become an ImportLink.
class PipeReader {
 public:
  PipeReader(const GisLayer& layer, const GisFieldMapping& m, const std::string& source,
             const Manholes& manholes, detail::NetworkImport& net, Counts& counts, Diagnostics& d)
      : m_(m),
        manholes_(manholes),
        net_(net),
        counts_(counts),
        d_(d),
        ff_(layer, source, d),
        nearest_(net.nodes, m.tolerance_m) {
    name_ = ff_.require(m[PipeField::kName], "pipe name");
    height_ = resolve(layer, m[PipeField::kHeight]);
    width_ = resolve(layer, m[PipeField::kWidth]);
    if (!height_ && !width_) {
      d.error(source + ":" + layer.name, "no field for the pipe's clear height (" +
                                             tried(m[PipeField::kHeight]) + ") or width (" +
                                             tried(m[PipeField::kWidth]) +
                                             "; name one in a field mapping file, docs/gis.md)");
    }
    from_ = resolve(layer, m[PipeField::kFrom]);
    to_ = resolve(layer, m[PipeField::kTo]);
    from_level_ = resolve(layer, m[PipeField::kFromLevel]);
    to_level_ = resolve(layer, m[PipeField::kToLevel]);
    shape_ = resolve(layer, m[PipeField::kShape]);
    length_ = resolve(layer, m[PipeField::kLength]);
    azimuth_[0] = resolve(layer, m[PipeField::kFromAzimuth]);
    azimuth_[1] = resolve(layer, m[PipeField::kToAzimuth]);
    risk_ = resolve(layer, m[PipeField::kBlockageRisk]);
    slot_[0] = resolve(layer, m[PipeField::kFromSlot]);
    slot_[1] = resolve(layer, m[PipeField::kToSlot]);
  }

  bool usable() const { return name_ && (height_ || width_); }

  // The feature's link, or nullopt with its errors reported.
  std::optional<detail::ImportLink> read(const GisFeature& f) {
    where_ = ff_.where(f);
    const bool line = f.geometry == GisGeometry::kLine && f.points.size() >= 2;
    if (f.geometry != GisGeometry::kNone && !line) {
      d_.error(where_, f.geometry == GisGeometry::kLine
                           ? "a line of fewer than two points"
                           : "the geometry is a " + f.geometry_name + ": a pipe is a line");
      return std::nullopt;
    }
    const std::optional<std::string> n = ff_.text(f, name_);
    if (!n) {
      d_.error(where_, "field " + name_->name + ": empty: every pipe needs a name");
      return std::nullopt;
    }
    const std::size_t errors = d_.error_count();
    const EndJoin a = join(f, *n, from_, true);
    const EndJoin b = join(f, *n, to_, false);
    if (a.failed || b.failed) return std::nullopt;
    if (!a.node && !b.node) {
      d_.error(where_, "pipe " + *n + ": joins no manhole at either end");
      return std::nullopt;
    }
    detail::ImportLink link{.name = *n};
    if (!size(f, link)) return std::nullopt;
    if (a.node) link.from = net_.nodes[*a.node].name;
    if (b.node) link.to = net_.nodes[*b.node].name;
    std::vector<std::array<double, 3>> points = f.points;
    if (line && a.node && b.node) {  // a line drawn against its from/to fields
      const Position& s = net_.nodes[*a.node].position;
      if (distance(points.front(), s.x_m, s.y_m) > distance(points.back(), s.x_m, s.y_m)) {
        std::ranges::reverse(points);
        ++counts_.reversed;
      }
    }
    std::optional<double> len = ff_.number(f, length_);
    if (!len && line) len = line_length(f);
    if (!len && a.node && b.node) {
      const Position& p = net_.nodes[*a.node].position;
      const Position& q = net_.nodes[*b.node].position;
      len = std::hypot(q.x_m - p.x_m, q.y_m - p.y_m);
    }
    link.length_m = len.value_or(0);
    auto invert = [&](const std::optional<Field>& field, const EndJoin& e, bool first) {
      if (std::optional<double> v = ff_.number(f, field)) return *v;
      if (line && f.has_z) return first ? points.front()[2] : points.back()[2];
      return e.node ? net_.nodes[*e.node].position.z_m : 0.0;
    };
    link.from_invert_z_m = invert(from_level_, a, true);
    link.to_invert_z_m = invert(to_level_, b, false);
    for (std::size_t i = 1; i + 1 < points.size(); ++i) {
      link.vertices.push_back({points[i][0], points[i][1]});
    }
    for (std::size_t end = 0; end < 2; ++end) {
      link.slot_index[end] = ff_.number(f, slot_[end]);
      link.azimuth_deg[end] = ff_.number(f, azimuth_[end]);
      if (link.azimuth_deg[end] &&
          (*link.azimuth_deg[end] <= -360 || *link.azimuth_deg[end] >= 360)) {
        d_.error(where_, "pipe " + *n + ": field " + azimuth_[end]->name + ": azimuth " +
                             number_text(*link.azimuth_deg[end]) +
                             " is not an angle in degrees (-360..360)");
      }
    }
    if (const std::optional<double> risk = ff_.number(f, risk_)) {
      link.blockage_risk = static_cast<float>(*risk);  // MapBuilder checks 0..1
    }
    if (d_.error_count() > errors) return std::nullopt;
    return link;
  }

  const std::string& where() const { return where_; }

 private:
  EndJoin join(const GisFeature& f, const std::string& pipe, const std::optional<Field>& field,
               bool first) {
    EndJoin e;
    if (const std::optional<std::string> key = ff_.text(f, field)) {
      auto it = manholes_.by_key.find(*key);
      if (it != manholes_.by_key.end()) {
        e.node = it->second;
      } else if (manholes_.rejected.contains(*key)) {
        e.failed = true;  // its manhole's error says why
      } else {
        d_.error(where_, "pipe " + pipe + ": field " + field->name + ": '" + *key +
                             "' names no manhole (by " + manholes_.describe_key + ")");
        e.failed = true;
      }
      return e;
    }
    if (f.geometry != GisGeometry::kLine || f.points.size() < 2) return e;
    const auto& p = first ? f.points.front() : f.points.back();
    e.node = nearest_.find(p[0], p[1]);
    if (!e.node) {
      d_.warning(where_, "pipe " + pipe + ": no manhole within " +
                             detail::metres_text(m_.tolerance_m) + " of its " +
                             (first ? "first" : "last") + " point: a blind end");
    }
    return e;
  }

  // Clear height and width (one of them may stand for both), and the shape.
  bool size(const GisFeature& f, detail::ImportLink& link) {
    std::optional<double> h = ff_.number(f, height_);
    std::optional<double> w = ff_.number(f, width_);
    if (!h && !w) {
      d_.error(where_, "pipe " + link.name + ": no clear height or width (fields " +
                           (height_ ? height_->name : "-") + ", " + (width_ ? width_->name : "-") +
                           ")");
      return false;
    }
    if (!h) h = w;
    if (!w) w = h;
    if (*h <= 0 || *w <= 0) {
      d_.error(where_, "pipe " + link.name + ": its clear height and width must be positive");
      return false;
    }
    link.height_m = *h;
    link.diameter_m = std::min(*h, *w);
    link.shape = *h == *w ? PipeShape::kCircular : PipeShape::kOther;
    if (const std::optional<std::string> s = ff_.text(f, shape_)) {
      if (std::optional<PipeShape> known = pipe_shape_from_string(ascii_lower(*s))) {
        link.shape = *known;
      } else {
        d_.warning(where_, "pipe " + link.name + ": field " + shape_->name + ": unknown shape '" +
                               *s + "' (" + pipe_shape_names() + "): read as " +
                               std::string(to_string(link.shape)));
      }
    }
    return true;
  }

  const GisFieldMapping& m_;
  const Manholes& manholes_;
  detail::NetworkImport& net_;
  Counts& counts_;
  Diagnostics& d_;
  FeatureFields ff_;
  NearestManhole nearest_;
  std::optional<Field> name_, height_, width_, from_, to_, from_level_, to_level_, shape_, length_;
  std::array<std::optional<Field>, 2> azimuth_;
  std::optional<Field> risk_;
  std::array<std::optional<Field>, 2> slot_;
  std::string where_;
};

std::vector<std::string> read_pipes(const GisLayer& layer, const GisFieldMapping& m,
                                    const std::string& source, const Manholes& manholes,
                                    detail::NetworkImport& net, Counts& counts, Diagnostics& d) {
  std::vector<std::string> wheres;
  PipeReader reader(layer, m, source, manholes, net, counts, d);
  if (!reader.usable()) return wheres;
  std::vector<detail::ImportLink> links;
  for (const GisFeature& f : layer.features) {
    std::optional<detail::ImportLink> link = reader.read(f);
    if (!link) continue;
    link->line = static_cast<std::uint32_t>(wheres.size() + 1);
    wheres.push_back(reader.where());
    links.push_back(std::move(*link));
  }
  // After the loop: the nearest-manhole index refers to net.nodes, not net.links.
  for (detail::ImportLink& l : links) net.links.push_back(std::move(l));
  return wheres;
}

// The inspection points: a name, the pipe's name and the offset from its from end, in metres.
std::vector<std::string> read_points(const GisLayer& layer, const std::string& source,
                                     detail::NetworkImport& net, Diagnostics& d) {
  std::vector<std::string> wheres;
  FeatureFields ff(layer, source, d);
  const std::optional<Field> name = ff.require({{"name", 1.0}}, "inspection point name");
  const std::optional<Field> pipe = ff.require({{"pipe", 1.0}}, "inspection point's pipe");
  const std::optional<Field> offset = ff.require({{"offset_m", 1.0}}, "inspection point's offset");
  if (!name || !pipe || !offset) return wheres;
  for (const GisFeature& f : layer.features) {
    const std::string where = ff.where(f);
    std::optional<std::string> n = ff.text(f, name);
    std::optional<std::string> p = ff.text(f, pipe);
    std::optional<double> o = ff.number(f, offset);
    if (!n || !p || !o) {
      d.error(where, "an inspection point needs a name, a pipe and an offset_m");
      continue;
    }
    wheres.push_back(where);
    net.points.push_back({.name = std::move(*n),
                          .pipe = std::move(*p),
                          .offset_m = *o,
                          .line = static_cast<std::uint32_t>(wheres.size())});
  }
  return wheres;
}

// The findings: the pipe's name, the code, its characterisation and quantities, and the offset
// from the pipe's from end, in metres.
std::vector<std::string> read_findings(const GisLayer& layer, const std::string& source,
                                       detail::NetworkImport& net, Diagnostics& d) {
  std::vector<std::string> wheres;
  FeatureFields ff(layer, source, d);
  const std::optional<Field> pipe = ff.require({{"pipe", 1.0}}, "finding's pipe");
  const std::optional<Field> code = ff.require({{"code", 1.0}}, "finding's code");
  const std::optional<Field> offset = ff.require({{"offset_m", 1.0}}, "finding's offset");
  const std::optional<Field> characterisation = resolve(layer, {{"characterisation", 1.0}});
  const std::optional<Field> q1 = resolve(layer, {{"quantity1", 1.0}});
  const std::optional<Field> q2 = resolve(layer, {{"quantity2", 1.0}});
  if (!pipe || !code || !offset) return wheres;
  for (const GisFeature& f : layer.features) {
    const std::string where = ff.where(f);
    std::optional<std::string> p = ff.text(f, pipe);
    std::optional<std::string> c = ff.text(f, code);
    std::optional<double> o = ff.number(f, offset);
    if (!p || !c || !o) {
      d.error(where, "a finding needs a pipe, a code and an offset_m");
      continue;
    }
    wheres.push_back(where);
    net.findings.push_back({.pipe = std::move(*p),
                            .code = std::move(*c),
                            .characterisation = ff.text(f, characterisation).value_or(""),
                            .station_m = *o,
                            .quantity1 = ff.number(f, q1),
                            .quantity2 = ff.number(f, q2),
                            .line = static_cast<std::uint32_t>(wheres.size())});
  }
  return wheres;
}

// The layer's points in metres: x, y and z scaled by its CRS's linear unit (GisLayer::unit_m).
GisLayer in_metres(const GisLayer& layer) {
  GisLayer out = layer;
  for (GisFeature& f : out.features) {
    for (std::array<double, 3>& p : f.points) {
      for (double& c : p) c *= layer.unit_m;
    }
  }
  return out;
}

}  // namespace

Result<SewerMap> map_from_gis_layers(const GisLayer& manholes_in, const GisLayer& pipes_in,
                                     const GisFieldMapping& mapping, const std::string& source,
                                     std::string map_name, Diagnostics& diagnostics,
                                     const GisLayer* points, const GisLayer* findings) {
  for (const GisLayer* l : {&manholes_in, &pipes_in}) {
    if (!(l->unit_m > 0) || !std::isfinite(l->unit_m)) {
      return Error{ErrorCode::kInvalidMap, source + ":" + l->name + ": the unit of its CRS (" +
                                               number_text(l->unit_m) +
                                               " m) is not a positive length"};
    }
  }
  std::optional<GisLayer> scaled_manholes, scaled_pipes;
  if (manholes_in.unit_m != 1) scaled_manholes = in_metres(manholes_in);
  if (pipes_in.unit_m != 1) scaled_pipes = in_metres(pipes_in);
  const GisLayer& manholes = scaled_manholes ? *scaled_manholes : manholes_in;
  const GisLayer& pipes = scaled_pipes ? *scaled_pipes : pipes_in;
  detail::NetworkImport net;
  net.crs = manholes.crs;
  if (manholes.crs && pipes.crs && *manholes.crs != *pipes.crs) {
    diagnostics.error(source, "layer " + manholes.name + " is in " + manholes.crs->to_string() +
                                  " but layer " + pipes.name + " in " + pipes.crs->to_string());
  }
  for (const GisLayer* l : {&manholes, &pipes}) {
    if (!l->crs && !l->unnamed_crs.empty()) {
      diagnostics.warning(source + ":" + l->name,
                          "its CRS '" + l->unnamed_crs +
                              "' has no AUTHORITY:CODE: the map has none (name it with --crs)");
    }
  }
  if (!net.crs) net.crs = pipes.crs;
  Counts counts;
  Manholes m = read_manholes(manholes, mapping, source, net, counts, diagnostics);
  std::vector<std::string> pipe_where =
      read_pipes(pipes, mapping, source, m, net, counts, diagnostics);
  std::vector<std::string> point_where;
  if (points != nullptr) point_where = read_points(*points, source, net, diagnostics);
  std::vector<std::string> finding_where;
  if (findings != nullptr) finding_where = read_findings(*findings, source, net, diagnostics);
  if (diagnostics.has_errors()) return Error{ErrorCode::kInvalidMap, diagnostics.error_summary()};
  const std::string& at = source;
  detail::warn_counted(diagnostics, at, counts.default_diameter,
                       "manholes have no size: diameter " +
                           detail::metres_text(mapping.default_manhole_diameter_m) + " assumed");
  detail::warn_counted(diagnostics, at, counts.no_level,
                       "manholes have no invert level (no field, no depth below a cover level, no "
                       "z): 0 m assumed");
  detail::warn_counted(diagnostics, at, counts.reversed,
                       "pipe lines run from their to manhole to their from manhole: read reversed");
  Locator locator = [manhole_where = std::move(m.where), pipe_where = std::move(pipe_where),
                     point_where = std::move(point_where), finding_where = std::move(finding_where),
                     source](const RecordRef& r, std::string_view) -> std::string {
    const std::vector<std::string>& w = r.kind == RecordRef::Kind::kManhole   ? manhole_where
                                        : r.kind == RecordRef::Kind::kPoint   ? point_where
                                        : r.kind == RecordRef::Kind::kFinding ? finding_where
                                                                              : pipe_where;
    const bool located = r.kind != RecordRef::Kind::kMap;
    if (located && r.line > 0 && r.line <= w.size()) return w[r.line - 1];
    return source;
  };
  return detail::assemble_network(std::move(net), std::move(map_name), std::move(locator), at,
                                  diagnostics);
}

}  // namespace sewerplan
