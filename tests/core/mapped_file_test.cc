// SPDX-License-Identifier: MIT
// The map reader's mapped file (core/mapped_file.h): what is mapped reads back byte for byte,
// and what is not mapped is left to read_text_file.
#include "sewerplan/core/mapped_file.h"

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include <unistd.h>

namespace sewerplan::detail {
namespace {

// A scratch directory of this test's own, removed with everything in it.
class ScratchDir {
 public:
  ScratchDir()
      : path_(std::filesystem::path(::testing::TempDir()) /
              ("sewerplan_mapped_file_" + std::to_string(::getpid()) + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name())) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

TEST(MappedFile, ReadsARegularFileByteForByteAndUnmapsOnClose) {
  ScratchDir dir;
  const auto path = dir.path() / "map.json";
  const std::string text =
      std::string("{\"manholes\": []}\n") + std::string(5000, ' ') + "\xc3\xa4";
  std::ofstream(path, std::ios::binary) << text;
  std::optional<MappedFile> file = MappedFile::open(path, 1);
  ASSERT_TRUE(file.has_value());
  EXPECT_EQ(file->text(), text);
  MappedFile moved = std::move(*file);
  EXPECT_TRUE(file->text().empty());
  EXPECT_EQ(moved.text(), text);
  moved.close();
  EXPECT_TRUE(moved.text().empty());
}

TEST(MappedFile, LeavesSmallEmptyMissingAndSpecialFilesToTheTextReader) {
  ScratchDir dir;
  const auto small = dir.path() / "small.json";
  std::ofstream(small) << "{}";
  EXPECT_FALSE(MappedFile::open(small).has_value()) << "below kMinMappedBytes";
  const auto empty = dir.path() / "empty.json";
  std::ofstream{empty};
  EXPECT_FALSE(MappedFile::open(empty, 0).has_value());
  EXPECT_FALSE(MappedFile::open(dir.path() / "missing.json", 0).has_value());
  EXPECT_FALSE(MappedFile::open(dir.path(), 0).has_value()) << "a directory";
  EXPECT_FALSE(MappedFile::open("/dev/null", 0).has_value());
}

}  // namespace
}  // namespace sewerplan::detail
