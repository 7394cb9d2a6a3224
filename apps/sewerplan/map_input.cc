// SPDX-License-Identifier: MIT
#include "map_input.h"

#include <cctype>
#include <filesystem>
#include <optional>

#include <CLI/CLI.hpp>

#include "sewerplan/core/map_io.h"
#ifdef SEWERPLAN_WITH_GIS
#include "sewerplan/gis/gdal_import.h"
#include "sewerplan/gis/map_source.h"
#endif

namespace sewerplan::cli {

void add_gis_fields_option(CLI::App& command, std::string& gis_fields) {
  command.add_option("--gis-fields", gis_fields,
                     "Field mapping (JSON, docs/formats/gis-layers.md) of a GeoPackage or "
                     "Shapefile map, instead of the one beside it (NET.fields.json)");
}

bool is_gis_path(const std::string& path) {
#ifdef SEWERPLAN_WITH_GIS
  return gis::is_gis_source(path);
#else
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  std::error_code ec;
  return ext == ".shp" || ext == ".gpkg" || std::filesystem::is_directory(path, ec);
#endif
}

Result<SewerMap> read_input_map(const MapSource& source, Diagnostics& diagnostics) {
  std::optional<std::filesystem::path> fields;
  if (!source.gis_fields.empty()) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(source.gis_fields, ec)) {
      return Error{ErrorCode::kIo, "--gis-fields " + source.gis_fields + ": no such file"};
    }
    fields = source.gis_fields;
  }
#ifdef SEWERPLAN_WITH_GIS
  return gis::read_map_source(source.path, diagnostics, fields);
#else
  if (is_gis_path(source.path) || fields) {
    return Error{ErrorCode::kUnsupportedFormat,
                 (fields ? "--gis-fields " + source.gis_fields : source.path) +
                     ": a GIS source (Shapefile, GeoPackage or directory): this sewerplan is "
                     "built without GIS support (SEWERPLAN_WITH_GIS)"};
  }
  return read_map(source.path, diagnostics);
#endif
}

}  // namespace sewerplan::cli
