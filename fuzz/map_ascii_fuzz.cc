// SPDX-License-Identifier: MIT
// libFuzzer target: the ASCII sewer database reader (map_ascii.h) on any bytes.
#include <cstddef>
#include <cstdint>

#include "sewerplan/core/map_ascii.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sewerplan::Diagnostics diagnostics;
  (void)sewerplan::read_map_ascii(sewerplan::fuzz::as_text(data, size), "fuzz.sewer", diagnostics);
  return 0;
}
