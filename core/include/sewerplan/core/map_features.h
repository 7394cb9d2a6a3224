// SPDX-License-Identifier: MIT
// A sewer network as GIS features (manholes as points, pipes as lines, each with attributes) and
// the field mapping that turns them into a SewerMap.
//
// Municipal sewer data lives in Shapefiles and GeoPackages: one layer of manholes (points), one of
// pipes (lines), with attribute fields whose names depend on who made the data (the QGEP/TEKSI
// wastewater model's `identifier`, `co_level`, `clear_height`, ..., or a town's own). Reading the
// files needs GDAL, which only the gis library links (gis/gdal_import.h); this header is the part
// that needs no GDAL: the features as plain values, the choice of the two layers, the field mapping
// (defaults for QGEP/TEKSI, sewerplan's own GeoJSON and common municipal names, overridden by a
// small JSON file, docs/gis.md), and map_from_gis_layers, which joins pipes to manholes by the
// named from/to fields, or else by the nearest manhole within `tolerance_m` of a line's end point,
// and builds the map like every other importer (core/src/network_import.h, then MapBuilder).
// Problems name the source, the layer, the feature ID and the field.
//
//   GisFieldMapping mapping = GisFieldMapping::defaults();
//   Result<SewerMap> map = map_from_gis_layers(manholes, pipes, mapping, "net.gpkg", diagnostics);
//
// Thread safety: plain values and free functions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "sewerplan/core/crs.h"
#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

// A field's value: null, a number or a text (UTF-8).
using GisValue = std::variant<std::monostate, double, std::string>;

enum class GisGeometry { kNone, kPoint, kLine, kOther };

struct GisFeature {
  std::int64_t fid = 0;
  GisGeometry geometry = GisGeometry::kNone;
  std::string geometry_name;                  // as the source names it, for messages: "Polygon"
  std::vector<std::array<double, 3>> points;  // one for a point, the vertices of a line
  bool has_z = false;
  std::vector<GisValue> values;  // by field, in GisLayer::fields order
};

struct GisLayer {
  std::string name;
  std::vector<std::string> fields;
  std::vector<GisFeature> features;
  std::optional<Crs> crs;
  std::string unnamed_crs;  // a CRS the source has but with no AUTHORITY:CODE: its name
  // Metres per unit of the CRS's axes (PROJ's linear unit: 0.3048006096 for US survey feet, as in
  // EPSG:2229): the points' x, y and z, and every field measured "in the CRS's unit", are scaled by
  // it, so that the map is in metres whatever the source's unit (docs/gis.md, "Units").
  double unit_m = 1;
};

// What a source holds, to choose the two layers before reading their features.
struct GisLayerInfo {
  std::string name;
  GisGeometry geometry = GisGeometry::kNone;  // kOther: polygons, or mixed geometry types
  std::size_t features = 0;
};

// The fields a manhole and a pipe are read from. Each has a list of candidate field names, the
// first one the layer has wins (case-insensitively; a Shapefile's name cut to 10 characters
// matches the longer candidate).
enum class ManholeField {
  kId,           // the key pipes' from/to fields name (default: the name)
  kName,         // required
  kType,         // with exit_types: which manholes are exits
  kExit,         // a boolean or 0/1: an exit (before kType)
  kCoverLevel,   // cover level, metres
  kInvertLevel,  // bottom (invert) level, metres; else cover less depth, else the point's z
  kDepth,        // metres
  kDimension1,   // shaft diameter or length
  kDimension2,   // shaft width (a rectangular shaft)
  kVariant,      // the geometric variant of its type, one letter A..Z (the paper's TYPE_B)
};
inline constexpr std::size_t kManholeFieldCount = 10;

enum class PipeField {
  kName,  // required
  kFrom,  // the upstream manhole's key (ManholeField::kId)
  kTo,
  kFromLevel,  // the pipe's invert at its from end, metres; else the line's z, else the manhole's
  kToLevel,
  kHeight,        // clear height; required with kWidth: one of them
  kWidth,         // clear width
  kShape,         // sewerplan's names: circular, rectangular, egg, other
  kLength,        // metres; else the line's length
  kFromAzimuth,   // degrees counter-clockwise from east: the slot's direction at the from end;
  kToAzimuth,     // else the line's direction there (export-geojson writes both)
  kBlockageRisk,  // the likelihood (0..1) that the pipe is blocked
  kFromSlot,      // the slot's number (0 first) in the from (to) manhole, which keeps the
  kToSlot,        // planner's slot numbers through a GIS round trip (export-geojson writes them)
};
inline constexpr std::size_t kPipeFieldCount = 14;

std::string_view to_string(ManholeField field);  // the mapping file's key: "cover_level"
std::string_view to_string(PipeField field);

// A field name and its unit, as metres per unit of the field's values (0.001 for millimetres,
// 0.0254 for inches; 1 for degrees, an azimuth field's only unit). Empty: the layer's CRS's own
// linear unit (GisLayer::unit_m), the default of levels, depths and lengths whose field name does
// not say "_m".
struct GisFieldCandidate {
  std::string field;
  std::optional<double> to_metres = 1.0;
};

// Metres per unit of a mapping file's unit name: "mm", "cm", "m", "inch" ("in"), "foot" ("ft",
// the international foot, 0.3048 m), "us_survey_foot" ("ftUS", 1200/3937 m); nullopt for any
// other name.
std::optional<double> gis_unit_to_metres(std::string_view unit);

struct GisFieldMapping {
  std::string manhole_layer;  // empty: chosen by geometry type and name (choose_gis_layers)
  std::string pipe_layer;
  // The inspection points' layer (fields name, pipe, offset_m, as export-geojson writes them);
  // empty: a point layer named inspection_point or inspection_points, if the source has one.
  std::string point_layer;
  // The findings' layer (fields pipe, code, characterisation, offset_m, quantity1, quantity2);
  // empty: a point layer named finding or findings, if the source has one.
  std::string finding_layer;
  std::array<std::vector<GisFieldCandidate>, kManholeFieldCount> manhole;
  std::array<std::vector<GisFieldCandidate>, kPipeFieldCount> pipe;
  std::vector<std::string> exit_types;  // type values (case-insensitive) of exit manholes
  double default_manhole_diameter_m = 1.0;
  double tolerance_m = 0.5;  // an end point this close to a manhole joins it

  // QGEP/TEKSI, sewerplan's GeoJSON export and common municipal names (docs/gis.md).
  static GisFieldMapping defaults();
  const std::vector<GisFieldCandidate>& operator[](ManholeField f) const {
    return manhole[static_cast<std::size_t>(f)];
  }
  const std::vector<GisFieldCandidate>& operator[](PipeField f) const {
    return pipe[static_cast<std::size_t>(f)];
  }
};

// The defaults, overridden by a mapping file (docs/gis.md): a field named there replaces that
// field's candidates, null removes them. Problems are "file:$.path: ..." diagnostics.
Result<GisFieldMapping> parse_gis_field_mapping(std::string_view text, const std::string& file,
                                                Diagnostics& diagnostics);
Result<GisFieldMapping> read_gis_field_mapping(const std::filesystem::path& path,
                                               Diagnostics& diagnostics);

struct GisLayerChoice {
  std::size_t manholes = 0;
  std::size_t pipes = 0;
};

// The layer the mapping names, else the only point (line) layer, else among several the one named
// `preferred` or with a well-known name (vw_qgep_wastewater_structure, manholes, ...;
// vw_qgep_reach, pipes, ...). An error (kInvalidMap) lists the layers when none or several fit, or
// a chosen layer is empty.
Result<GisLayerChoice> choose_gis_layers(const std::vector<GisLayerInfo>& layers,
                                         const GisFieldMapping& mapping, const std::string& source,
                                         std::string_view preferred = {});

// The inspection points' (findings') layer among `layers` (not `manholes`): the one the mapping
// names (an error if there is none such), else a point layer named inspection_point(s)
// (finding(s)); nullopt: none.
enum class GisPlaceLayer { kInspectionPoints, kFindings };
Result<std::optional<std::size_t>> choose_gis_place_layer(const std::vector<GisLayerInfo>& layers,
                                                          const GisFieldMapping& mapping,
                                                          GisPlaceLayer which, std::size_t manholes,
                                                          const std::string& source);

// The map, named `map_name`, with the manhole layer's CRS (the pipe layer's must agree), the
// inspection points of `points` (fields name, pipe and offset_m, metres from the pipe's from end)
// and the findings of `findings` (pipe, code, characterisation, offset_m, quantity1, quantity2).
Result<SewerMap> map_from_gis_layers(const GisLayer& manholes, const GisLayer& pipes,
                                     const GisFieldMapping& mapping, const std::string& source,
                                     std::string map_name, Diagnostics& diagnostics,
                                     const GisLayer* points = nullptr,
                                     const GisLayer* findings = nullptr);

}  // namespace sewerplan
