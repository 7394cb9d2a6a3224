// SPDX-License-Identifier: MIT
// libFuzzer target: the SWMM importer (map_swmm.h) on any bytes.
#include <cstddef>
#include <cstdint>

#include "sewerplan/core/map_swmm.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sewerplan::Diagnostics diagnostics;
  (void)sewerplan::read_map_swmm(sewerplan::fuzz::as_text(data, size), "fuzz.inp", diagnostics);
  return 0;
}
