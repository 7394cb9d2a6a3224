// SPDX-License-Identifier: MIT
// The field mapping of GIS sewer layers: its defaults, its JSON file, and the choice of the layers.
#include <algorithm>
#include <initializer_list>
#include <optional>
#include <string>
#include <utility>

#include "sewerplan/core/ascii_case.h"
#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/map_features.h"
#include "sewerplan/core/text_file.h"

namespace sewerplan {
namespace {

constexpr double kMm = 0.001;
constexpr std::optional<double> kCrsUnit = std::nullopt;

constexpr std::array<std::string_view, kManholeFieldCount> kManholeKeys = {
    "id",           "name",  "type",       "exit",       "cover_level",
    "invert_level", "depth", "dimension1", "dimension2", "variant"};
constexpr std::array<std::string_view, kPipeFieldCount> kPipeKeys = {
    "name",  "from",   "to",           "from_level", "to_level",      "height",    "width",
    "shape", "length", "from_azimuth", "to_azimuth", "blockage_risk", "from_slot", "to_slot"};

// Sizes (shaft dimensions, pipe profiles) are in millimetres in a mapping file unless it says so;
// azimuths in degrees; levels, depths and lengths in the unit of the layers' CRS (metres when
// they have none).
bool is_size(std::string_view key) {
  return key == "dimension1" || key == "dimension2" || key == "height" || key == "width";
}
bool is_angle(std::string_view key) { return key == "from_azimuth" || key == "to_azimuth"; }
bool is_measure(std::string_view key) {
  return key == "cover_level" || key == "invert_level" || key == "depth" || key == "from_level" ||
         key == "to_level" || key == "length" || is_size(key);
}

std::vector<GisFieldCandidate> names(std::initializer_list<const char*> fields,
                                     std::optional<double> scale = 1.0) {
  std::vector<GisFieldCandidate> out;
  for (const char* f : fields) out.push_back({f, scale});
  return out;
}

// One field of the mapping file: "name", {"field": "name", "unit": "mm"}, or null.
std::optional<std::vector<GisFieldCandidate>> read_field(JsonFields& f, std::string_view key,
                                                         std::string_view file) {
  std::optional<JsonElement> e = f.member(key, JsonFields::Need::kOptional);
  if (!e) return std::nullopt;
  if (e->is_null()) return std::vector<GisFieldCandidate>{};
  const std::optional<double> unit = is_size(key)      ? std::optional(kMm)
                                     : is_measure(key) ? kCrsUnit
                                                       : std::optional(1.0);
  if (e->is_string())
    return std::vector<GisFieldCandidate>{{std::string(e->get_string().value()), unit}};
  JsonFields spec(*e, f.path() + "." + std::string(key), file, f.diagnostics());
  std::optional<std::string> field = spec.string("field");
  std::optional<std::string> unit_name = spec.string("unit", JsonFields::Need::kOptional);
  spec.warn_unknown({"field", "unit"});
  if (!field) return std::nullopt;
  std::optional<double> scale = unit;
  if (unit_name) {
    if (is_angle(key)) {
      if (*unit_name != "deg") {
        f.diagnostics().error(
            spec.where("unit"),
            "field " + std::string(key) + ": an azimuth's unit is deg, not '" + *unit_name + "'");
        return std::nullopt;
      }
    } else if (!is_measure(key)) {
      f.diagnostics().error(spec.where("unit"),
                            "field " + std::string(key) + " is not a measure: it takes no unit");
      return std::nullopt;
    } else if (std::optional<double> metres = gis_unit_to_metres(*unit_name)) {
      scale = metres;
    } else {
      f.diagnostics().error(spec.where("unit"), "field " + std::string(key) + ": unknown unit '" +
                                                    *unit_name +
                                                    "' (mm, cm, m, inch, foot or us_survey_foot)");
      return std::nullopt;
    }
  }
  return std::vector<GisFieldCandidate>{{*field, scale}};
}

template <std::size_t N>
void read_layer(JsonFields& f, std::string_view file, std::string& layer,
                std::array<std::vector<GisFieldCandidate>, N>& fields,
                const std::array<std::string_view, N>& keys) {
  if (auto name = f.string("layer", JsonFields::Need::kOptional)) layer = *name;
  for (std::size_t i = 0; i < N; ++i) {
    if (auto read = read_field(f, keys[i], file)) fields[i] = std::move(*read);
  }
}

// A well-known layer name: QGEP/TEKSI's views, then common names (lower case).
bool well_known(std::string_view name, GisGeometry geometry) {
  static const std::vector<std::string_view> kManholes = {"vw_qgep_wastewater_structure",
                                                          "vw_tww_wastewater_structure",
                                                          "manholes",
                                                          "manhole",
                                                          "schacht",
                                                          "schaechte",
                                                          "nodes",
                                                          "junctions"};
  static const std::vector<std::string_view> kPipes = {"vw_qgep_reach", "vw_tww_reach", "pipes",
                                                       "pipe",          "reaches",      "haltung",
                                                       "haltungen",     "conduits",     "links"};
  const std::string n = ascii_lower(name);
  const auto& known = geometry == GisGeometry::kPoint ? kManholes : kPipes;
  return std::ranges::find(known, n) != known.end();
}

std::string describe(const GisLayerInfo& l) {
  switch (l.geometry) {
    case GisGeometry::kPoint:
      return l.name + " (points)";
    case GisGeometry::kLine:
      return l.name + " (lines)";
    case GisGeometry::kNone:
      return l.name + " (no geometry)";
    case GisGeometry::kOther:
      break;
  }
  return l.name + " (other or mixed geometry)";
}

std::string list(const std::vector<GisLayerInfo>& layers) {
  std::string out;
  for (const GisLayerInfo& l : layers) out += (out.empty() ? "" : ", ") + describe(l);
  return out.empty() ? "no layers" : out;
}

Result<std::size_t> choose(const std::vector<GisLayerInfo>& layers, GisGeometry geometry,
                           const std::string& named, const std::string& source,
                           std::string_view preferred) {
  const std::string what = geometry == GisGeometry::kPoint ? "manholes" : "pipes";
  const std::string kind = geometry == GisGeometry::kPoint ? "point" : "line";
  std::optional<std::size_t> chosen;
  if (!named.empty()) {
    for (std::size_t i = 0; i < layers.size(); ++i) {
      if (ascii_lower(layers[i].name) == ascii_lower(named)) chosen = i;
    }
    if (!chosen) {
      return Error{ErrorCode::kInvalidMap, source + ": no layer '" + named + "' (the " + what +
                                               "' layer of the field mapping); the source has " +
                                               list(layers)};
    }
  } else {
    std::vector<std::size_t> fit;
    for (std::size_t i = 0; i < layers.size(); ++i) {
      if (layers[i].geometry == geometry) fit.push_back(i);
    }
    auto pick = [&](auto&& pred) -> std::optional<std::size_t> {
      std::vector<std::size_t> hits;
      for (std::size_t i : fit) {
        if (pred(layers[i])) hits.push_back(i);
      }
      return hits.size() == 1 ? std::optional(hits[0]) : std::nullopt;
    };
    if (fit.size() == 1) {
      chosen = fit[0];
    } else if (fit.empty()) {
      return Error{ErrorCode::kInvalidMap, source + ": no " + kind + " layer for the " + what +
                                               "; the source has " + list(layers)};
    } else if (auto p = pick([&](const GisLayerInfo& l) {
                 return !preferred.empty() && ascii_lower(l.name) == ascii_lower(preferred);
               })) {
      chosen = p;
    } else if (auto k = pick([&](const GisLayerInfo& l) { return well_known(l.name, geometry); })) {
      chosen = k;
    } else {
      return Error{ErrorCode::kInvalidMap,
                   source + ": " + std::to_string(fit.size()) + " " + kind +
                       " layers could hold the " + what + " (" + list(layers) +
                       "): name the layer in a field mapping file (docs/gis.md)"};
    }
  }
  const GisLayerInfo& l = layers[*chosen];
  if (l.geometry != geometry) {
    return Error{ErrorCode::kInvalidMap, source + ": layer " + describe(l) + " cannot hold the " +
                                             what + ": expected " + kind + "s"};
  }
  if (l.features == 0) {
    return Error{ErrorCode::kInvalidMap,
                 source + ": layer " + l.name + " (the " + what + ") has no features"};
  }
  return *chosen;
}

}  // namespace

std::optional<double> gis_unit_to_metres(std::string_view unit) {
  struct Unit {
    std::string_view name;
    double metres;
  };
  static constexpr Unit kUnits[] = {{"mm", 0.001},
                                    {"cm", 0.01},
                                    {"m", 1.0},
                                    {"inch", 0.0254},
                                    {"in", 0.0254},
                                    {"foot", 0.3048},
                                    {"ft", 0.3048},
                                    {"us_survey_foot", 1200.0 / 3937.0},
                                    {"ftUS", 1200.0 / 3937.0}};
  for (const Unit& u : kUnits) {
    if (u.name == unit) return u.metres;
  }
  return std::nullopt;
}

std::string_view to_string(ManholeField field) {
  return kManholeKeys[static_cast<std::size_t>(field)];
}
std::string_view to_string(PipeField field) { return kPipeKeys[static_cast<std::size_t>(field)]; }

GisFieldMapping GisFieldMapping::defaults() {
  GisFieldMapping m;
  auto mh = [&](ManholeField f) -> auto& { return m.manhole[static_cast<std::size_t>(f)]; };
  auto pp = [&](PipeField f) -> auto& { return m.pipe[static_cast<std::size_t>(f)]; };
  mh(ManholeField::kId) = names({"wn_obj_id"});
  mh(ManholeField::kName) = names(
      {"identifier", "name", "manhole_id", "mh_id", "node_id", "schacht_nr", "schachtnr", "id"});
  mh(ManholeField::kType) = names({"ws_type", "manhole_type", "mh_type", "schachtart"});
  mh(ManholeField::kExit) = names({"exit", "is_exit"});
  mh(ManholeField::kCoverLevel) =
      names({"co_level", "cover_level", "rim_level", "rim_elev", "deckelhoehe"}, kCrsUnit);
  mh(ManholeField::kInvertLevel) = names(
      {"wn_bottom_level", "bottom_level", "invert_level", "invert_elev", "sohlhoehe"}, kCrsUnit);
  mh(ManholeField::kInvertLevel).push_back({"z_m", 1.0});
  mh(ManholeField::kDepth) = {{"_depth", kCrsUnit}, {"depth_m", 1.0}, {"depth", kCrsUnit}};
  // sewerplan's GeoJSON writes a shaft's length and width (equal for a round one) in metres.
  mh(ManholeField::kDimension1) = {{"ma_dimension1", kMm},
                                   {"shaft_l_m", 1.0},
                                   {"diameter_m", 1.0},
                                   {"dimension1", kMm},
                                   {"diameter", kMm}};
  mh(ManholeField::kDimension2) = {{"ma_dimension2", kMm}, {"shaft_w_m", 1.0}, {"dimension2", kMm}};
  mh(ManholeField::kVariant) = names({"variant"});
  pp(PipeField::kName) = names({"identifier", "name", "pipe_id", "reach_id", "haltung_nr", "id"});
  pp(PipeField::kFrom) = names({"rp_from_fk_wastewater_networkelement", "from", "from_node",
                                "node_from", "us_node", "upstream", "von_schacht"});
  pp(PipeField::kTo) = names({"rp_to_fk_wastewater_networkelement", "to", "to_node", "node_to",
                              "ds_node", "downstream", "bis_schacht"});
  // sewerplan's GeoJSON: from_lvl_m and to_lvl_m, metres (10 characters, for a Shapefile).
  pp(PipeField::kFromLevel) =
      names({"rp_from_level", "from_level", "from_invert", "us_invert", "invert_from"}, kCrsUnit);
  pp(PipeField::kFromLevel).insert(pp(PipeField::kFromLevel).begin(), {"from_lvl_m", 1.0});
  pp(PipeField::kToLevel) =
      names({"rp_to_level", "to_level", "to_invert", "ds_invert", "invert_to"}, kCrsUnit);
  pp(PipeField::kToLevel).insert(pp(PipeField::kToLevel).begin(), {"to_lvl_m", 1.0});
  pp(PipeField::kHeight) = {{"clear_height", kMm}, {"height_m", 1}, {"height", kMm},
                            {"profil_hoehe", kMm}, {"dn", kMm},     {"diameter", kMm}};
  pp(PipeField::kWidth) = {
      {"width", kMm}, {"diameter_m", 1}, {"clear_width", kMm}, {"profil_breite", kMm}};
  pp(PipeField::kShape) = names({"shape"});
  pp(PipeField::kLength) = {
      {"length_effective", kCrsUnit}, {"length_m", 1.0}, {"length", kCrsUnit}};
  pp(PipeField::kFromAzimuth) = names({"from_az"});
  pp(PipeField::kToAzimuth) = names({"to_az"});
  pp(PipeField::kBlockageRisk) = names({"blockage_risk"});
  pp(PipeField::kFromSlot) = names({"from_slot"});
  pp(PipeField::kToSlot) = names({"to_slot"});
  m.exit_types = {"manhole", "schacht", "normschacht", "mh"};
  return m;
}

Result<GisFieldMapping> parse_gis_field_mapping(std::string_view text, const std::string& file,
                                                Diagnostics& diagnostics) {
  GisFieldMapping m = GisFieldMapping::defaults();
  std::optional<JsonDocument> doc = JsonDocument::parse(text, file, diagnostics);
  if (doc) {
    using Need = JsonFields::Need;
    JsonFields root(doc->root(), "$", file, diagnostics);
    if (auto e = root.member("manholes", Need::kOptional)) {
      JsonFields f(*e, "$.manholes", file, diagnostics);
      read_layer(f, file, m.manhole_layer, m.manhole, kManholeKeys);
      if (auto types = f.array("exit_types", Need::kOptional)) {
        m.exit_types.clear();
        for (JsonElement t : *types) {
          if (t.is_string()) {
            m.exit_types.emplace_back(t.get_string().value());
          } else {
            diagnostics.error(f.where("exit_types"), "expected a list of texts");
          }
        }
      }
      if (auto d = f.number("default_diameter_m", Need::kOptional)) {
        if (*d > 0) {
          m.default_manhole_diameter_m = *d;
        } else {
          diagnostics.error(f.where("default_diameter_m"), "must be positive");
        }
      }
      f.warn_unknown([](std::string_view k) {
        return k == "layer" || k == "exit_types" || k == "default_diameter_m" ||
               std::ranges::find(kManholeKeys, k) != kManholeKeys.end();
      });
    }
    if (auto e = root.member("pipes", Need::kOptional)) {
      JsonFields f(*e, "$.pipes", file, diagnostics);
      read_layer(f, file, m.pipe_layer, m.pipe, kPipeKeys);
      f.warn_unknown([](std::string_view k) {
        return k == "layer" || std::ranges::find(kPipeKeys, k) != kPipeKeys.end();
      });
    }
    for (auto [key, layer] : {std::pair{"inspection_points", &m.point_layer},
                              std::pair{"findings", &m.finding_layer}}) {
      if (auto e = root.member(key, Need::kOptional)) {
        JsonFields f(*e, std::string("$.") + key, file, diagnostics);
        if (auto name = f.string("layer", Need::kOptional)) *layer = *name;
        f.warn_unknown({"layer"});
      }
    }
    if (auto t = root.number("tolerance_m", Need::kOptional)) {
      if (*t >= 0) {
        m.tolerance_m = *t;
      } else {
        diagnostics.error(root.where("tolerance_m"), "must not be negative");
      }
    }
    root.warn_unknown({"manholes", "pipes", "inspection_points", "findings", "tolerance_m"});
  }
  if (diagnostics.has_errors()) {
    return Error{ErrorCode::kParse, diagnostics.error_summary()};
  }
  return m;
}

Result<GisFieldMapping> read_gis_field_mapping(const std::filesystem::path& path,
                                               Diagnostics& diagnostics) {
  Result<std::string> text = read_text_file(path);
  if (!text.has_value()) return text.error();
  return parse_gis_field_mapping(*text, path.string(), diagnostics);
}

Result<GisLayerChoice> choose_gis_layers(const std::vector<GisLayerInfo>& layers,
                                         const GisFieldMapping& mapping, const std::string& source,
                                         std::string_view preferred) {
  Result<std::size_t> manholes =
      choose(layers, GisGeometry::kPoint, mapping.manhole_layer, source, preferred);
  if (!manholes.has_value()) return manholes.error();
  Result<std::size_t> pipes =
      choose(layers, GisGeometry::kLine, mapping.pipe_layer, source, preferred);
  if (!pipes.has_value()) return pipes.error();
  return GisLayerChoice{*manholes, *pipes};
}

Result<std::optional<std::size_t>> choose_gis_place_layer(const std::vector<GisLayerInfo>& layers,
                                                          const GisFieldMapping& mapping,
                                                          GisPlaceLayer which, std::size_t manholes,
                                                          const std::string& source) {
  const bool points = which == GisPlaceLayer::kInspectionPoints;
  const std::string& named = points ? mapping.point_layer : mapping.finding_layer;
  const std::string_view one = points ? "inspection_point" : "finding";
  for (std::size_t i = 0; i < layers.size(); ++i) {
    if (i == manholes || layers[i].geometry != GisGeometry::kPoint) continue;
    const std::string n = ascii_lower(layers[i].name);
    if (named.empty() ? n == one || n == std::string(one) + "s" : n == ascii_lower(named)) {
      return std::optional(i);
    }
  }
  if (!named.empty()) {
    return Error{ErrorCode::kInvalidMap,
                 source + ": no point layer '" + named + "' (the " +
                     (points ? "inspection points'" : "findings'") +
                     " layer of the field mapping) other than the manholes'; the source has " +
                     list(layers)};
  }
  return std::optional<std::size_t>();
}

}  // namespace sewerplan
