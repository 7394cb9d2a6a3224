// SPDX-License-Identifier: MIT
// --profile P on `render` and `export-geojson`: what that robot can drive of the map, from its
// exits (domain/driveability.h, the reasons `info --profile` prints), for the picture or the GIS
// layer to show.
#pragma once

#include <optional>
#include <string>

#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/driveability.h"

namespace sewerplan::cli {

// None when `profile` is empty. Errors: load_profile's (a built-in name or a profile JSON file),
// the message beginning "--profile: ".
Result<std::optional<domain::DriveabilityReport>> driveability_for_profile(
    const SewerMap& map, const std::string& profile);

}  // namespace sewerplan::cli
