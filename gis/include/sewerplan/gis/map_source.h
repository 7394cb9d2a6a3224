// SPDX-License-Identifier: MIT
// A map from any source sewerplan reads: a GIS source (a GeoPackage, a Shapefile or a directory of
// them) through GDAL (gdal_import.h), any other file through core's read_map (core/map_io.h: JSON,
// the ASCII database, SWMM, ISYBAU). The one place that chooses the reader for a path: the
// sewerplan command (apps/sewerplan/map_input.h) and the Python module's read_map both read here.
//
//   Diagnostics diagnostics;
//   Result<SewerMap> map = gis::read_map_source("sewers.gpkg", diagnostics, "town.fields.json");
//
// Thread safety: as the readers it calls: each call shares nothing.
#pragma once

#include <filesystem>
#include <optional>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::gis {

// `field_mapping`: the GIS field mapping file (docs/formats/gis-layers.md) instead of the
// source's sidecar; given for a source that is not a GIS source, it is a kInvalidArgument error
// naming both files (a mapping that would be ignored is a mistake to point out, not to pass over).
Result<SewerMap> read_map_source(const std::filesystem::path& path, Diagnostics& diagnostics,
                                 const std::optional<std::filesystem::path>& field_mapping = {});

}  // namespace sewerplan::gis
