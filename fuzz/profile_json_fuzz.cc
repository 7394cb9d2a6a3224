// SPDX-License-Identifier: MIT
// libFuzzer target: the robot-profile JSON reader (core/robot_profile.h).
#include <cstddef>
#include <cstdint>

#include "sewerplan/core/robot_profile.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sewerplan::Diagnostics diagnostics;
  (void)sewerplan::read_profile_json(sewerplan::fuzz::as_text(data, size), "fuzz.json",
                                     diagnostics);
  return 0;
}
