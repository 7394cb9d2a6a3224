// SPDX-License-Identifier: MIT
// libFuzzer target: the ISYBAU Zustandsdaten reader (condition.h) on any bytes, joined to the
// street network of datasets/isybau/.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <string>

#include "sewerplan/core/condition.h"
#include "sewerplan/core/map_io.h"

#include "fuzz_support.h"

namespace {

// Aborts if the network does not load: the fuzz target would test nothing.
const sewerplan::SewerMap& street() {
  static const sewerplan::SewerMap kStreet = [] {
    sewerplan::Diagnostics d;
    sewerplan::Result<sewerplan::SewerMap> map = sewerplan::read_map(
        std::string(SEWERPLAN_SOURCE_DIR) + "/datasets/isybau/street-2017.xml", d);
    if (!map.has_value()) {
      std::cerr << map.error() << '\n';
      std::abort();
    }
    return std::move(map).value();
  }();
  return kStreet;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sewerplan::Diagnostics diagnostics;
  (void)sewerplan::read_condition_isybau(street(), sewerplan::fuzz::as_text(data, size), "fuzz.xml",
                                         diagnostics);
  return 0;
}
