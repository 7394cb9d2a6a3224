// SPDX-License-Identifier: MIT
// libFuzzer target: the event-log reader (executor/event_json.h) and, on it, the reader of
// `sewerplan render --log` (render/event_trace.h) against the AIS test bed. Whatever the log reader
// reads must write back to lines that read as the same events; whatever the trace reads must draw.
#include <cstddef>
#include <cstdint>
#include <string>

#include "sewerplan/core/check.h"
#include "sewerplan/executor/event_json.h"
#include "sewerplan/render/event_trace.h"
#include "sewerplan/render/map_picture.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = sewerplan::fuzz::as_text(data, size);
  sewerplan::Diagnostics diagnostics;
  auto events = sewerplan::executor::read_event_log(text, "fuzz.jsonl", diagnostics);
  if (events.has_value()) {
    std::string written;
    for (const auto& e : *events) written += sewerplan::executor::to_json_line(e) + '\n';
    sewerplan::Diagnostics again;
    auto reread = sewerplan::executor::read_event_log(written, "written.jsonl", again);
    SEWER_CHECK(reread.has_value() && *reread == *events,
                "an event log read does not read back the same when written");
  }
  const sewerplan::fuzz::Testbed& t = sewerplan::fuzz::testbed();
  sewerplan::Diagnostics trace_diagnostics;
  auto trace =
      sewerplan::render::read_event_trace(text, "fuzz.jsonl", t.map, t.mission, trace_diagnostics);
  if (trace.has_value()) {
    (void)sewerplan::render::render_map_svg(
        {.map = &t.map, .mission = &t.mission, .trace = &*trace});
  }
  return 0;
}
