// SPDX-License-Identifier: MIT
// The module probe: a module for the tests only (sewerplan_module_probe.so in the build tree's
// lib/sewerplan, never installed) whose table is its own copy of core's module loader. A module
// that loads another has such a copy: the server module's station plans with fusion, which loads
// the OMPL module. The tests load the probe, then other modules through it.
#pragma once

#include <string>
#include <string_view>

#include "sewerplan/core/module.h"
#include "sewerplan/core/result.h"

namespace sewerplan::test {

struct ModuleProbeTable {
  // load_module (sewerplan/core/module.h), as the probe's copy of core runs it.
  Result<const void*> (*load_module)(std::string_view name, const std::string& stamp);
};

inline constexpr const char* kModuleProbeName = "module_probe";

inline std::string module_probe_stamp() {
  const ModuleType types[] = {
      {"ModuleProbeTable", sizeof(ModuleProbeTable)},
      {"Result<const void*>", sizeof(Result<const void*>)},
      {"string", sizeof(std::string)},
      {"string_view", sizeof(std::string_view)},
  };
  return module_abi_stamp(types);
}

}  // namespace sewerplan::test
