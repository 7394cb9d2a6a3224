// SPDX-License-Identifier: MIT
// The server module (sewerplan/server/module.h) as `sewerplan serve` loads it, and as code in
// another module does: the station's own planning loads fusion's OMPL module from inside
// sewerplan_server.so, with the loader's copy in there, which must find the modules beside it.
#include <string>

#include <gtest/gtest.h>

#include "sewerplan/core/module.h"
#include "sewerplan/server/module.h"

#include "module_probe.h"

namespace sewerplan::server {
namespace {

TEST(ServerModuleTest, LoadsWithThisBuildsStamp) {
  const Result<const ModuleTable*> table =
      load_module_table<ModuleTable>(kModuleName, module_stamp());
  ASSERT_TRUE(table.has_value()) << table.error().message;
  EXPECT_NE((*table)->serve_until_signal, nullptr);
}

TEST(ServerModuleTest, IsFoundFromCodeInAnotherModule) {
  const Result<const test::ModuleProbeTable*> probe =
      load_module_table<test::ModuleProbeTable>(test::kModuleProbeName, test::module_probe_stamp());
  ASSERT_TRUE(probe.has_value()) << probe.error().message;
  const Result<const void*> through_probe = (*probe)->load_module(kModuleName, module_stamp());
  ASSERT_TRUE(through_probe.has_value()) << through_probe.error().message;
  const Result<const ModuleTable*> direct =
      load_module_table<ModuleTable>(kModuleName, module_stamp());
  ASSERT_TRUE(direct.has_value()) << direct.error().message;
  // One file, loaded once by the dynamic loader: the same table.
  EXPECT_EQ(*through_probe, static_cast<const void*>(*direct));
}

}  // namespace
}  // namespace sewerplan::server
