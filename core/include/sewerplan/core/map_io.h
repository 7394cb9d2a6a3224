// SPDX-License-Identifier: MIT
// Reading and writing maps in any format sewerplan knows, chosen by file name or content.
//
// Formats: the native JSON map (map_json.h, ".json") and the paper's ASCII database
// (map_ascii.h, ".sewer"). A file with another extension is recognised by its content: '{' opens
// a JSON map, a "sewerdb" line an ASCII database.
//
//   Diagnostics diagnostics;
//   Result<SewerMap> map = read_map("datasets/ais-testbed/map.json", diagnostics);
//   Result<void> written = write_map(*map, "ais.sewer");  // format from the extension
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

enum class MapFormat { kJson, kAscii };

std::string_view to_string(MapFormat format);
// "json" or "ascii".
std::optional<MapFormat> map_format_from_name(std::string_view name);
// From the extension (".json", ".sewer"), if it names a format.
std::optional<MapFormat> map_format_from_extension(const std::filesystem::path& path);

// From the extension, else from the content; an error names the file if neither tells.
Result<MapFormat> detect_map_format(const std::filesystem::path& path, std::string_view text);

Result<SewerMap> parse_map(std::string_view text, const std::string& file_name, MapFormat format,
                           Diagnostics& diagnostics);

Result<SewerMap> read_map(const std::filesystem::path& path, Diagnostics& diagnostics);

// Without a format, the extension decides (an unknown extension is an error).
Result<void> write_map(const SewerMap& map, const std::filesystem::path& path,
                       std::optional<MapFormat> format = std::nullopt);

}  // namespace sewerplan
