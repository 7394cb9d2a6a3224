// SPDX-License-Identifier: MIT
// Reading and writing maps in any format sewerplan knows, chosen by file name or content.
//
// Formats: the native JSON map (map_json.h, ".json") and the paper's ASCII database
// (map_ascii.h, ".sewer"), read and written; EPA SWMM input files (map_swmm.h, ".inp") and
// ISYBAU XML (map_isybau.h, ".xml"), read only. A file with another extension is recognised by its
// content: '{' opens a JSON map, a "sewerdb" line an ASCII database, a "[SECTION]" line a SWMM
// file, '<' an ISYBAU file. GIS sources (a GeoPackage, a Shapefile, a directory) need GDAL: they
// are read by gis::read_gis_map (gis/gdal_import.h), and read_map says so. is_gis_source_path is
// the one test of what a GIS source is, and read_map_without_gis the one reader of a build without
// GDAL (SEWERPLAN_WITH_GIS off), for the sewerplan command and the Python module alike.
//
//   Diagnostics diagnostics;
//   Result<SewerMap> map = read_map("datasets/ais-testbed/map.json", diagnostics);
//   Result<void> written = write_map(*map, "ais.sewer");  // format from the extension
//
// Thread safety: The readers and writers share nothing: call them from any number of threads, each
// with its own Diagnostics.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

enum class MapFormat { kJson, kAscii, kSwmm, kIsybau };

// The formats write_map writes: kJson and kAscii. The others are read only.
constexpr bool is_writable(MapFormat format) {
  return format == MapFormat::kJson || format == MapFormat::kAscii;
}

std::string_view to_string(MapFormat format);
// "json", "ascii", "swmm" or "isybau".
std::optional<MapFormat> map_format_from_name(std::string_view name);
// The names map_format_from_name reads, "json, ascii, swmm, isybau", for messages.
std::string map_format_names();
// From the extension (".json", ".sewer", ".inp", ".xml"), if it names a format.
std::optional<MapFormat> map_format_from_extension(const std::filesystem::path& path);

// From the extension, else from the content; an error names the file if neither tells.
Result<MapFormat> detect_map_format(const std::filesystem::path& path, std::string_view text);

Result<SewerMap> parse_map(std::string_view text, const std::string& file_name, MapFormat format,
                           Diagnostics& diagnostics);

// A GIS source (see is_gis_source_path) is a kUnsupportedFormat error that names gis::read_gis_map.
Result<SewerMap> read_map(const std::filesystem::path& path, Diagnostics& diagnostics);

// Whether `path` is a GIS source: a ".shp", ".gpkg" or ".geojson" extension, in any case, a
// directory (that exists), or a regular file whose first kGeoJsonSniffBytes are GeoJSON
// (looks_like_geojson): sewerplan's own export-geojson output, whatever its name, is read through
// the GIS path, not as a native JSON map.
bool is_gis_source_path(const std::filesystem::path& path);

// Whether the opening of a file is a GeoJSON object (RFC 7946): after an optional UTF-8 BOM and
// white space a '{', no "format" member (a sewerplan map's first), and a "FeatureCollection", or
// a "Feature" with a "geometry".
bool looks_like_geojson(std::string_view head);
inline constexpr std::size_t kGeoJsonSniffBytes = 4096;

// The map reader of a build without GIS support, where gis::read_map_source (gis/map_source.h) is
// absent: a field mapping file (`field_mapping`, docs/formats/gis-layers.md) or a GIS source is a
// kUnsupportedFormat error saying that this build has no GIS support; any other path is read_map's.
Result<SewerMap> read_map_without_gis(
    const std::filesystem::path& path, Diagnostics& diagnostics,
    const std::optional<std::filesystem::path>& field_mapping = std::nullopt);

// The format write_map writes `path` in: `format`, else the extension's; an unknown extension or a
// read-only format is a kUnsupportedFormat error naming the file. Asked before a map is made, so
// that a wrong name fails before the work (sewerplan generate, convert).
Result<MapFormat> map_output_format(const std::filesystem::path& path,
                                    std::optional<MapFormat> format = std::nullopt);

// Without a format, the extension decides (an unknown extension is an error). A read-only format
// is a kUnsupportedFormat error, and nothing is written (map_output_format).
Result<void> write_map(const SewerMap& map, const std::filesystem::path& path,
                       std::optional<MapFormat> format = std::nullopt);

}  // namespace sewerplan
