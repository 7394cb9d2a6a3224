// SPDX-License-Identifier: MIT
#include "crs_option.h"

#include <CLI/CLI.hpp>

#include "sewerplan/core/crs.h"
#include "sewerplan/core/map_builder.h"

namespace sewerplan::cli {

void add_crs_option(CLI::App& command, std::string& crs) {
  command.add_option("--crs", crs,
                     "Coordinate reference system of the map's x and y when its file names none "
                     "(SWMM, .sewer, generated), e.g. EPSG:25832");
}

Result<SewerMap> apply_crs_option(SewerMap map, const std::string& crs) {
  if (crs.empty()) return map;
  Result<Crs> given = parse_crs(crs);
  if (!given.has_value()) {
    return Error{ErrorCode::kInvalidArgument, "--crs: " + given.error().message};
  }
  if (map.crs() && *map.crs() != *given) {
    return Error{
        ErrorCode::kInvalidArgument,
        "--crs " + given->to_string() + ": the map names its own CRS, " + map.crs()->to_string()};
  }
  return MapBuilder::with_crs(std::move(map), std::move(*given));
}

}  // namespace sewerplan::cli
