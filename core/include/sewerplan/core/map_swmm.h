// SPDX-License-Identifier: MIT
// Importing EPA SWMM 5 input files (.inp): the hydraulic models many towns keep of their sewers.
//
// SWMM (the US EPA's Storm Water Management Model) describes a sewer as nodes ([JUNCTIONS],
// [OUTFALLS], [STORAGE], [DIVIDERS]) joined by links; its conduits ([CONDUITS] with their
// [XSECTIONS]) are the pipes a robot can drive. read_map_swmm turns each node into a manhole and
// each conduit into a pipe, in metres whatever the file's units ([OPTIONS] FLOW_UNITS: CFS, GPM,
// MGD mean feet; CMS, LPS, MLD metres). Each pipe end's invert, from the node's invert and the
// conduit's offsets (LINK_OFFSETS DEPTH or ELEVATION), is its slot's invert, so the steps between
// pipes in a manhole are the file's; each slot's azimuth is the direction of the conduit's first
// segment leaving the node ([COORDINATES], through [VERTICES]).
//
// What SWMM does not say gets a documented default, each counted in one warning: manhole
// diameters (from a [STORAGE] node's constant plan area when it has one, else
// SwmmImportOptions::manhole_diameter_m), and which manholes are exits (every node but the
// outfalls, which discharge into open water; a mission may choose its own, mission-json.md).
// Pumps, orifices, weirs and outlets are not drivable and are left out, counted. The mapping field
// by field, with every warning and error: docs/formats/swmm.md.
//
//   Diagnostics diagnostics;
//   Result<SewerMap> map = read_map_swmm(text, "datasets/swmm/epa-example1.inp", diagnostics);
//   if (!map.has_value()) std::cerr << map.error();  // kParse or kInvalidMap, naming file:line
//
// Thread safety: The importer shares nothing: call it from any number of threads, each with its own
// Diagnostics.
#pragma once

#include <string>
#include <string_view>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

struct SwmmImportOptions {
  // The diameter of manholes whose size the file does not give, in metres (> 0).
  double manhole_diameter_m = 1.0;
};

// Reads a map from `text`, the content of the SWMM input file `file_name` (its stem names the
// map). Errors in rows (too few fields, a field that is not a number, an unknown shape, units
// given twice and differently) are each reported as "file:line" and then reading fails with
// kParse; otherwise the network goes to MapBuilder, whose errors (unknown nodes, duplicate names,
// non-positive lengths, ...) fail with kInvalidMap at the row concerned. Never throws, whatever
// the input. Runtime: O(n log n) in the size of the text.
Result<SewerMap> read_map_swmm(std::string_view text, const std::string& file_name,
                               Diagnostics& diagnostics, const SwmmImportOptions& options = {});

}  // namespace sewerplan
