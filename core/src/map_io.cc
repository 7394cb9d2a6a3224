// SPDX-License-Identifier: MIT
#include "sewerplan/core/map_io.h"

#include <algorithm>
#include <cstddef>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include "sewerplan/core/ascii_case.h"
#include "sewerplan/core/enum_names.h"
#include "sewerplan/core/map_ascii.h"
#include "sewerplan/core/map_isybau.h"
#include "sewerplan/core/map_json.h"
#include "sewerplan/core/map_swmm.h"
#include "sewerplan/core/mapped_file.h"
#include "sewerplan/core/text_file.h"

#include "map_json_fast.h"

namespace sewerplan {
namespace {

constexpr detail::EnumNames<MapFormat, 4> kMapFormats{{
    {MapFormat::kJson, "json"},
    {MapFormat::kAscii, "ascii"},
    {MapFormat::kSwmm, "swmm"},
    {MapFormat::kIsybau, "isybau"},
}};
static_assert(detail::distinct(kMapFormats));

// A SWMM file opens with a "[SECTION]" line, after ';' comments.
bool looks_like_swmm(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
      ++i;
    } else if (c == ';') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else {
      return c == '[';
    }
  }
  return false;
}

Error read_only(MapFormat format, const std::filesystem::path& path) {
  return Error{ErrorCode::kUnsupportedFormat,
               path.string() + ": sewerplan reads " + std::string(to_string(format)) +
                   " files but does not write them (write .json or .sewer)"};
}

}  // namespace

std::string_view to_string(MapFormat format) { return detail::name_of(kMapFormats, format); }

std::optional<MapFormat> map_format_from_name(std::string_view name) {
  return detail::value_of(kMapFormats, name);
}

std::string map_format_names() { return detail::names_joined(kMapFormats); }

std::optional<MapFormat> map_format_from_extension(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".json") return MapFormat::kJson;
  if (ext == ".sewer") return MapFormat::kAscii;
  if (ext == ".inp" || ext == ".INP") return MapFormat::kSwmm;
  if (ext == ".xml" || ext == ".XML") return MapFormat::kIsybau;
  return std::nullopt;
}

Result<MapFormat> detect_map_format(const std::filesystem::path& path, std::string_view text) {
  const std::string ext = path.extension().string();
  if (ext == ".xtf" || ext == ".XTF" || ext == ".itf" || ext == ".ITF" ||
      text.starts_with("SCNT")) {
    return Error{ErrorCode::kUnsupportedFormat,
                 path.string() +
                     ": an INTERLIS transfer file (SIA405 Abwasser, VSA-KEK): sewerplan reads "
                     "ISYBAU XML, not INTERLIS; export the network as ISYBAU XML"};
  }
  if (auto f = map_format_from_extension(path)) return *f;
  std::size_t i = 0;
  while (i < text.size()) {
    // Skip white space and '#' comment lines.
    if (text[i] == ' ' || text[i] == '\t' || text[i] == '\r' || text[i] == '\n') {
      ++i;
    } else if (text[i] == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else {
      break;
    }
  }
  const std::string_view rest = text.substr(i);
  if (rest.starts_with("{")) return MapFormat::kJson;
  if (rest.starts_with("sewerdb")) return MapFormat::kAscii;
  if (looks_like_swmm(rest)) return MapFormat::kSwmm;
  if (rest.starts_with("<")) return MapFormat::kIsybau;
  return Error{
      ErrorCode::kUnsupportedFormat,
      path.string() +
          ": unknown map format (expected a .json map, a .sewer database, a SWMM .inp or an "
          "ISYBAU .xml file)"};
}

Result<SewerMap> parse_map(std::string_view text, const std::string& file_name, MapFormat format,
                           Diagnostics& diagnostics) {
  switch (format) {
    case MapFormat::kJson:
      return read_map_json(text, file_name, diagnostics);
    case MapFormat::kAscii:
      return read_map_ascii(text, file_name, diagnostics);
    case MapFormat::kSwmm:
      return read_map_swmm(text, file_name, diagnostics);
    case MapFormat::kIsybau:
      return read_map_isybau(text, file_name, diagnostics);
  }
  return Error{ErrorCode::kUnsupportedFormat, file_name + ": unknown format"};
}

bool looks_like_geojson(std::string_view head) {
  if (head.starts_with("\xEF\xBB\xBF")) head.remove_prefix(3);
  const std::size_t open = head.find_first_not_of(" \t\r\n");
  if (open == std::string_view::npos || head[open] != '{') return false;
  // A sewerplan map names its format first; a GeoJSON object's "type" is a FeatureCollection or
  // a Feature (RFC 7946 3.2, 3.3), wherever in the object it stands: the features' own "type":
  // "Feature" and "geometry" show it too when the collection's "type" comes after them.
  if (head.find("\"format\"") != std::string_view::npos) return false;
  if (head.find("\"FeatureCollection\"") != std::string_view::npos) return true;
  return head.find("\"Feature\"") != std::string_view::npos &&
         head.find("\"geometry\"") != std::string_view::npos;
}

bool is_gis_source_path(const std::filesystem::path& path) {
  const std::string ext = ascii_lower(path.extension().string());
  if (ext == ".shp" || ext == ".gpkg" || ext == ".geojson") return true;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return true;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  std::string head(kGeoJsonSniffBytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, in.gcount())));
  return looks_like_geojson(head);
}

Result<SewerMap> read_map_without_gis(const std::filesystem::path& path, Diagnostics& diagnostics,
                                      const std::optional<std::filesystem::path>& field_mapping) {
  if (field_mapping) {
    return Error{ErrorCode::kUnsupportedFormat,
                 field_mapping->string() +
                     ": a GIS field mapping, but this sewerplan is built without GIS support "
                     "(SEWERPLAN_WITH_GIS)"};
  }
  if (is_gis_source_path(path)) {
    return Error{ErrorCode::kUnsupportedFormat,
                 path.string() +
                     ": a GIS source (GeoJSON, GeoPackage, Shapefile or a directory of them), "
                     "but this sewerplan is built without GIS support (SEWERPLAN_WITH_GIS)"};
  }
  return read_map(path, diagnostics);
}

Result<SewerMap> read_map(const std::filesystem::path& path, Diagnostics& diagnostics) {
  if (is_gis_source_path(path)) {
    return Error{
        ErrorCode::kUnsupportedFormat,
        path.string() +
            ": a GIS source (GeoJSON, GeoPackage, Shapefile or a directory of them): read it with "
            "gis::read_gis_map (docs/formats/gis-layers.md), as the sewerplan command does"};
  }
  // A regular file is read where the page cache holds it (mapped_file.h); anything else as text.
  std::optional<detail::MappedFile> mapped = detail::MappedFile::open(path);
  std::string read;
  if (!mapped) {
    Result<std::string> text = read_text_file(path);
    if (!text.has_value()) return text.error();
    read = std::move(*text);
  }
  std::string_view text = mapped ? mapped->text() : std::string_view(read);
  // A byte-order mark (read_text_file's files are without one already): UTF-8's is skipped,
  // UTF-16 and UTF-32 text decoded.
  if (const ByteOrderMark mark = byte_order_mark(text); mark.encoding == "UTF-8") {
    text.remove_prefix(mark.size);
  } else if (mark.size > 0) {
    Result<std::string> decoded = without_byte_order_mark(text, path.string());
    if (!decoded.has_value()) return decoded.error();
    read = std::move(*decoded);
    mapped.reset();
    text = read;
  }
  Result<MapFormat> format = detect_map_format(path, text);
  if (!format.has_value()) return format.error();
  if (*format == MapFormat::kJson) {
    // The records own their names: free the text before building (a 1,000,000-manhole map is
    // 430 MB of text), so that text and map are never held at once.
    if (std::optional<MapBuilder> builder = detail::read_map_json_fast(text, path.string())) {
      if (mapped) mapped->close();
      std::string().swap(read);
      return std::move(*builder).build(diagnostics);
    }
    return detail::read_map_json_document(text, path.string(), diagnostics);
  }
  return parse_map(text, path.string(), *format, diagnostics);
}

Result<MapFormat> map_output_format(const std::filesystem::path& path,
                                    std::optional<MapFormat> format) {
  if (!format) format = map_format_from_extension(path);
  if (!format) {
    return Error{
        ErrorCode::kUnsupportedFormat,
        path.string() + ": cannot tell the format from the extension (use .json or .sewer)"};
  }
  if (!is_writable(*format)) return read_only(*format, path);
  return *format;
}

Result<void> write_map(const SewerMap& map, const std::filesystem::path& path,
                       std::optional<MapFormat> format) {
  const Result<MapFormat> writable = map_output_format(path, format);
  if (!writable.has_value()) return writable.error();
  std::ostringstream out;
  switch (*writable) {
    case MapFormat::kJson:
      write_map_json(map, out);
      break;
    case MapFormat::kAscii:
      if (Result<void> written = write_map_ascii(map, out); !written.has_value()) return written;
      break;
    case MapFormat::kSwmm:
    case MapFormat::kIsybau:
      return read_only(*writable, path);  // refused by map_output_format already
  }
  return write_text_file(path, out.str());
}

}  // namespace sewerplan
