// SPDX-License-Identifier: MIT
#include "sewerplan/core/clock.h"

#include <chrono>

namespace sewerplan {

double SteadyClock::now_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace sewerplan
