// SPDX-License-Identifier: MIT
// The map a command reads: any format of docs/formats/ (core/map_io.h), or a GIS source (a
// GeoPackage, a Shapefile or a directory of them, read through GDAL by gis/gdal_import.h when the
// CLI is built with SEWERPLAN_WITH_GIS). Every command reads its map here.
#pragma once

#include <string>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::cli {

// A GIS source without GIS support is a kUnsupportedFormat error that says so.
Result<SewerMap> read_input_map(const std::string& path, Diagnostics& diagnostics);

}  // namespace sewerplan::cli
