// SPDX-License-Identifier: MIT
// libFuzzer target: the native JSON map reader (map_json.h) on any bytes.
#include <cstddef>
#include <cstdint>

#include "sewerplan/core/map_json.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sewerplan::Diagnostics diagnostics;
  (void)sewerplan::read_map_json(sewerplan::fuzz::as_text(data, size), "fuzz.json", diagnostics);
  return 0;
}
