// SPDX-License-Identifier: MIT
#include "map_input.h"

#include <filesystem>
#include <optional>

#include <CLI/CLI.hpp>

#include "sewerplan/core/map_io.h"
#ifdef SEWERPLAN_WITH_GIS
#include "sewerplan/modules/gis.h"
#endif

namespace sewerplan::cli {

void add_gis_fields_option(CLI::App& command, std::string& gis_fields) {
  command.add_option("--gis-fields", gis_fields,
                     "Field mapping (JSON, docs/formats/gis-layers.md) of a GeoPackage or "
                     "Shapefile map, instead of the one beside it (NET.fields.json)");
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
  // Only a GIS source (or a field mapping, whose misuse gis::read_map_source explains) loads the
  // GIS module; every other map is core's.
  if (!is_gis_source_path(source.path) && !fields) return read_map(source.path, diagnostics);
  Result<const modules::GisTable*> module = modules::gis_module("reading " + source.path);
  if (!module.has_value()) return module.error();
  return (*module)->read_map_source(source.path, diagnostics, fields);
#else
  return read_map_without_gis(source.path, diagnostics, fields);
#endif
}

}  // namespace sewerplan::cli
