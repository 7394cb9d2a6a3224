// SPDX-License-Identifier: MIT
// The map's geometry fingerprint (passage_motion.h: map_geometry_fingerprint) computed under a stop
// condition, for the motion precompute (issue 14: a cancel within 1 ms). Formatting every manhole's
// numbers takes 1.3 ms on 1,000 manholes, so this asks `stop` every 64 manholes.
//
//   std::optional<std::string> fp = map_geometry_fingerprint(map, options.stop);
//   if (!fp) {
//     return stopped_error(options.stop.interrupted().value_or(SearchStatus::kCancelled), ...);
//   }
//
// Declared beside, not in, passage_motion.h only because nearly every file includes that one; the
// fingerprint itself is defined once, in passage_motion.cc. Thread safety: a pure function.
#pragma once

#include <optional>
#include <string>

#include "sewerplan/core/sewer_map.h"
#include "sewerplan/core/stop_condition.h"

namespace sewerplan {

// map_geometry_fingerprint(map), or nothing once `stop` fired (stop.interrupted() says why).
std::optional<std::string> map_geometry_fingerprint(const SewerMap& map, const StopCondition& stop);

}  // namespace sewerplan
