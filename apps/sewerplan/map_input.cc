// SPDX-License-Identifier: MIT
#include "map_input.h"

#include <filesystem>

#include "sewerplan/core/map_io.h"
#ifdef SEWERPLAN_WITH_GIS
#include "sewerplan/gis/gdal_import.h"
#endif

namespace sewerplan::cli {

Result<SewerMap> read_input_map(const std::string& path, Diagnostics& diagnostics) {
#ifdef SEWERPLAN_WITH_GIS
  if (gis::is_gis_source(path)) return gis::read_gis_map(path, diagnostics);
#else
  const std::string ext = std::filesystem::path(path).extension().string();
  std::error_code ec;
  if (ext == ".shp" || ext == ".gpkg" || std::filesystem::is_directory(path, ec)) {
    return Error{ErrorCode::kUnsupportedFormat,
                 path +
                     ": a GIS source (Shapefile, GeoPackage or directory): this sewerplan is "
                     "built without GIS support (SEWERPLAN_WITH_GIS)"};
  }
#endif
  return read_map(path, diagnostics);
}

}  // namespace sewerplan::cli
