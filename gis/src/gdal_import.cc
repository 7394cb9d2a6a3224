// SPDX-License-Identifier: MIT
// GDAL's C API (Debian libgdal-dev), private to this file: layers and features in, as the plain
// values of core/map_features.h.
#include "sewerplan/gis/gdal_import.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "sewerplan/core/ascii_case.h"
#include "sewerplan/core/map_features.h"
#include "sewerplan/core/text_file.h"

#include <cpl_error.h>
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

namespace sewerplan::gis {
namespace {

// GDAL reports through a global handler that prints to stderr; a quiet one is pushed for the
// calling thread while sewerplan reads, and the last message goes into the error instead.
class QuietGdal {
 public:
  QuietGdal() {
    static std::once_flag registered;
    std::call_once(registered, [] { GDALAllRegister(); });
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~QuietGdal() { CPLPopErrorHandler(); }
  QuietGdal(const QuietGdal&) = delete;
  QuietGdal& operator=(const QuietGdal&) = delete;

  static std::string last_message() {
    const char* m = CPLGetLastErrorMsg();
    return m != nullptr && *m != '\0' ? std::string(": ") + m : std::string();
  }
};

struct DatasetClose {
  void operator()(void* ds) const { GDALClose(ds); }
};
using Dataset = std::unique_ptr<void, DatasetClose>;

struct FeatureDestroy {
  void operator()(OGRFeatureH f) const { OGR_F_Destroy(f); }
};
using Feature = std::unique_ptr<std::remove_pointer_t<OGRFeatureH>, FeatureDestroy>;

GisGeometry kind_of(OGRwkbGeometryType type) {
  const OGRwkbGeometryType flat = OGR_GT_Flatten(type);
  if (flat == wkbNone) return GisGeometry::kNone;
  if (flat == wkbPoint || flat == wkbMultiPoint) return GisGeometry::kPoint;
  if (flat == wkbLineString || flat == wkbMultiLineString || flat == wkbCircularString ||
      flat == wkbCompoundCurve || flat == wkbMultiCurve) {
    return GisGeometry::kLine;
  }
  return GisGeometry::kOther;
}

// A layer of unknown geometry type (a GeoPackage's GEOMETRY, ogr2ogr's output from GeoJSON) is a
// point or line layer if every feature with a geometry is one.
GisGeometry kind_of(OGRLayerH layer) {
  const OGRwkbGeometryType declared = OGR_L_GetGeomType(layer);
  if (OGR_GT_Flatten(declared) != wkbUnknown) return kind_of(declared);
  std::optional<GisGeometry> seen;
  OGR_L_ResetReading(layer);
  while (Feature f{OGR_L_GetNextFeature(layer)}) {
    OGRGeometryH g = OGR_F_GetGeometryRef(f.get());
    if (g == nullptr || OGR_G_IsEmpty(g)) continue;
    const GisGeometry k = kind_of(OGR_G_GetGeometryType(g));
    if (seen && *seen != k) return GisGeometry::kOther;
    seen = k;
  }
  return seen.value_or(GisGeometry::kOther);
}

void read_geometry(OGRGeometryH g, GisFeature& out) {
  if (g == nullptr || OGR_G_IsEmpty(g)) return;  // kNone
  out.geometry_name = OGR_G_GetGeometryName(g);
  std::unique_ptr<std::remove_pointer_t<OGRGeometryH>, decltype(&OGR_G_DestroyGeometry)> linear(
      nullptr, &OGR_G_DestroyGeometry);
  if (OGR_GT_IsNonLinear(OGR_G_GetGeometryType(g))) {  // QGEP's compound curves
    linear.reset(OGR_G_GetLinearGeometry(g, 0, nullptr));
    if (!linear) {
      out.geometry = GisGeometry::kOther;
      return;
    }
    g = linear.get();
  }
  OGRwkbGeometryType flat = OGR_GT_Flatten(OGR_G_GetGeometryType(g));
  if (flat == wkbMultiPoint || flat == wkbMultiLineString) {
    const int parts = OGR_G_GetGeometryCount(g);
    if (parts != 1) {
      out.geometry = GisGeometry::kOther;
      out.geometry_name += " of " + std::to_string(parts) + " parts";
      return;
    }
    g = OGR_G_GetGeometryRef(g, 0);
    flat = OGR_GT_Flatten(OGR_G_GetGeometryType(g));
  }
  if (flat != wkbPoint && flat != wkbLineString) {
    out.geometry = GisGeometry::kOther;
    return;
  }
  out.geometry = flat == wkbPoint ? GisGeometry::kPoint : GisGeometry::kLine;
  out.has_z = OGR_G_Is3D(g) != 0;
  const int n = OGR_G_GetPointCount(g);
  for (int i = 0; i < n; ++i) {
    out.points.push_back({OGR_G_GetX(g, i), OGR_G_GetY(g, i), OGR_G_GetZ(g, i)});
  }
}

using Srs = std::unique_ptr<std::remove_pointer_t<OGRSpatialReferenceH>, decltype(&OSRRelease)>;

// The layer's CRS as AUTHORITY:CODE, identified by GDAL when the source does not say it, and its
// linear unit: a projected CRS's axes in feet or US survey feet are scaled to metres
// (GisLayer::unit_m).
void read_crs(OGRLayerH layer, GisLayer& out) {
  OGRSpatialReferenceH srs = OGR_L_GetSpatialRef(layer);
  if (srs == nullptr) return;
  Srs copy(OSRClone(srs), &OSRRelease);
  if (OSRIsProjected(copy.get()) != 0) out.unit_m = OSRGetLinearUnits(copy.get(), nullptr);
  if (OSRGetAuthorityName(copy.get(), nullptr) == nullptr) OSRAutoIdentifyEPSG(copy.get());
  const char* authority = OSRGetAuthorityName(copy.get(), nullptr);
  const char* code = OSRGetAuthorityCode(copy.get(), nullptr);
  if (authority != nullptr && code != nullptr) {
    if (Result<Crs> crs = parse_crs(std::string(authority) + ":" + code); crs.has_value()) {
      out.crs = *crs;
      return;
    }
  }
  const char* name = OSRGetName(copy.get());
  out.unnamed_crs = name != nullptr && *name != '\0' ? name : "unnamed";
}

GisLayer read_layer(OGRLayerH layer) {
  GisLayer out;
  out.name = to_utf8_lossy(OGR_L_GetName(layer));
  read_crs(layer, out);
  OGRFeatureDefnH defn = OGR_L_GetLayerDefn(layer);
  const int fields = OGR_FD_GetFieldCount(defn);
  std::vector<bool> numeric;
  for (int i = 0; i < fields; ++i) {
    OGRFieldDefnH fd = OGR_FD_GetFieldDefn(defn, i);
    out.fields.push_back(to_utf8_lossy(OGR_Fld_GetNameRef(fd)));
    const OGRFieldType t = OGR_Fld_GetType(fd);
    numeric.push_back(t == OFTInteger || t == OFTInteger64 || t == OFTReal);
  }
  OGR_L_ResetReading(layer);
  while (Feature f{OGR_L_GetNextFeature(layer)}) {
    GisFeature feature;
    feature.fid = OGR_F_GetFID(f.get());
    for (int i = 0; i < fields; ++i) {
      if (!OGR_F_IsFieldSetAndNotNull(f.get(), i)) {
        feature.values.emplace_back();
      } else if (numeric[static_cast<std::size_t>(i)]) {
        feature.values.emplace_back(OGR_F_GetFieldAsDouble(f.get(), i));
      } else {
        feature.values.emplace_back(to_utf8_lossy(OGR_F_GetFieldAsString(f.get(), i)));
      }
    }
    read_geometry(OGR_F_GetGeometryRef(f.get()), feature);
    out.features.push_back(std::move(feature));
  }
  return out;
}

// A source in longitude and latitude (GeoJSON is always WGS84, RFC 7946) has no lengths: its
// points are projected to `target`, a projected CRS, through GDAL's transformation (PROJ).
Result<void> project_geographic(OGRLayerH layer, const Crs& target, GisLayer& out,
                                const std::string& source) {
  Srs from(OSRClone(OGR_L_GetSpatialRef(layer)), &OSRRelease);
  Srs to(OSRNewSpatialReference(nullptr), &OSRRelease);
  if (OSRSetFromUserInput(to.get(), target.to_string().c_str()) != OGRERR_NONE ||
      OSRIsProjected(to.get()) == 0) {
    return Error{ErrorCode::kInvalidMap,
                 source + ": " + target.to_string() + " is no projected CRS that PROJ knows"};
  }
  OSRSetAxisMappingStrategy(from.get(), OAMS_TRADITIONAL_GIS_ORDER);
  OSRSetAxisMappingStrategy(to.get(), OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<std::remove_pointer_t<OGRCoordinateTransformationH>,
                  decltype(&OCTDestroyCoordinateTransformation)>
      transform(OCTNewCoordinateTransformation(from.get(), to.get()),
                &OCTDestroyCoordinateTransformation);
  if (!transform) {
    return Error{ErrorCode::kInvalidMap, source + ": no transformation from " + out.name +
                                             "'s CRS to " + target.to_string() +
                                             QuietGdal::last_message()};
  }
  for (GisFeature& f : out.features) {
    for (std::array<double, 3>& p : f.points) {
      double x = p[0], y = p[1], z = p[2];
      if (OCTTransform(transform.get(), 1, &x, &y, &z) == 0 || !std::isfinite(x) ||
          !std::isfinite(y)) {
        return Error{ErrorCode::kInvalidMap,
                     source + ":" + out.name + ": feature " + std::to_string(f.fid) + ": (" +
                         std::to_string(p[0]) + ", " + std::to_string(p[1]) +
                         ") cannot be projected to " + target.to_string()};
      }
      p = {x, y, p[2]};  // heights stay as they are: metres above the datum
    }
  }
  out.crs = target;
  out.unnamed_crs.clear();
  out.unit_m = OSRGetLinearUnits(to.get(), nullptr);
  return {};
}

// The UTM zone of WGS84 (EPSG:326zz north, 327zz south) around the mean of the layer's points.
std::optional<Crs> utm_zone_of(const GisLayer& layer) {
  double lon = 0, lat = 0;
  std::size_t n = 0;
  for (const GisFeature& f : layer.features) {
    for (const std::array<double, 3>& p : f.points) {
      lon += p[0];
      lat += p[1];
      ++n;
    }
  }
  if (n == 0) return std::nullopt;
  lon /= static_cast<double>(n);
  lat /= static_cast<double>(n);
  if (!(lon >= -180 && lon <= 180 && lat >= -80 && lat <= 84)) return std::nullopt;
  const int zone = std::clamp(static_cast<int>(std::floor((lon + 180) / 6)) + 1, 1, 60);
  return Crs{.authority = "EPSG",
             .code = static_cast<std::uint32_t>((lat >= 0 ? 32600 : 32700) + zone)};
}

// One GeoJSON layer split into the GIS layers it holds: by the "layer" property sewerplan's
// export-geojson writes (manhole, pipe, inspection_point, ...), else by geometry ("points",
// "lines").
std::vector<GisLayer> split_geojson(const GisLayer& all) {
  std::optional<std::size_t> layer_field;
  for (std::size_t i = 0; i < all.fields.size(); ++i) {
    if (all.fields[i] == "layer") layer_field = i;
  }
  std::vector<GisLayer> out;
  auto layer_for = [&](const std::string& name) -> GisLayer& {
    for (GisLayer& l : out) {
      if (l.name == name) return l;
    }
    GisLayer l{.name = name,
               .fields = all.fields,
               .features = {},
               .crs = all.crs,
               .unnamed_crs = all.unnamed_crs,
               .unit_m = all.unit_m};
    out.push_back(std::move(l));
    return out.back();
  };
  for (const GisFeature& f : all.features) {
    std::string name;
    if (layer_field && f.values.size() > *layer_field) {
      if (const auto* t = std::get_if<std::string>(&f.values[*layer_field])) name = *t;
    }
    if (name.empty()) {
      name = f.geometry == GisGeometry::kPoint  ? "points"
             : f.geometry == GisGeometry::kLine ? "lines"
                                                : "other";
    }
    layer_for(name).features.push_back(f);
  }
  return out;
}

GisGeometry kind_of(const GisLayer& layer) {
  std::optional<GisGeometry> seen;
  for (const GisFeature& f : layer.features) {
    if (f.geometry == GisGeometry::kNone) continue;
    if (seen && *seen != f.geometry) return GisGeometry::kOther;
    seen = f.geometry;
  }
  return seen.value_or(GisGeometry::kOther);
}

// The CRS sewerplan's export-geojson names in its FeatureCollection's foreign member
// "sewerplan_crs": the map's own, to project the WGS84 coordinates back into.
std::optional<Crs> geojson_map_crs(const std::filesystem::path& source, Diagnostics& diagnostics) {
  Result<std::string> text = read_text_file(source);
  if (!text.has_value()) return std::nullopt;
  const nlohmann::json doc = nlohmann::json::parse(*text, nullptr, false);
  if (!doc.is_object() || !doc.contains("sewerplan_crs")) return std::nullopt;
  const nlohmann::json& crs = doc["sewerplan_crs"];
  if (!crs.is_string()) {
    diagnostics.warning(source.string() + ":$.sewerplan_crs", "not a text: ignored");
    return std::nullopt;
  }
  Result<Crs> parsed = parse_crs(crs.get<std::string>());
  if (!parsed.has_value()) {
    diagnostics.warning(source.string() + ":$.sewerplan_crs", parsed.error().message + ": ignored");
    return std::nullopt;
  }
  return *parsed;
}

}  // namespace

std::filesystem::path field_mapping_sidecar(const std::filesystem::path& source) {
  std::error_code ec;
  if (std::filesystem::is_directory(source, ec)) return source / "fields.json";
  std::filesystem::path p = source;
  return p.replace_extension(".fields.json");
}

Result<SewerMap> read_gis_map(const std::filesystem::path& source, Diagnostics& diagnostics,
                              const std::optional<std::filesystem::path>& mapping_file) {
  std::error_code ec;
  if (!std::filesystem::exists(source, ec)) {
    return Error{ErrorCode::kIo, source.string() + ": no such file or directory"};
  }
  GisFieldMapping mapping = GisFieldMapping::defaults();
  std::optional<std::filesystem::path> mapping_path = mapping_file;
  if (!mapping_path && std::filesystem::exists(field_mapping_sidecar(source), ec)) {
    mapping_path = field_mapping_sidecar(source);
  }
  if (mapping_path) {
    Result<GisFieldMapping> read = read_gis_field_mapping(*mapping_path, diagnostics);
    if (!read.has_value()) return read.error();
    mapping = std::move(*read);
  }
  const bool shapefile = ascii_lower(source.extension().string()) == ".shp";
  std::error_code dir_ec;
  const bool geojson = !shapefile && !std::filesystem::is_directory(source, dir_ec) &&
                       ascii_lower(source.extension().string()) != ".gpkg";
  std::filesystem::path open = source;
  if (shapefile) open = source.has_parent_path() ? source.parent_path() : ".";
  const std::string name = source.string();
  QuietGdal quiet;
  const char* const drivers[] = {"ESRI Shapefile", "GPKG", "GeoJSON", nullptr};
  Dataset ds(
      GDALOpenEx(open.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, drivers, nullptr, nullptr));
  if (!ds) {
    return Error{ErrorCode::kParse, name +
                                        ": not a GeoJSON, GeoPackage or Shapefile GDAL can open" +
                                        QuietGdal::last_message()};
  }
  std::vector<GisLayerInfo> infos;
  std::vector<OGRLayerH> layers;
  std::vector<GisLayer> split;  // a GeoJSON's one layer, split (split_geojson)
  const int count = GDALDatasetGetLayerCount(ds.get());
  for (int i = 0; i < count; ++i) {
    OGRLayerH l = GDALDatasetGetLayer(ds.get(), i);
    if (l == nullptr) continue;
    layers.push_back(l);
    if (geojson) {
      for (GisLayer& part : split_geojson(read_layer(l))) {
        infos.push_back(
            {.name = part.name, .geometry = kind_of(part), .features = part.features.size()});
        split.push_back(std::move(part));
      }
      continue;
    }
    infos.push_back(
        {.name = to_utf8_lossy(OGR_L_GetName(l)),
         .geometry = kind_of(l),
         .features = static_cast<std::size_t>(std::max<GIntBig>(0, OGR_L_GetFeatureCount(l, 1)))});
  }
  const std::string preferred = shapefile ? source.stem().string() : std::string();
  Result<GisLayerChoice> choice = choose_gis_layers(infos, mapping, name, preferred);
  if (!choice.has_value()) return choice.error();
  auto layer_of = [&](std::size_t i) { return geojson ? layers.front() : layers[i]; };
  GisLayer manholes = geojson ? split[choice->manholes] : read_layer(layers[choice->manholes]);
  GisLayer pipes = geojson ? split[choice->pipes] : read_layer(layers[choice->pipes]);
  // Inspection points and findings, when the source has their layers.
  std::array<std::optional<GisLayer>, 2> places;
  for (GisPlaceLayer which : {GisPlaceLayer::kInspectionPoints, GisPlaceLayer::kFindings}) {
    Result<std::optional<std::size_t>> chosen =
        choose_gis_place_layer(infos, mapping, which, choice->manholes, name);
    if (!chosen.has_value()) return chosen.error();
    if (*chosen) {
      places[static_cast<std::size_t>(which)] =
          geojson ? split[**chosen] : read_layer(layers[**chosen]);
    }
  }
  // Longitude and latitude: projected to the map's own CRS (sewerplan's GeoJSON names it), else
  // to the UTM zone the network lies in.
  OGRSpatialReferenceH srs = OGR_L_GetSpatialRef(layer_of(choice->manholes));
  if (srs != nullptr && OSRIsGeographic(srs) != 0) {
    std::optional<Crs> target = geojson ? geojson_map_crs(source, diagnostics) : std::nullopt;
    if (!target) {
      target = utm_zone_of(manholes);
      if (!target) {
        return Error{ErrorCode::kInvalidMap,
                     name +
                         ": longitudes and latitudes outside every UTM zone: no projected CRS "
                         "to put the network in"};
      }
      diagnostics.warning(name, "positions in longitude and latitude: projected to " +
                                    target->to_string() +
                                    " (WGS 84 / UTM, the zone the manholes lie in)");
    }
    for (auto [layer, out] : {std::pair{layer_of(choice->manholes), &manholes},
                              std::pair{layer_of(choice->pipes), &pipes}}) {
      if (Result<void> done = project_geographic(layer, *target, *out, name); !done.has_value()) {
        return done.error();
      }
    }
  }
  std::string map_name = source.stem().string();
  if (map_name.empty() || map_name == ".") map_name = std::filesystem::absolute(source).filename();
  return map_from_gis_layers(manholes, pipes, mapping, name, to_utf8_lossy(map_name), diagnostics,
                             places[0] ? &*places[0] : nullptr, places[1] ? &*places[1] : nullptr);
}

}  // namespace sewerplan::gis
