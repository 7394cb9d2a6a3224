// SPDX-License-Identifier: MIT
// generate_mission: the three spreads of tasks (issue 16), each seeded and on distinct pipes.
#include "sewerplan/domain/mission_generator.h"

#include <set>

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/domain/compile.h"

#include "support/enum_round_trip.h"

namespace sewerplan::domain {
namespace {

SewerMap city() {
  return *generate_network({.manholes = 3000, .seed = 4, .topology = Topology::kMeshed});
}

// The cost of reaching every task from the start: the first row of the compiled distances is
// not public, so the compile's settled nodes stand for how far the routes reach.
std::size_t settled(const SewerMap& map, const Mission& mission) {
  auto task = compile_sewer_task(map, mission, initial_progress(mission, map));
  EXPECT_TRUE(task.has_value());
  return task.has_value() ? task->statistics().settled_nodes : 0;
}

TEST(MissionGenerator, EverySpreadGivesDistinctPipesAndTheSameMissionForTheSameSeed) {
  const SewerMap map = city();
  for (MissionSpread spread :
       {MissionSpread::kUniform, MissionSpread::kClustered, MissionSpread::kNearExit}) {
    auto a = generate_mission(map, {.tasks = 10, .seed = 3, .spread = spread});
    auto b = generate_mission(map, {.tasks = 10, .seed = 3, .spread = spread});
    ASSERT_TRUE(a.has_value()) << to_string(spread) << ": " << a.error();
    ASSERT_EQ(a->tasks.size(), 10U);
    std::set<PipeId> pipes;
    for (std::size_t i = 0; i < a->tasks.size(); ++i) {
      pipes.insert(std::get<PipeSpot>(a->tasks[i].place).pipe);
      EXPECT_EQ(a->tasks[i].name, b->tasks[i].name);
    }
    EXPECT_EQ(pipes.size(), 10U) << to_string(spread);
    EXPECT_EQ(mission_spread_from_string(to_string(spread)), spread);
  }
  EXPECT_FALSE(mission_spread_from_string("everywhere").has_value());
}

TEST(MissionGenerator, EverySpreadRoundTripsThroughItsNameAndBack) {
  testing::expect_round_trip(
      {MissionSpread::kUniform, MissionSpread::kClustered, MissionSpread::kNearExit},
      mission_spread_from_string);
}

// Uniform tasks lie all over the robot's range: routing between them covers far more of the
// network than between tasks near the start.
TEST(MissionGenerator, UniformTasksSpreadFartherThanTasksNearTheExit) {
  const SewerMap map = city();
  auto uniform = generate_mission(map, {.tasks = 10, .seed = 3, .spread = MissionSpread::kUniform});
  auto near = generate_mission(map, {.tasks = 10, .seed = 3, .spread = MissionSpread::kNearExit});
  ASSERT_TRUE(uniform.has_value() && near.has_value());
  EXPECT_GT(settled(map, *uniform), 3 * settled(map, *near));
}

TEST(MissionGenerator, ABatteryGivenReplacesTheProfilesAndOneOutOfRangeIsAnError) {
  const SewerMap map = city();
  const auto big = generate_mission(
      map, {.tasks = 5, .seed = 1, .spread = MissionSpread::kUniform, .battery_wh = 1e6});
  ASSERT_TRUE(big.has_value()) << big.error().message;
  EXPECT_EQ(big->profile.battery_wh, 1e6);
  for (double wh : {0.0, -5.0, 2e6}) {
    const auto bad = generate_mission(map, {.tasks = 5, .seed = 1, .battery_wh = wh});
    ASSERT_FALSE(bad.has_value()) << wh;
    EXPECT_EQ(bad.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(bad.error().message.find("battery_wh"), std::string::npos);
  }
}

}  // namespace
}  // namespace sewerplan::domain
