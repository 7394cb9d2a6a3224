// SPDX-License-Identifier: MIT
// The native JSON map reader's two paths, for map_io.cc to free the text before building.
//
// Private to core. read_map_json (map_json.h) tries the fast path first: one pass over the text
// with no document tree (json_scan.h), for a well-formed map whose every field is known and of the
// right type; it gives the records, unvalidated, in a MapBuilder. Anything else (a syntax error, a
// wrong type, an unknown field, a string with an escape) gives nullopt, and the document reader
// then reads the text and reports every problem with its JSON path. Both give the same map and
// the same diagnostics for a map the fast path reads.
//
//   if (auto builder = read_map_json_fast(text, "map.json")) {
//     text = {};  // the records hold their own copies
//     return std::move(*builder).build(diagnostics);
//   }
//   return read_map_json_document(text, "map.json", diagnostics);
//
// Thread safety: both share nothing.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/map_builder.h"
#include "sewerplan/core/result.h"

namespace sewerplan::detail {

std::optional<MapBuilder> read_map_json_fast(std::string_view text, const std::string& file_name);

Result<SewerMap> read_map_json_document(std::string_view text, const std::string& file_name,
                                        Diagnostics& diagnostics);

}  // namespace sewerplan::detail
