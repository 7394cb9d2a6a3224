// SPDX-License-Identifier: MIT
// --crs AUTHORITY:CODE: the coordinate reference system of a map whose file does not name one
// (SWMM, the ASCII database, a generated city; core/crs.h). A map that names its own keeps it, and
// a --crs that contradicts it is an error rather than a silent relabelling of its coordinates.
#pragma once

#include <string>

#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace CLI {
class App;
}

namespace sewerplan::cli {

void add_crs_option(CLI::App& command, std::string& crs);

// `map` with the CRS of --crs `crs` (nothing to do when `crs` is empty). Errors (kInvalidArgument,
// the message beginning "--crs"): a text parse_crs rejects, a CRS other than the map's own.
Result<SewerMap> apply_crs_option(SewerMap map, const std::string& crs);

}  // namespace sewerplan::cli
