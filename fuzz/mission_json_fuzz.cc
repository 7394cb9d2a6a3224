// SPDX-License-Identifier: MIT
// libFuzzer target: the mission JSON reader (mission.h) against the AIS test bed.
#include <cstddef>
#include <cstdint>

#include "sewerplan/core/mission.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sewerplan::Diagnostics diagnostics;
  const sewerplan::fuzz::Testbed& t = sewerplan::fuzz::testbed();
  (void)sewerplan::read_mission_json(sewerplan::fuzz::as_text(data, size), "fuzz.json", t.map,
                                     diagnostics);
  return 0;
}
