// SPDX-License-Identifier: MIT
// A module built only for the module loader's tests (tests/modules/module_test.cc): its table and
// stamp. Built twice (tests/CMakeLists.txt): as module "fixture", with this build's stamp, and as
// "fixture_other", whose stamp names another build.
#pragma once

#include <string>

#include "sewerplan/modules/module.h"

namespace sewerplan::test {

struct FixtureTable {
  int (*answer)();
};

inline std::string fixture_stamp() {
  const modules::ModuleType types[] = {{"FixtureTable", sizeof(FixtureTable)}};
  return modules::module_abi_stamp(types);
}

}  // namespace sewerplan::test
