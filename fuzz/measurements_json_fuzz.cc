// SPDX-License-Identifier: MIT
// libFuzzer target: the measurements JSON reader (core/measurements_json.h) against the AIS test
// bed; what it reads must write back to equal measurements, from which discrepancies and a
// corrected map are derived without a crash (the corrected map may fail to validate: an error).
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "sewerplan/core/measurements_json.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sewerplan::Diagnostics diagnostics;
  const sewerplan::fuzz::Testbed& t = sewerplan::fuzz::testbed();
  auto m = sewerplan::read_measurements_json(sewerplan::fuzz::as_text(data, size), "fuzz.json",
                                             t.map, diagnostics);
  if (!m.has_value()) return 0;
  sewerplan::Diagnostics again;
  auto back = sewerplan::read_measurements_json(sewerplan::measurements_json(*m, t.map),
                                                "back.json", t.map, again);
  if (!back.has_value() || !(*back == *m)) std::abort();
  (void)sewerplan::discrepancies(*m, t.map);
  (void)sewerplan::corrected_map(t.map, *m);
  return 0;
}
