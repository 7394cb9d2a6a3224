// SPDX-License-Identifier: MIT
#include "swmm_sections.h"

#include <algorithm>
#include <array>
#include <cctype>

#include "ascii_syntax.h"

namespace sewerplan::detail {
namespace {

// The sections of SWMM 5.2's input file (its manual, appendix D). Only some matter to sewerplan;
// the others are read past in silence.
constexpr auto kKnownSections = std::to_array<std::string_view>(
    {"TITLE",       "OPTIONS",     "REPORT",        "FILES",      "RAINGAGES",    "EVAPORATION",
     "TEMPERATURE", "ADJUSTMENTS", "SUBCATCHMENTS", "SUBAREAS",   "INFILTRATION", "LID_CONTROLS",
     "LID_USAGE",   "AQUIFERS",    "GROUNDWATER",   "GWF",        "SNOWPACKS",    "JUNCTIONS",
     "OUTFALLS",    "DIVIDERS",    "STORAGE",       "CONDUITS",   "PUMPS",        "ORIFICES",
     "WEIRS",       "OUTLETS",     "XSECTIONS",     "TRANSECTS",  "STREETS",      "INLETS",
     "INLET_USAGE", "LOSSES",      "CONTROLS",      "POLLUTANTS", "LANDUSES",     "COVERAGES",
     "LOADINGS",    "BUILDUP",     "WASHOFF",       "TREATMENT",  "INFLOWS",      "DWF",
     "RDII",        "HYDROGRAPHS", "CURVES",        "TIMESERIES", "PATTERNS",     "MAP",
     "COORDINATES", "VERTICES",    "POLYGONS",      "SYMBOLS",    "LABELS",       "BACKDROP",
     "TAGS",        "PROFILES",    "EVENTS"});

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

void split_fields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    if (is_space(line[i])) {
      ++i;
    } else if (line[i] == ';') {
      break;
    } else {
      const std::size_t start = i;
      while (i < line.size() && !is_space(line[i]) && line[i] != ';') ++i;
      fields.push_back(line.substr(start, i - start));
    }
  }
}

}  // namespace

std::span<const SwmmRow> SwmmSections::rows(std::string_view name) const {
  auto it = sections_.find(name);
  if (it == sections_.end()) return {};
  return it->second.rows;
}

std::optional<std::uint32_t> SwmmSections::header_line(std::string_view name) const {
  auto it = sections_.find(name);
  if (it == sections_.end()) return std::nullopt;
  return it->second.header_line;
}

SwmmSections split_swmm_sections(std::string_view text, const std::string& file_name,
                                 Diagnostics& diagnostics) {
  SwmmSections result;
  ascii_syntax::LineReader lines(text);
  std::vector<std::string_view> fields;
  SwmmSections::Section* current = nullptr;
  bool skipping = false;  // inside a section sewerplan does not know
  bool reported_stray = false;
  for (std::string_view line; lines.next(line);) {
    split_fields(line, fields);
    if (fields.empty()) continue;
    const std::string where = file_name + ":" + std::to_string(lines.line_number());
    if (fields[0].starts_with('[')) {
      const std::size_t close = fields[0].find(']');
      if (close == std::string_view::npos || fields.size() > 1 || close + 1 != fields[0].size()) {
        diagnostics.error(where, "malformed section header " + ascii_syntax::quoted(line));
        current = nullptr;
        skipping = true;
        continue;
      }
      const std::string name = to_upper(fields[0].substr(1, close - 1));
      skipping =
          std::find(kKnownSections.begin(), kKnownSections.end(), name) == kKnownSections.end();
      if (skipping) {
        diagnostics.warning(where, "unknown section [" + name + "], ignored");
        current = nullptr;
        continue;
      }
      auto [it, inserted] = result.sections_.try_emplace(name);
      if (inserted) it->second.header_line = lines.line_number();
      current = &it->second;
      continue;
    }
    if (current == nullptr) {
      if (!skipping && !reported_stray) {
        diagnostics.error(where, "data before the first [SECTION] header: " +
                                     ascii_syntax::quoted(line) + " (is this a SWMM .inp file?)");
        reported_stray = true;
      }
      continue;
    }
    current->rows.push_back({lines.line_number(), fields});
  }
  return result;
}

std::string to_upper(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](char c) {
    return static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  });
  return out;
}

std::optional<double> parse_swmm_number(std::string_view field) {
  if (field.starts_with('+')) field.remove_prefix(1);
  double value = 0;
  if (ascii_syntax::parse_number(field, value) != ascii_syntax::NumberError::kNone) {
    return std::nullopt;
  }
  return value;
}

}  // namespace sewerplan::detail
