// SPDX-License-Identifier: MIT
// Issue 31: every text reader skips a UTF-8 byte-order mark and reads UTF-16 with one (as Windows
// editors save files), by path, whatever the format: maps (JSON, the ASCII database, SWMM,
// ISYBAU), missions, Zustandsdaten, risk tables, and every file read through read_text_file.
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/condition.h"
#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/text_file.h"

#include "support/paths.h"

namespace sewerplan {
namespace {

using ::testing::HasSubstr;

// `utf8` (code points below U+10000) in UTF-16LE, with its byte-order mark.
std::string utf16le(std::string_view utf8) {
  std::string out("\xFF\xFE", 2);
  auto byte = [&](std::size_t k) { return static_cast<unsigned char>(utf8[k]); };
  for (std::size_t i = 0; i < utf8.size();) {
    const auto c = byte(i);
    char32_t u = c;
    std::size_t n = 1;
    if (c >= 0xE0) {
      u = ((c & 0x0Fu) << 12) | ((byte(i + 1) & 0x3Fu) << 6) | (byte(i + 2) & 0x3Fu);
      n = 3;
    } else if (c >= 0xC0) {
      u = ((c & 0x1Fu) << 6) | (byte(i + 1) & 0x3Fu);
      n = 2;
    }
    out += static_cast<char>(u & 0xFF);
    out += static_cast<char>(u >> 8);
    i += n;
  }
  return out;
}

std::string contents(const std::filesystem::path& path) {
  Result<std::string> text = read_text_file(path);
  EXPECT_TRUE(text.has_value());
  return text.has_value() ? *text : std::string();
}

std::filesystem::path written(const std::string& name, const std::string& bytes) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("sewerplan-bom-test-" + name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

const std::string kUtf8Bom = "\xEF\xBB\xBF";

class ByteOrderMark : public ::testing::TestWithParam<std::string> {};

// A map in every format, with a UTF-8 mark and in UTF-16: the same map as without.
TEST_P(ByteOrderMark, Issue31MapsAreReadWithAMarkInUtf8AndUtf16) {
  Diagnostics d;
  Result<SewerMap> plain = read_map(testing::dataset_path(GetParam()), d);
  ASSERT_TRUE(plain.has_value()) << plain.error().message;
  const std::string text = contents(testing::dataset_path(GetParam()));
  const std::string name = std::filesystem::path(GetParam()).filename().string();
  for (const std::string& bytes : {kUtf8Bom + text, utf16le(text)}) {
    const std::filesystem::path path = written(name, bytes);
    Diagnostics d2;
    Result<SewerMap> map = read_map(path, d2);
    ASSERT_TRUE(map.has_value()) << map.error().message;
    EXPECT_EQ(map->manhole_count(), plain->manhole_count());
    EXPECT_EQ(map->pipe_count(), plain->pipe_count());
    EXPECT_EQ(d2.warning_count(), d.warning_count());
    std::filesystem::remove(path);
  }
}

INSTANTIATE_TEST_SUITE_P(EveryMapFormat, ByteOrderMark,
                         ::testing::Values("ais-testbed/map.json", "swmm/epa-example1.inp",
                                           "isybau/street-2017.xml"));

TEST(ByteOrderMarkFiles, Issue31TheAsciiDatabaseMissionsConditionAndRiskTables) {
  Diagnostics d;
  Result<SewerMap> map = read_map(testing::dataset_path("ais-testbed/map.json"), d);
  ASSERT_TRUE(map.has_value());
  const std::filesystem::path sewer = written("map.sewer", "");
  ASSERT_TRUE(write_map(*map, sewer).has_value());
  const std::filesystem::path marked = written("marked.sewer", kUtf8Bom + contents(sewer));
  Result<SewerMap> ascii = read_map(marked, d);
  ASSERT_TRUE(ascii.has_value()) << ascii.error().message;
  EXPECT_EQ(ascii->manhole_count(), map->manhole_count());
  const std::filesystem::path mission =
      written("mission.json",
              kUtf8Bom + contents(testing::dataset_path("ais-testbed/missions/paper.json")));
  Result<Mission> m = read_mission(mission, *map, d);
  ASSERT_TRUE(m.has_value()) << m.error().message;
  EXPECT_EQ(m->tasks.size(), 3U);
  const std::filesystem::path table = written(
      "risk.json", utf16le(contents(testing::dataset_path("condition/default-risk-table.json"))));
  Result<RiskTable> risk = read_risk_table(table, d);
  ASSERT_TRUE(risk.has_value()) << risk.error().message;
  EXPECT_EQ(risk->rules.size(), default_risk_table().rules.size());
  Result<SewerMap> street = read_map(testing::dataset_path("isybau/street-2017.xml"), d);
  ASSERT_TRUE(street.has_value());
  const std::filesystem::path zustand = written(
      "zustand.xml", kUtf8Bom + contents(testing::dataset_path("isybau/street-zustand.xml")));
  Result<SewerMap> joined = read_condition(std::move(*street), zustand, d);
  ASSERT_TRUE(joined.has_value()) << joined.error().message;
  EXPECT_EQ(joined->finding_count(), 7U);
  for (const auto& path : {sewer, marked, mission, table, zustand}) std::filesystem::remove(path);
}

// UTF-16 that is not what its mark says is an error naming the file and the byte, not text
// with NULs.
TEST(ByteOrderMarkFiles, Issue31BrokenUtf16IsAnErrorNamingTheFile) {
  // A lone high surrogate (D800) after "<a".
  const std::filesystem::path path =
      written("broken.xml", std::string("\xFF\xFE<\0a\0\x00\xD8>\0", 10));
  Diagnostics d;
  Result<SewerMap> map = read_map(path, d);
  ASSERT_FALSE(map.has_value());
  EXPECT_THAT(map.error().message,
              HasSubstr(path.string() + ": begins with the byte-order mark of UTF-16LE but is "
                                        "not UTF-16LE at byte 6"));
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace sewerplan
