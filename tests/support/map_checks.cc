// SPDX-License-Identifier: MIT
#include "support/map_checks.h"

#include <gtest/gtest.h>

namespace sewerplan::testing {

const Slot& slot_of(const SewerMap& map, ManholeId m, std::string_view pipe) {
  for (const Slot& s : map.slots(m)) {
    if (map.pipe(s.pipe).name == pipe) return s;
  }
  ADD_FAILURE() << "manhole " << map.manhole(m).name << " has no slot for pipe " << pipe;
  static const Slot kNone;
  return kNone;
}

bool has_warning(const Diagnostics& diagnostics, std::string_view text) {
  for (const Diagnostic& d : diagnostics.all()) {
    if (d.severity == Severity::kWarning && d.message.find(text) != std::string::npos) return true;
  }
  return false;
}

}  // namespace sewerplan::testing
