// SPDX-License-Identifier: MIT
// libFuzzer target: the candump log reader (hal/can/candump.h); every record read must be written
// back as a line that reads to the same frame.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>

#include "sewerplan/hal/can/candump.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in{std::string(sewerplan::fuzz::as_text(data, size))};
  const auto records = sewerplan::hal::read_candump(in, "fuzz.log");
  if (!records.has_value()) return 0;
  for (const sewerplan::hal::CandumpRecord& r : *records) {
    const auto back = sewerplan::hal::parse_candump_line(sewerplan::hal::candump_line(r));
    if (!back.has_value() || !(back->frame == r.frame) || back->interface != r.interface) {
      std::abort();
    }
  }
  return 0;
}
