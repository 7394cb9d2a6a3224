// SPDX-License-Identifier: MIT
// The format of a file a command writes, told by the file's extension. Each option that writes
// more than one format has its table of the extensions it accepts (render -o: .svg and .png;
// --corrected-map: .json and .xml), the first being its default. A name with any other extension
// (`render -o map.pdf`) is refused before any work is done, with an error that names the option,
// the file and the extensions accepted, never written in a format its name does not say. A name
// without an extension (`-o /dev/stdout`, a FIFO, `-o picture`) gets the default.
//
// The map writers (convert, generate) tell a map's format by core/map_io.h's own table, with its
// own errors.
#pragma once

#include <filesystem>
#include <span>
#include <string_view>

#include "sewerplan/core/result.h"

namespace sewerplan::cli {

struct OutputExtension {
  std::string_view extension;  // with its dot, lower case: ".svg"
  std::string_view format;     // what the command calls the format: "svg"
};

// The format of `file` by its extension (compared without regard to ASCII case); the first of
// `accepted` when the file has no extension; else kInvalidArgument (a usage error) naming
// `option`, the file and the extensions accepted: `render -o map.pdf: unknown extension ".pdf"
// (.svg or .png)`.
Result<std::string_view> output_format(const std::filesystem::path& file, std::string_view option,
                                       std::span<const OutputExtension> accepted);

}  // namespace sewerplan::cli
