// SPDX-License-Identifier: MIT
#include "sewerplan/gis/map_source.h"

#include "sewerplan/core/map_io.h"
#include "sewerplan/gis/gdal_import.h"

namespace sewerplan::gis {

Result<SewerMap> read_map_source(const std::filesystem::path& path, Diagnostics& diagnostics,
                                 const std::optional<std::filesystem::path>& field_mapping) {
  if (is_gis_source_path(path)) return read_gis_map(path, diagnostics, field_mapping);
  if (field_mapping) {
    return Error{ErrorCode::kInvalidArgument,
                 field_mapping->string() + ": a GIS field mapping, but " + path.string() +
                     " is not a GIS source (a GeoPackage, a Shapefile or a directory of them)"};
  }
  return read_map(path, diagnostics);
}

}  // namespace sewerplan::gis
