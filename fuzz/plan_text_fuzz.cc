// SPDX-License-Identifier: MIT
// libFuzzer target: the plan text parser (domain/plan_text.h) against the AIS test bed and its
// paper mission.
#include <cstddef>
#include <cstdint>

#include "sewerplan/domain/plan_text.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sewerplan::Diagnostics diagnostics;
  const sewerplan::fuzz::Testbed& t = sewerplan::fuzz::testbed();
  (void)sewerplan::domain::parse_plan(sewerplan::fuzz::as_text(data, size), "fuzz.plan", t.map,
                                      t.mission, diagnostics);
  return 0;
}
