// SPDX-License-Identifier: MIT
// Whole-file text I/O with errors that name the file and the system's reason.
//
//   Result<std::string> text = read_text_file("ais.json");
//   if (!text.has_value()) std::cerr << text.error().message;  // "cannot read ais.json: No such
//   ..."
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "sewerplan/core/result.h"

namespace sewerplan {

Result<std::string> read_text_file(const std::filesystem::path& path);

// Writes through a temporary file renamed into place, so a failed write leaves no half file.
Result<void> write_text_file(const std::filesystem::path& path, std::string_view text);

}  // namespace sewerplan
