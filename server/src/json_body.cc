// SPDX-License-Identifier: MIT
#include "json_body.h"

#include <optional>
#include <string>
#include <utility>

namespace sewerplan::server {

Result<JsonDocument> parse_json_body(std::string_view text) {
  Diagnostics diagnostics;
  std::optional<JsonDocument> doc =
      JsonDocument::parse(text, kBodyFile, diagnostics, kMaxBodyDepth);
  if (doc &&
      report_repeated_keys(doc->root(), "$", kBodyFile, diagnostics, kMaxRepeatsNamed) == 0) {
    return std::move(*doc);
  }
  return Error{ErrorCode::kParse, diagnostics.error_summary()};
}

}  // namespace sewerplan::server
