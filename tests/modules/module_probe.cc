// SPDX-License-Identifier: MIT
// The module probe's two exported symbols (module_probe.h).
#include "module_probe.h"

namespace sewerplan::test {
namespace {

const ModuleProbeTable kTable{.load_module = &sewerplan::modules::load_module};

}  // namespace
}  // namespace sewerplan::test

extern "C" __attribute__((visibility("default"))) const char*
sewerplan_module_probe_module_stamp() {
  static const std::string stamp = sewerplan::test::module_probe_stamp();
  return stamp.c_str();
}

extern "C" __attribute__((visibility("default"))) const void* sewerplan_module_probe_module() {
  return &sewerplan::test::kTable;
}
