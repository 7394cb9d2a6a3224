// SPDX-License-Identifier: MIT
// libFuzzer target: the ISYBAU XML importer (map_isybau.h) on any bytes.
#include <cstddef>
#include <cstdint>

#include "sewerplan/core/map_isybau.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sewerplan::Diagnostics diagnostics;
  (void)sewerplan::read_map_isybau(sewerplan::fuzz::as_text(data, size), "fuzz.xml", diagnostics);
  return 0;
}
