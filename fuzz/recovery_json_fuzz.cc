// SPDX-License-Identifier: MIT
// libFuzzer target: the recovery-settings JSON reader (executor/recovery.h).
#include <cstddef>
#include <cstdint>

#include "sewerplan/executor/recovery.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)sewerplan::executor::read_recovery_json(sewerplan::fuzz::as_text(data, size), "fuzz.json");
  return 0;
}
