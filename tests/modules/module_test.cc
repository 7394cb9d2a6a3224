// SPDX-License-Identifier: MIT
// The module loader (sewerplan/modules/module.h) on fixture modules built beside the tests
// (tests/modules/module_fixture/, SEWERPLAN_TEST_MODULE_DIR).
#include "sewerplan/modules/module.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "module_fixture/fixture.h"

namespace sewerplan::modules {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

// Points the loader at the fixtures' directory for one test.
class ModuleTest : public ::testing::Test {
 protected:
  void SetUp() override { setenv("SEWERPLAN_MODULE_DIR", SEWERPLAN_TEST_MODULE_DIR, 1); }
  void TearDown() override { unsetenv("SEWERPLAN_MODULE_DIR"); }
};

TEST_F(ModuleTest, LoadsAModuleOfThisBuildOnceAndCallsItsTable) {
  Result<const test::FixtureTable*> table =
      load_module_table<test::FixtureTable>("fixture", test::fixture_stamp());
  ASSERT_TRUE(table.has_value()) << table.error().message;
  EXPECT_EQ((*table)->answer(), 42);
  Result<const test::FixtureTable*> again =
      load_module_table<test::FixtureTable>("fixture", test::fixture_stamp());
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(*again, *table);
}

// The header promises any thread may ask: eight at once get the one table, loaded once.
TEST_F(ModuleTest, ThreadsAskingAtOnceGetTheSameTable) {
  std::vector<const void*> tables(8, nullptr);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < tables.size(); ++i) {
    threads.emplace_back([&tables, i] {
      Result<const void*> t = load_module("fixture", test::fixture_stamp());
      if (t.has_value()) tables[i] = *t;
    });
  }
  for (std::thread& t : threads) t.join();
  ASSERT_NE(tables[0], nullptr);
  for (const void* t : tables) EXPECT_EQ(t, tables[0]);
}

TEST_F(ModuleTest, RefusesAModuleOfAnotherBuildNamingBothStamps) {
  Result<const void*> table = load_module("fixture_other", test::fixture_stamp());
  ASSERT_FALSE(table.has_value());
  EXPECT_EQ(table.error().code, ErrorCode::kUnsupportedFormat);
  EXPECT_THAT(table.error().message,
              AllOf(HasSubstr("the fixture_other module "),
                    HasSubstr("sewerplan_fixture_other.so is of another build or configuration"),
                    HasSubstr("its ABI stamp: \"sewerplan 0.0.0 build 0000000000000000"),
                    HasSubstr("this sewerplan's: \"" + test::fixture_stamp() + "\"")));
  // Remembered: the same answer without loading again.
  Result<const void*> again = load_module("fixture_other", test::fixture_stamp());
  ASSERT_FALSE(again.has_value());
  EXPECT_EQ(again.error(), table.error());
}

TEST_F(ModuleTest, NamesWhereItLookedForAMissingModule) {
  Result<const void*> table = load_module("nonesuch", "any");
  ASSERT_FALSE(table.has_value());
  EXPECT_EQ(table.error().code, ErrorCode::kUnsupportedFormat);
  EXPECT_EQ(table.error().message, std::string("the nonesuch module is missing (looked for ") +
                                       SEWERPLAN_TEST_MODULE_DIR + "/sewerplan_nonesuch.so)");
}

TEST_F(ModuleTest, AFileThatIsNoSharedObjectIsAnErrorWithTheLoadersReason) {
  const std::string dir = ::testing::TempDir() + "sewerplan_module_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/sewerplan_broken.so") << "not an ELF file\n";
  setenv("SEWERPLAN_MODULE_DIR", dir.c_str(), 1);
  Result<const void*> table = load_module("broken", "any");
  ASSERT_FALSE(table.has_value());
  EXPECT_EQ(table.error().code, ErrorCode::kUnsupportedFormat);
  EXPECT_THAT(table.error().message, AllOf(HasSubstr("the broken module " + dir +
                                                     "/sewerplan_broken.so cannot be loaded: "),
                                           HasSubstr("sewerplan_broken.so")));
}

// A stale module of another install earlier on the path (here: a file without this name's entry
// symbols) does not hide the right one later.
TEST_F(ModuleTest, AStaleModuleEarlierOnThePathDoesNotHideTheRightOne) {
  const std::string stale = ::testing::TempDir() + "sewerplan_module_stale";
  std::filesystem::create_directories(stale);
  std::filesystem::copy_file(std::string(SEWERPLAN_TEST_MODULE_DIR) + "/sewerplan_fixture.so",
                             stale + "/sewerplan_fixture_late.so",
                             std::filesystem::copy_options::overwrite_existing);
  setenv("SEWERPLAN_MODULE_DIR", (stale + ":" + SEWERPLAN_TEST_MODULE_DIR).c_str(), 1);
  Result<const test::FixtureTable*> table =
      load_module_table<test::FixtureTable>("fixture_late", test::fixture_stamp());
  ASSERT_TRUE(table.has_value()) << table.error().message;
  EXPECT_EQ((*table)->answer(), 42);
}

// When none loads, the error is the first one found's, not "missing".
TEST_F(ModuleTest, WhenNoneLoadsTheErrorIsTheFirstFoundsReason) {
  const std::string broken = ::testing::TempDir() + "sewerplan_module_first";
  std::filesystem::create_directories(broken);
  std::ofstream(broken + "/sewerplan_fixture_bad.so") << "not an ELF file\n";
  setenv("SEWERPLAN_MODULE_DIR", (broken + ":" + SEWERPLAN_TEST_MODULE_DIR).c_str(), 1);
  Result<const void*> table = load_module("fixture_bad", "any");
  ASSERT_FALSE(table.has_value());
  EXPECT_THAT(table.error().message, HasSubstr("the fixture_bad module " + broken +
                                               "/sewerplan_fixture_bad.so cannot be "
                                               "loaded: "));
}

TEST_F(ModuleTest, RefusesANameThatIsNoModuleName) {
  for (const char* name : {"", "../fixture", "Fixture", "a b"}) {
    Result<const void*> table = load_module(name, "any");
    ASSERT_FALSE(table.has_value()) << name;
    EXPECT_EQ(table.error().code, ErrorCode::kInvalidArgument) << name;
  }
}

TEST(ModuleSearch, LooksWhereTheBuildTreeAndTheInstallPutModules) {
  unsetenv("SEWERPLAN_MODULE_DIR");
  const std::vector<std::filesystem::path> dirs = module_search_dirs();
  ASSERT_FALSE(dirs.empty());
  // The test program is in the build tree's tests/: its lib/sewerplan is one level up.
  const std::filesystem::path own = std::filesystem::read_symlink("/proc/self/exe").parent_path();
  EXPECT_NE(
      std::find(dirs.begin(), dirs.end(), (own / ".." / "lib" / "sewerplan").lexically_normal()),
      dirs.end());
  EXPECT_TRUE(dirs.back().is_absolute());
  EXPECT_EQ(dirs.back().filename(), "sewerplan");
  setenv("SEWERPLAN_MODULE_DIR", "/somewhere/else", 1);
  EXPECT_EQ(module_search_dirs(), std::vector<std::filesystem::path>{"/somewhere/else"});
  setenv("SEWERPLAN_MODULE_DIR", "/a::/b:", 1);  // a list, as PATH; empty entries skipped
  EXPECT_EQ(module_search_dirs(), (std::vector<std::filesystem::path>{"/a", "/b"}));
  unsetenv("SEWERPLAN_MODULE_DIR");
}

}  // namespace
}  // namespace sewerplan::modules
