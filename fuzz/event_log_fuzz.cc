// SPDX-License-Identifier: MIT
// libFuzzer target: the event-log reader of `sewerplan render --log` (render/event_trace.h) against
// the AIS test bed; whatever it reads must draw.
#include <cstddef>
#include <cstdint>

#include "sewerplan/render/event_trace.h"
#include "sewerplan/render/svg_map.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sewerplan::Diagnostics diagnostics;
  const sewerplan::fuzz::Testbed& t = sewerplan::fuzz::testbed();
  auto trace = sewerplan::render::read_event_trace(sewerplan::fuzz::as_text(data, size),
                                                   "fuzz.jsonl", t.map, t.mission, diagnostics);
  if (trace.has_value()) {
    (void)sewerplan::render::render_map_svg(
        {.map = &t.map, .mission = &t.mission, .trace = &*trace});
  }
  return 0;
}
