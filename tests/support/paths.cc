// SPDX-License-Identifier: MIT
#include "support/paths.h"

namespace sewerplan::testing {

std::filesystem::path source_dir() { return SEWERPLAN_SOURCE_DIR; }

}  // namespace sewerplan::testing
