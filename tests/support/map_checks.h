// SPDX-License-Identifier: MIT
// Checks on maps read by the importers' tests: a manhole's slot for a pipe, and warnings.
#pragma once

#include <string_view>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::testing {

// The slot of `pipe` in manhole `m`; a test failure (and a default slot) if there is none.
const Slot& slot_of(const SewerMap& map, ManholeId m, std::string_view pipe);

// Whether a warning's message contains `text`.
bool has_warning(const Diagnostics& diagnostics, std::string_view text);

}  // namespace sewerplan::testing
