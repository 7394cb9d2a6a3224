// SPDX-License-Identifier: MIT
// GIS sewer layers in: a Shapefile directory or a GeoPackage read through GDAL as a SewerMap.
//
// A source is a GeoPackage (".gpkg"), a Shapefile (".shp": read with the other Shapefiles of its
// directory, its own layer preferred) or a directory of Shapefiles (core's is_gis_source_path,
// core/map_io.h, tells one by its path). Of its layers, one of points
// becomes the manholes and one of lines the pipes (core/map_features.h: choose_gis_layers), their
// fields read through the field mapping: the defaults (QGEP/TEKSI, sewerplan's GeoJSON, common
// municipal names), or a mapping file, by default the "sidecar" beside the source (net.gpkg:
// net.fields.json; a directory: fields.json inside it). The map's CRS is the layers'. GDAL's own
// messages are caught and put into the error; nothing is printed. docs/gis.md has the mapping.
//
//   Diagnostics diagnostics;
//   Result<SewerMap> map = gis::read_gis_map("sewers.gpkg", diagnostics);
//
// Thread safety: each call opens its own dataset; GDAL's error handler is set per thread.
#pragma once

#include <filesystem>
#include <optional>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::gis {

// Where the default mapping file of `source` is (it need not exist).
std::filesystem::path field_mapping_sidecar(const std::filesystem::path& source);

// `mapping_file`: the field mapping; none: the sidecar if it exists, else the defaults. Errors:
// kIo (no such source or mapping file), kParse (GDAL cannot open it, a bad mapping file),
// kInvalidMap (no fitting layers, bad features: source:layer: feature FID: field: what).
Result<SewerMap> read_gis_map(const std::filesystem::path& source, Diagnostics& diagnostics,
                              const std::optional<std::filesystem::path>& mapping_file = {});

}  // namespace sewerplan::gis
