// SPDX-License-Identifier: MIT
// Planning on networks imported from sewer databases (SWMM, ISYBAU).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/search/planner.h"

#include "support/paths.h"

namespace sewerplan::search {
namespace {

using ::testing::HasSubstr;

struct Loaded {
  SewerMap map;
  Mission mission;
};

Loaded load(const std::string& map_file, const std::string& mission_json) {
  Diagnostics d;
  Result<SewerMap> map = read_map(testing::dataset_path(map_file), d);
  EXPECT_TRUE(map.has_value());
  if (!map.has_value()) return {};
  Result<Mission> mission = read_mission_json(mission_json, "mission.json", *map, d);
  EXPECT_TRUE(mission.has_value()) << (mission.has_value() ? "" : mission.error().message);
  if (!mission.has_value()) return {};
  return {std::move(map).value(), std::move(mission).value()};
}

// On the ISYBAU street: inspect the egg pipe S3 and come out at any manhole ("exits": "all").
// From S1 the robot drives pipe S1 to S2 and turns into S3 there (63.4 deg, a 0.30 m step: just
// within makro-plus's limits).
TEST(ImportedNetwork, PlansAnInspectionOnTheIsybauStreet) {
  const Loaded in = load("isybau/street-2017.xml", R"({
    "format": "sewerplan-mission", "version": 1, "profile": "makro-plus",
    "start": {"manhole": "S1"},
    "tasks": [{"name": "egg", "type": "inspect_pipe", "pipe": "S3"}],
    "exits": "all"})");
  Result<PlanOutcome> outcome =
      plan_mission(in.map, in.mission, domain::initial_progress(in.mission, in.map), {});
  ASSERT_TRUE(outcome.has_value()) << outcome.error().message;
  const domain::ValidationReport report = domain::validate_plan(outcome->plan, in.map, in.mission);
  EXPECT_TRUE(report.valid) << report;
  EXPECT_THAT(domain::format_plan(outcome->plan, in.map, in.mission), HasSubstr("INSPECT_PIPE S3"));
}

// With steps limited to 0.20 m, the robot lowered into S4 cannot reach pipe S3: the turn from
// pipe S2 into it at S2 is 116.6 degrees, and from pipe S1 (backing out) the step is 0.30 m. No
// plan; the driveability report (driveability_test.cc) says why.
TEST(ImportedNetwork, FindsNoPlanWhenTheOnlyWayTurnsTooSharply) {
  const Loaded in = load("isybau/street-2017.xml", R"({
    "format": "sewerplan-mission", "version": 1,
    "profile": {"base": "makro-plus", "max_step_m": 0.2},
    "start": {"manhole": "S4"},
    "tasks": [{"name": "egg", "type": "inspect_pipe", "pipe": "S3"}],
    "exits": ["S4"]})");
  Result<PlanOutcome> outcome =
      plan_mission(in.map, in.mission, domain::initial_progress(in.mission, in.map), {});
  ASSERT_FALSE(outcome.has_value());
  EXPECT_EQ(outcome.error().code, ErrorCode::kNoPlan);
}

// EPA Example 1: conduits 1 (9 -> 10, 1.5 ft) and 6 (10 -> 21, 1 ft) are drivable, 400 ft each.
TEST(ImportedNetwork, PlansOnEpaExample1) {
  const Loaded in = load("swmm/epa-example1.inp", R"({
    "format": "sewerplan-mission", "version": 1, "profile": "makro-plus",
    "start": {"manhole": "9"},
    "tasks": [{"name": "c6", "type": "inspect_pipe", "pipe": "6"}]})");
  Result<PlanOutcome> outcome =
      plan_mission(in.map, in.mission, domain::initial_progress(in.mission, in.map), {});
  ASSERT_TRUE(outcome.has_value()) << outcome.error().message;
  EXPECT_TRUE(domain::validate_plan(outcome->plan, in.map, in.mission).valid);
}

}  // namespace
}  // namespace sewerplan::search
