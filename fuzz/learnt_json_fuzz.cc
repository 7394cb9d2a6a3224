// SPDX-License-Identifier: MIT
// libFuzzer target: the learnt-file reader (executor/learnt.h: what a robot learnt, its hazard
// beliefs and the localisation filter's memory of junctions and mouths) against the AIS test
// bed. What it reads must be what a Replanner and the filter accept, and write back to an equal
// file.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "sewerplan/executor/learnt.h"
#include "sewerplan/localisation/topological_filter.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sewerplan::Diagnostics diagnostics;
  const sewerplan::fuzz::Testbed& t = sewerplan::fuzz::testbed();
  auto learnt = sewerplan::executor::read_learnt_json(sewerplan::fuzz::as_text(data, size),
                                                      "fuzz.json", t.map, diagnostics);
  if (!learnt.has_value()) return 0;
  // The reader checks every entry against the map; the filter's own check must agree.
  if (!sewerplan::localisation::check_memory(learnt->junctions, t.map).has_value()) std::abort();
  sewerplan::Diagnostics again;
  auto back = sewerplan::executor::read_learnt_json(
      sewerplan::executor::learnt_json(*learnt, t.map), "back.json", t.map, again);
  if (!back.has_value() || !(*back == *learnt)) std::abort();
  return 0;
}
