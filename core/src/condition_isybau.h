// SPDX-License-Identifier: MIT
// Reading ISYBAU Zustandsdaten (inspection findings) from parsed XML. Private to core/src: used by
// the ISYBAU importer for findings in the map's own file, and by read_condition (condition.h)
// for a second file joined to a map.
//
// Each InspizierteAbwassertechnischeAnlage names an object (Objektbezeichnung) and its kind
// (Anlagentyp 1 Haltung; 2 Anschlussleitung and 3 Schacht are not pipes of the map: counted and
// left out). Each RZustand below its OptischeInspektion elements is one finding: InspektionsKode,
// Charakterisierung1/2, Quantifizierung1/2Numerisch, and Station, measured from where the
// inspection began: Rohrleitung/Inspektionsrichtung "O" (with the flow, from the upstream node)
// or "U" (against it, from the downstream node). Every inspection of a Haltung (over all entries
// for it) covers a stretch: from where it began to its farthest station or Inspektionslaenge, the
// whole pipe when it reached the far node (BCE) without being abandoned (BDC). A finding stands
// unless a later inspection (Inspektionsdatum, then Uhrzeit) covered its place: inspections from
// the two ends at one date and time (the camera could not pass) complement each other.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <pugixml.hpp>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/map_builder.h"

namespace sewerplan::detail {

// Appends every element below `node` named `name` (not looking inside those) to `out`.
void collect(pugi::xml_node node, std::string_view name, std::vector<pugi::xml_node>& out);

// The length of the map's pipe `name` (the length that findings' stations are measured along);
// none if the map has no such pipe.
using PipeLength = std::function<std::optional<double>(const std::string& name)>;

// Appends the findings of `inspected` (InspizierteAbwassertechnischeAnlage elements, in document
// order) to `findings`, and each one's RZustand element to `elements`; FindingRecord::line is its
// index in `elements` + 1. Malformed fields are errors naming the element; fallbacks warnings.
// `pipe_length` places inspections against the flow on the pipe, to tell which stretch each
// covered.
void read_condition_records(std::span<const pugi::xml_node> inspected, const std::string& file,
                            Diagnostics& diagnostics, const PipeLength& pipe_length,
                            std::vector<FindingRecord>& findings,
                            std::vector<pugi::xml_node>& elements);

}  // namespace sewerplan::detail
