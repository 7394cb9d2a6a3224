// SPDX-License-Identifier: MIT
#include "output_format.h"

#include <string>

#include "sewerplan/core/ascii_case.h"
#include "sewerplan/core/check.h"

namespace sewerplan::cli {

Result<std::string_view> output_format(const std::filesystem::path& file, std::string_view option,
                                       std::span<const OutputExtension> accepted) {
  SEWER_CHECK(!accepted.empty(), "output_format: no format accepted");
  const std::string extension = ascii_lower(file.extension().string());
  if (extension.empty()) return accepted.front().format;
  std::string listed;  // ".svg or .png", ".json, .sewer or .xml"
  for (std::size_t i = 0; i < accepted.size(); ++i) {
    if (extension == accepted[i].extension) return accepted[i].format;
    if (i > 0) listed += i + 1 == accepted.size() ? " or " : ", ";
    listed += accepted[i].extension;
  }
  return Error{ErrorCode::kInvalidArgument, std::string(option) + " " + file.string() +
                                                ": unknown extension \"" +
                                                file.extension().string() + "\" (" + listed + ")"};
}

}  // namespace sewerplan::cli
