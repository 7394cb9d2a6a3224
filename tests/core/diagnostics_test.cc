// SPDX-License-Identifier: MIT
// One Diagnostics reused across several files (a library user reading a map, then a mission,
// then the next map): what an earlier file reported is that file's, so it neither fails the next
// read nor appears in the next read's error.
#include "sewerplan/core/diagnostics.h"

#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/map_ascii.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/robot_profile.h"

#include "support/paths.h"

namespace sewerplan {
namespace {

using testing::dataset_path;
using ::testing::HasSubstr;
using ::testing::Not;

constexpr std::string_view kEarlier = "an earlier file's error";

Diagnostics with_earlier_error() {
  Diagnostics d;
  d.error("earlier.json:1", std::string(kEarlier));
  return d;
}

TEST(DiagnosticsTest, MarkSeparatesLaterErrorsFromEarlierOnes) {
  Diagnostics d = with_earlier_error();
  d.warning("a", "a warning");
  const Diagnostics::Mark before = d.mark();
  EXPECT_FALSE(d.has_errors_since(before));
  EXPECT_EQ(d.error_summary(before), "");
  d.error("later.json:3", "a later error");
  EXPECT_TRUE(d.has_errors_since(before));
  EXPECT_EQ(d.error_summary(before), "later.json:3: error: a later error");
  EXPECT_THAT(d.error_summary(), HasSubstr(std::string(kEarlier)));
}

TEST(DiagnosticsTest, DroppedCountIsOnlyTheNewOnes) {
  Diagnostics d;
  for (std::size_t i = 0; i < Diagnostics::kMaxKept + 5; ++i) d.error("x", "old");
  const Diagnostics::Mark before = d.mark();
  EXPECT_EQ(d.error_summary(before), "");
  d.error("y", "new");
  EXPECT_EQ(d.error_summary(before), "\n(1 more problems not shown)");
}

// Every map format reads with an error already collected, and its map is the same.
TEST(DiagnosticsTest, MapReadersIgnoreErrorsReportedBefore) {
  for (const char* file :
       {"ais-testbed/map.json", "swmm/epa-example1.inp", "isybau/street-2013.xml"}) {
    Diagnostics clean;
    Result<SewerMap> expected = read_map(dataset_path(file), clean);
    ASSERT_TRUE(expected.has_value()) << file << ": " << expected.error().message;
    Diagnostics d = with_earlier_error();
    Result<SewerMap> map = read_map(dataset_path(file), d);
    ASSERT_TRUE(map.has_value()) << file << ": " << map.error().message;
    EXPECT_EQ(map->manhole_count(), expected->manhole_count()) << file;
    EXPECT_EQ(map->pipe_count(), expected->pipe_count()) << file;
  }
}

TEST(DiagnosticsTest, AsciiMapReaderIgnoresErrorsReportedBefore) {
  Diagnostics clean;
  Result<SewerMap> ais = read_map(dataset_path("ais-testbed/map.json"), clean);
  ASSERT_TRUE(ais.has_value());
  std::ostringstream text;
  ASSERT_TRUE(write_map_ascii(*ais, text).has_value());
  Diagnostics d = with_earlier_error();
  Result<SewerMap> map = read_map_ascii(text.str(), "ais.txt", d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_EQ(map->pipe_count(), ais->pipe_count());
}

TEST(DiagnosticsTest, MissionProfileAndRiskReadersIgnoreErrorsReportedBefore) {
  Diagnostics clean;
  Result<SewerMap> map = read_map(dataset_path("ais-testbed/map.json"), clean);
  ASSERT_TRUE(map.has_value());
  Diagnostics d = with_earlier_error();
  Result<Mission> mission = read_mission(dataset_path("ais-testbed/missions/paper.json"), *map, d);
  EXPECT_TRUE(mission.has_value()) << mission.error().message;
  Result<RobotProfile> profile =
      read_profile_json(R"({"base": "makro-plus", "speed_mps": 0.5})", "p.json", d);
  ASSERT_TRUE(profile.has_value()) << profile.error().message;
  EXPECT_EQ(profile->speed_mps, 0.5);
  Result<RiskTable> table = read_risk_table_json(
      R"({"format": "sewerplan-risk-table", "version": 1, "rules": []})", "risk.json", d);
  EXPECT_TRUE(table.has_value()) << table.error().message;
}

// A read that fails names its own problem only.
TEST(DiagnosticsTest, AFailedReadReportsOnlyItsOwnErrors) {
  Diagnostics d = with_earlier_error();
  Result<SewerMap> map = read_map_ascii("sewerdb 1\nmanhole\n", "broken.txt", d);
  ASSERT_FALSE(map.has_value());
  EXPECT_THAT(map.error().message, HasSubstr("broken.txt:2"));
  EXPECT_THAT(map.error().message, Not(HasSubstr(std::string(kEarlier))));

  Diagnostics clean;
  Result<SewerMap> ais = read_map(dataset_path("ais-testbed/map.json"), clean);
  ASSERT_TRUE(ais.has_value());
  Result<Mission> mission = read_mission_json(R"({"format": "sewerplan-mission", "version": 1,
      "start": {"manhole": "NO-SUCH-MANHOLE"}, "tasks": []})",
                                              "m.json", *ais, d);
  ASSERT_FALSE(mission.has_value());
  EXPECT_THAT(mission.error().message, HasSubstr("NO-SUCH-MANHOLE"));
  EXPECT_THAT(mission.error().message, Not(HasSubstr(std::string(kEarlier))));
}

}  // namespace
}  // namespace sewerplan
