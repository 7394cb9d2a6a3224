// SPDX-License-Identifier: MIT
// The module probe: a module for the tests only (sewerplan_module_probe.so in the build tree's
// lib/sewerplan, never installed) whose table is its own copy of the module loader
// (sewerplan/modules/module.h), as the loader linked into a shared object has: a module that
// loads another (none does today) or a program that is a shared object. The tests load the
// probe, then other modules through it.
#pragma once

#include <string>
#include <string_view>

#include "sewerplan/core/result.h"
#include "sewerplan/modules/module.h"

namespace sewerplan::test {

struct ModuleProbeTable {
  // load_module (sewerplan/modules/module.h), as the probe's copy of the loader runs it.
  Result<const void*> (*load_module)(std::string_view name, const std::string& stamp);
};

inline constexpr const char* kModuleProbeName = "module_probe";

inline std::string module_probe_stamp() {
  const modules::ModuleType types[] = {
      {"ModuleProbeTable", sizeof(ModuleProbeTable)},
      {"Result<const void*>", sizeof(Result<const void*>)},
      {"string", sizeof(std::string)},
      {"string_view", sizeof(std::string_view)},
  };
  return modules::module_abi_stamp(types);
}

}  // namespace sewerplan::test
