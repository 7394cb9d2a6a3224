// SPDX-License-Identifier: MIT
// libFuzzer target: the motion table reader (passage_motion.h) against the AIS test bed.
#include <cstddef>
#include <cstdint>

#include "sewerplan/core/passage_motion.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sewerplan::Diagnostics diagnostics;
  const sewerplan::fuzz::Testbed& t = sewerplan::fuzz::testbed();
  (void)sewerplan::read_passage_motion_json(sewerplan::fuzz::as_text(data, size), "fuzz.json",
                                            t.map, diagnostics);
  return 0;
}
