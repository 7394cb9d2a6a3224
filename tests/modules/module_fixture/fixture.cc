// SPDX-License-Identifier: MIT
// The fixture module's two entry symbols (fixture.h). SEWERPLAN_FIXTURE_NAME is its name;
// SEWERPLAN_FIXTURE_OTHER_BUILD makes its stamp one of another build.
#include "fixture.h"

#include <string>

#define SEWERPLAN_FIXTURE_CAT(a, b, c) a##b##c
#define SEWERPLAN_FIXTURE_SYMBOL(name, suffix) SEWERPLAN_FIXTURE_CAT(sewerplan_, name, suffix)

namespace {

int answer() { return 42; }

const sewerplan::test::FixtureTable kTable{.answer = &answer};

}  // namespace

extern "C" __attribute__((visibility("default"))) const char* SEWERPLAN_FIXTURE_SYMBOL(
    SEWERPLAN_FIXTURE_NAME, _module_stamp)() {
#ifdef SEWERPLAN_FIXTURE_OTHER_BUILD
  static const std::string stamp = "sewerplan 0.0.0 build 0000000000000000; sizes FixtureTable 8";
#else
  static const std::string stamp = sewerplan::test::fixture_stamp();
#endif
  return stamp.c_str();
}

extern "C" __attribute__((visibility("default"))) const void* SEWERPLAN_FIXTURE_SYMBOL(
    SEWERPLAN_FIXTURE_NAME, _module)() {
  return &kTable;
}
