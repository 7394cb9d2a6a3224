// SPDX-License-Identifier: MIT
// BackgroundReplan: a replan on its own thread, cancelled from another. These are the concurrent
// tests that scripts/tsan.sh runs under ThreadSanitizer (filter: BackgroundReplan*).
#include "sewerplan/executor/background_replan.h"

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/domain/mission_generator.h"
#include "sewerplan/domain/validator.h"

#include "support/ais_testbed.h"

namespace sewerplan::executor {
namespace {

TEST(BackgroundReplan, GivesTheAnswerAReplanOnTheCallersThreadGives) {
  const auto ais = testing::load_ais_testbed();
  const PipeId p4 = *ais.map.find_pipe("P4");
  const Failure blocked{.kind = Failure::Kind::kBlockage, .pipe = p4, .offset_m = 2.0};
  ManualClock clock;
  Replanner here(ais.map, ais.mission, {.clock = &clock});
  const PlanResponse expected = here.report_failure(blocked);
  Replanner there(ais.map, ais.mission, {.clock = &clock});
  BackgroundReplan replan(there, blocked);
  Result<PlanResponse> r = replan.get();
  ASSERT_TRUE(r.has_value()) << r.error();
  EXPECT_TRUE(replan.ready());
  EXPECT_EQ(r->decision, expected.decision);
  EXPECT_EQ(r->plan.steps, expected.plan.steps);
  EXPECT_EQ(there.learnt(), here.learnt());
}

// Cancelled while it searches (or just after it finished: the race is the robot's too), the
// replan answers kCancelled or its plan, never the beacon; the blockage stays learnt, and the
// newer report is planned from there.
TEST(BackgroundReplan, ACancelledReplanKeepsWhatItLearntAndTheNextReplanPlans) {
  auto map = generate_network({.manholes = 3000, .seed = 5, .topology = Topology::kMeshed});
  ASSERT_TRUE(map.has_value()) << map.error();
  auto mission = domain::generate_mission(*map, {.tasks = 20, .seed = 2});
  ASSERT_TRUE(mission.has_value()) << mission.error();
  Replanner replanner(
      *map, *mission,
      {.planner = {.algorithm = search::Algorithm::kGbfs, .improvement_expansions = 0}});
  // Two blockages in a pipe at the start: in it, or at the start manhole's first slot.
  const auto& here = replanner.progress().position;
  const auto* in = std::get_if<domain::InPipe>(&here);
  const PipeId pipe = in != nullptr ? in->pipe : map->slots(*domain::manhole_of(here)).front().pipe;
  const double x = in != nullptr ? in->offset_m : map->pipe(pipe).length_m / 2;
  {
    BackgroundReplan replan(replanner, std::nullopt, "first");
    replan.cancel();
    const Result<PlanResponse> r = replan.get();
    if (r.has_value()) {
      EXPECT_TRUE(has_plan(r->decision)) << r->reason;
    } else {
      EXPECT_EQ(r.error().code, ErrorCode::kCancelled);
    }
  }
  {
    BackgroundReplan replan(
        replanner, Failure{.kind = Failure::Kind::kBlockage, .pipe = pipe, .offset_m = x + 0.01});
    replan.cancel();
    (void)replan.get();
  }
  EXPECT_EQ(replanner.learnt().blockages.size(), 1U);
  BackgroundReplan newer(
      replanner, Failure{.kind = Failure::Kind::kBlockage, .pipe = pipe, .offset_m = x - 0.01});
  const Result<PlanResponse> r = newer.get();
  ASSERT_TRUE(r.has_value()) << r.error();
  EXPECT_FALSE(r->decision == PlanResponse::Decision::kInvalidReport) << r->reason;
  EXPECT_EQ(replanner.learnt().blockages.size(), 2U);
  if (has_plan(r->decision)) {
    domain::MissionProgress start = replanner.progress();
    for (const auto& d : replanner.dropped()) start.done[d.task.index()] = true;
    const auto report = domain::validate_plan(r->plan, *map, replanner.mission(), start);
    EXPECT_TRUE(report.valid) << report.error;
  }
}

TEST(BackgroundReplan, DestroyingAReplanThatRunsCancelsItAndWaits) {
  const auto ais = testing::load_ais_testbed();
  Replanner replanner(ais.map, ais.mission);
  { BackgroundReplan replan(replanner, std::nullopt); }
  // The Replanner is free again.
  EXPECT_TRUE(has_plan(replanner.plan().decision));
}

}  // namespace
}  // namespace sewerplan::executor
