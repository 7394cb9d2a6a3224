// SPDX-License-Identifier: MIT
// Condition data: the findings of sewer inspections, joined to a map.
//
// German municipalities inspect their sewers by camera and record every finding in the codes of
// DIN EN 13508-2 (roots BBA, deposits BBB and BBC, obstacles BBE, deformation BAA, collapse BAC,
// displaced joints BAJ, intruding connections BAG, ...), exchanged as ISYBAU Zustandsdaten:
// InspizierteAbwassertechnischeAnlage objects, named like the Haltungen of the Stammdaten. They
// come inside the map's own ISYBAU file (read_map_isybau reads them) or as a second file, joined
// to a map read before by the pipes' names: read_condition. Each finding lands in the map
// (SewerMap::findings) at its offset from the pipe's upstream end, whichever way the inspection
// ran. What a finding means for a robot is the risk table's business (condition_risk.h).
// Elements, fallbacks and errors: docs/formats/isybau.md, "Zustandsdaten".
//
//   Diagnostics d;
//   Result<SewerMap> map = read_map("street.xml", d);
//   if (map.has_value()) map = read_condition(std::move(*map), "street-zustand.xml", d);
//
// Thread safety: The readers share nothing: call them from any number of threads, each with
// its own Diagnostics.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

// `map` with the findings of the ISYBAU Zustandsdaten in `text` (the file `file_name`). Findings
// naming no pipe of the map, or lying off their pipe, are warnings (left out, or clamped onto it);
// XML that is not well-formed, a file that is not ISYBAU (DWA-M 150 and INTERLIS files are named
// as such), a file without any inspected object and malformed fields are kParse errors. Never
// throws. Runtime: O(size of the text + findings x log findings).
Result<SewerMap> read_condition_isybau(SewerMap map, std::string_view text,
                                       const std::string& file_name, Diagnostics& diagnostics);

// The same for a file; an unreadable file is a kIo error naming it.
Result<SewerMap> read_condition(SewerMap map, const std::filesystem::path& path,
                                Diagnostics& diagnostics);

// The name DIN EN 13508-2 gives a pipe's main code ("BBA": "roots", "BCD": "start node"), for
// people reading a finding (the operator station's hover, reports); empty for a code it does not
// list (a manhole's D.. codes, a typo). Runtime: O(codes).
std::string_view finding_code_name(std::string_view code);

}  // namespace sewerplan
