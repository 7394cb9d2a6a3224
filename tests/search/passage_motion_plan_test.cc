// SPDX-License-Identifier: MIT
// Planning with a motion table (core/passage_motion.h): a passage the motion planner rejects is
// not planned through, planned durations are the passages' costs, and the validator agrees.
#include <memory>

#include <gtest/gtest.h>

#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/search/planner.h"

#include "support/small_map.h"

namespace sewerplan::search {
namespace {

using testing::add_task;
using testing::small_mission;
using testing::SmallMap;

// A square: M1 (exit, start) to M3 either via M2 or via M4, both with a right-angle turn.
struct Square {
  SewerMap map = SmallMap()
                     .manhole("M1", 0, 0, /*exit=*/true)
                     .manhole("M2", 10, 0)
                     .manhole("M3", 10, 10)
                     .manhole("M4", 0, 9.9)  // a little shorter: via M4 is the cheaper way
                     .pipe("P1", "M1", "M2")
                     .pipe("P2", "M2", "M3")
                     .pipe("P3", "M4", "M3")
                     .pipe("P4", "M1", "M4")
                     .build();
  Mission mission = make_mission();

  Mission make_mission() const {
    Mission m = small_mission(map, "M1");
    add_task(m, map, "there", TaskKind::kGoTo, "M3", std::nullopt, /*final=*/true);
    return m;
  }

  // The passage through `manhole` from the slot of pipe `from` into the slot of pipe `to`.
  PassageMotion passage(const char* manhole, const char* from, const char* to, bool feasible,
                        double duration_s) const {
    const ManholeId m = *map.find_manhole(manhole);
    auto slot_of = [&](const char* pipe) {
      const auto slots = map.slots(m);
      for (std::uint16_t i = 0; i < slots.size(); ++i) {
        if (slots[i].pipe == *map.find_pipe(pipe)) return SlotIndex{i};
      }
      ADD_FAILURE() << pipe << " is not at " << manhole;
      return SlotIndex{0};
    };
    PassageMotion p{.manhole = m, .from = slot_of(from), .to = slot_of(to), .feasible = feasible};
    if (feasible) {
      p.duration_s = duration_s;
      p.waypoints = {Waypoint{0, 0, 0, 0}, Waypoint{0.5, 0, 0, 0}};
    } else {
      p.reason = "test: no motion";
    }
    return p;
  }

  void attach(std::vector<PassageMotion> entries) {
    mission.passage_motion = std::make_shared<const PassageMotionTable>(
        map_geometry_fingerprint(map), profile_geometry_fingerprint(mission.profile),
        std::move(entries));
  }

  PlanOutcome plan() const {
    Result<PlanOutcome> outcome = plan_mission(map, mission, domain::initial_progress(mission, map),
                                               {.algorithm = Algorithm::kAstar});
    EXPECT_TRUE(outcome.has_value()) << outcome.error();
    if (!outcome.has_value()) return {};
    const auto report = domain::validate_plan(outcome->plan, map, mission);
    EXPECT_TRUE(report.valid) << report.error;
    EXPECT_NEAR(report.total_cost_s, outcome->cost_s, 0.01);
    return *outcome;
  }

  std::string text(const PlanOutcome& outcome) const {
    return domain::format_plan(outcome.plan, map, mission);
  }
};

TEST(PassageMotionPlanning, WithoutATableTheRulesChooseTheShorterWay) {
  Square s;
  EXPECT_NE(s.text(s.plan()).find("M4"), std::string::npos);
}

TEST(PassageMotionPlanning, APassageTheMotionPlannerRejectsIsNotPlannedThrough) {
  Square s;
  s.attach({s.passage("M4", "P4", "P3", false, 0)});
  const std::string plan = s.text(s.plan());
  EXPECT_EQ(plan.find("M4"), std::string::npos) << plan;
  EXPECT_NE(plan.find("M2"), std::string::npos) << plan;
}

TEST(PassageMotionPlanning, PlannedDurationsAreThePassagesCosts) {
  Square s;
  const double rules_cost = s.plan().cost_s;
  // The turn at M2 becomes much quicker than the rules say: the plan goes that way, cheaper.
  s.attach({s.passage("M2", "P1", "P2", true, 5.0)});
  const PlanOutcome outcome = s.plan();
  EXPECT_NE(s.text(outcome).find("M2"), std::string::npos);
  EXPECT_LT(outcome.cost_s, rules_cost - 30);
}

TEST(PassageMotionPlanning, TheValidatorRefusesAPassageTheTableRejectsAndSaysWhy) {
  Square s;
  s.attach({s.passage("M4", "P4", "P3", false, 0)});
  const PassageMotion p = s.passage("M4", "P4", "P3", false, 0);
  const domain::Plan plan{
      {domain::EnterPipe{*s.map.find_manhole("M1"), *s.map.find_pipe("P4")},
       domain::DrivePipeToManhole{*s.map.find_pipe("P4"), p.manhole},
       domain::DriveManhole{p.manhole, p.from, p.to},
       domain::DrivePipeToManhole{*s.map.find_pipe("P3"), *s.map.find_manhole("M3")}}};
  const auto report = domain::validate_plan(plan, s.map, s.mission);
  EXPECT_FALSE(report.valid);
  EXPECT_NE(report.error.find("motion planner found no motion"), std::string::npos) << report.error;
}

}  // namespace
}  // namespace sewerplan::search
