// SPDX-License-Identifier: MIT
#include "sewerplan/core/check.h"

#include <cstdio>
#include <cstdlib>

namespace sewerplan::detail {

void check_failed(const char* condition, const char* file, int line, const char* message) {
  std::fprintf(stderr, "%s:%d: SEWER_CHECK(%s) failed: %s\n", file, line, condition, message);
  std::fflush(stderr);
  std::abort();
}

}  // namespace sewerplan::detail
