// SPDX-License-Identifier: MIT
// The server module (sewerplan/modules/server_table.h) as `sewerplan serve` loads it, and as the
// loader linked into another shared object (the module probe, module_probe.h) does: that copy must
// find the modules beside it.
#include <string>

#include <gtest/gtest.h>

#include "sewerplan/modules/module.h"
#include "sewerplan/modules/server_table.h"

#include "module_probe.h"

namespace sewerplan::modules {
namespace {

TEST(ServerModuleTest, LoadsWithThisBuildsStamp) {
  const Result<const ServerTable*> table =
      load_module_table<ServerTable>(kServerModule, server_stamp());
  ASSERT_TRUE(table.has_value()) << table.error().message;
  EXPECT_NE((*table)->serve_until_signal, nullptr);
}

TEST(ServerModuleTest, IsFoundFromCodeInAnotherModule) {
  const Result<const test::ModuleProbeTable*> probe =
      load_module_table<test::ModuleProbeTable>(test::kModuleProbeName, test::module_probe_stamp());
  ASSERT_TRUE(probe.has_value()) << probe.error().message;
  const Result<const void*> through_probe = (*probe)->load_module(kServerModule, server_stamp());
  ASSERT_TRUE(through_probe.has_value()) << through_probe.error().message;
  const Result<const ServerTable*> direct =
      load_module_table<ServerTable>(kServerModule, server_stamp());
  ASSERT_TRUE(direct.has_value()) << direct.error().message;
  // One file, loaded once by the dynamic loader: the same table.
  EXPECT_EQ(*through_probe, static_cast<const void*>(*direct));
}

}  // namespace
}  // namespace sewerplan::modules
