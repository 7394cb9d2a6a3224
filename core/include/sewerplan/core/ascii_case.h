// SPDX-License-Identifier: MIT
// ASCII case folding, for the names that sewer and GIS formats compare without case: file
// extensions (".SHP"), GIS layer and field names, declared encodings ("ISO-8859-1"), PDDL names.
//
// Only 'A'..'Z' change; every other byte, UTF-8 sequences included, is kept. std::tolower would
// follow the C locale, which a host program may set (Python sets LC_CTYPE from the environment):
// in a Latin-1 locale it would change bytes of UTF-8 names, and results would differ by machine.
//
//   ascii_lower("Vw_QGEP_Reach.GPKG") == "vw_qgep_reach.gpkg"
//
// Thread safety: A pure function: call it from any number of threads.
#pragma once

#include <string>
#include <string_view>

namespace sewerplan {

// `text` with 'A'..'Z' in lower case. Runtime: O(size).
inline std::string ascii_lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

}  // namespace sewerplan
