// SPDX-License-Identifier: MIT
// libFuzzer target: the fault-scenario JSON reader (hal/fault_scenario.h) against the AIS test
// bed; what it reads must validate and write back to an equal scenario.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "sewerplan/hal/fault_scenario.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sewerplan::Diagnostics diagnostics;
  const sewerplan::fuzz::Testbed& t = sewerplan::fuzz::testbed();
  auto faults = sewerplan::hal::read_faults_json(sewerplan::fuzz::as_text(data, size), "fuzz.json",
                                                 t.map, diagnostics);
  if (!faults.has_value()) return 0;
  if (!sewerplan::hal::validate_faults(*faults, t.map).has_value()) std::abort();
  sewerplan::Diagnostics again;
  auto back = sewerplan::hal::read_faults_json(sewerplan::hal::faults_json(*faults, t.map),
                                               "back.json", t.map, again);
  if (!back.has_value() || !(*back == *faults)) std::abort();
  return 0;
}
