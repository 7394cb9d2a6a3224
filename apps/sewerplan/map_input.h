// SPDX-License-Identifier: MIT
// The map a command reads: any format of docs/formats/ (core/map_io.h), or a GIS source (a
// GeoPackage, a Shapefile or a directory of them, read through GDAL when the CLI is built with
// SEWERPLAN_WITH_GIS). The choice of reader is the gis library's (gis/map_source.h), shared with
// the Python module, as is the reader without GIS (core/map_io.h: read_map_without_gis); this file
// adds the command line's side: --gis-fields FILE, the field mapping
// of a GIS source (docs/formats/gis-layers.md) instead of its sidecar. Every command reads its map
// here.
#pragma once

#include <string>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace CLI {
class App;
}

namespace sewerplan::cli {

// Where a command's map comes from: --map FILE and --gis-fields FILE.
struct MapSource {
  std::string path;
  std::string gis_fields;  // empty: the source's sidecar mapping if it has one, else the defaults
};

void add_gis_fields_option(CLI::App& command, std::string& gis_fields);

// Errors: a GIS source, or any --gis-fields, without GIS support (kUnsupportedFormat, saying so);
// --gis-fields naming no file (kIo), a malformed one (kParse, its problems in `diagnostics`), or
// given with a map that is not a GIS source (kInvalidArgument: a usage error).
Result<SewerMap> read_input_map(const MapSource& source, Diagnostics& diagnostics);

}  // namespace sewerplan::cli
