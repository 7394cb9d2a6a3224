// SPDX-License-Identifier: MIT
// Reading ISYBAU Zustandsdaten (inspection findings) from parsed XML. Private to core/src: used by
// the ISYBAU importer for findings in the map's own file, and by read_condition (condition.h)
// for a second file joined to a map.
//
// Each InspizierteAbwassertechnischeAnlage names an object (Objektbezeichnung) and its kind
// (Anlagentyp 1 Haltung; 2 Anschlussleitung and 3 Schacht are not pipes of the map: counted and
// left out). Of its OptischeInspektion elements the latest (Inspektionsdatum) counts, as does
// the latest of several entries for one object. Each RZustand below it is one finding:
// InspektionsKode, Charakterisierung1/2, Quantifizierung1/2Numerisch, and Station, measured from
// where the inspection began: Rohrleitung/Inspektionsrichtung "O" (with the flow, from the
// upstream node) or "U" (against it, from the downstream node).
#pragma once

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

// Appends the findings of `inspected` (InspizierteAbwassertechnischeAnlage elements, in document
// order) to `findings`, and each one's RZustand element to `elements`; FindingRecord::line is its
// index in `elements` + 1. Malformed fields are errors naming the element; fallbacks warnings.
void read_condition_records(std::span<const pugi::xml_node> inspected, const std::string& file,
                            Diagnostics& diagnostics, std::vector<FindingRecord>& findings,
                            std::vector<pugi::xml_node>& elements);

}  // namespace sewerplan::detail
