// SPDX-License-Identifier: MIT
// The lexical layer of the EPA SWMM 5 input file (map_swmm.h): sections, rows, fields. Private to
// core/src.
//
// A SWMM .inp file is a list of sections, each opened by a line "[NAME]" (case-insensitive) and
// holding rows of white-space separated fields; ';' starts a comment to the end of the line. Rows
// are kept with their line numbers so that every diagnostic names "file:line". Sections sewerplan
// does not know are reported once each as a warning; rows before the first section are errors.
//
//   SwmmSections s = split_swmm_sections(text, "net.inp", diagnostics);
//   for (const SwmmRow& row : s.rows("JUNCTIONS")) use(row.fields[0], row.line);
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/diagnostics.h"

namespace sewerplan::detail {

struct SwmmRow {
  std::uint32_t line = 0;
  std::vector<std::string_view> fields;  // views into the file's text
};

class SwmmSections {
 public:
  // The rows of section `name` (upper case, without brackets), in file order; empty if absent.
  std::span<const SwmmRow> rows(std::string_view name) const;
  // The line of the section's header, if the file has the section.
  std::optional<std::uint32_t> header_line(std::string_view name) const;

 private:
  friend SwmmSections split_swmm_sections(std::string_view, const std::string&, Diagnostics&);
  struct Section {
    std::uint32_t header_line = 0;
    std::vector<SwmmRow> rows;
  };
  std::map<std::string, Section, std::less<>> sections_;
};

// Splits `text` into sections. A section given twice continues where it left off (SWMM allows
// it). Never throws.
SwmmSections split_swmm_sections(std::string_view text, const std::string& file_name,
                                 Diagnostics& diagnostics);

// `s` in ASCII upper case: SWMM's keywords and section names are case-insensitive.
std::string to_upper(std::string_view s);

// Reads a decimal number as SWMM writes them ("12", "-0.5", "+3", "1e-3", ".5"); nullopt if the
// field is not a finite number.
std::optional<double> parse_swmm_number(std::string_view field);

}  // namespace sewerplan::detail
