// SPDX-License-Identifier: MIT
// Contingency-aware battery planning (PlannerOptions::contingency, domain::CompileOptions::
// contingency): at every drive past a possible blockage the plan keeps enough battery to back out
// and reach an exit another way, so a hazard that does stop the robot cannot strand it (issue 14:
// robots blocked late in their tour had a way out but not the battery for it).
#include <gtest/gtest.h>

#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/search/planner.h"
#include "sewerplan/search/tour_search.h"

#include "support/small_map.h"

namespace sewerplan::search {
namespace {

using domain::initial_progress;
using testing::add_task;
using testing::small_mission;
using testing::SmallMap;

// The robot starts at S. The task is a water sample 45 m into SX (there and back). The near
// exit E is 10 m west
// through SHORT, with roots at 5 m (p = 0.3); the far exit F is 90 m north through LONG.
// The battery fits the task and the short way out with a minute to spare.
struct Trap {
  SewerMap map = SmallMap()
                     .manhole("S", 0, 0)
                     .manhole("X", 50, 0)
                     .manhole("Y", 100, 0)
                     .manhole("E", -10, 0, /*exit=*/true)
                     .manhole("F", 0, 90, /*exit=*/true)
                     .pipe("SX", "S", "X", 0.5, 50.0)
                     .pipe("XY", "X", "Y", 0.5, 50.0)
                     .pipe("SHORT", "S", "E", 0.5, 10.0)
                     .pipe("LONG", "S", "F", 0.5, 90.0)
                     .build();
  Mission mission = make_mission(map);

  static Mission make_mission(const SewerMap& map) {
    Mission m = small_mission(map, "S");
    add_task(m, map, "sample in SX", TaskKind::kTakeWaterSample, "SX", 45.0);
    m.hazards.push_back(
        {.pipe = *map.find_pipe("SHORT"), .offset_m = 5, .probability = 0.3, .reason = "roots"});
    return m;
  }
};

// The blind plan's cost, and a battery that fits it with `spare_s` to spare.
double battery_for(const Trap& trap, double spare_s) {
  auto blind = plan_mission(trap.map, trap.mission, initial_progress(trap.mission, trap.map),
                            {.select_goals = true, .contingency = false});
  EXPECT_TRUE(blind.has_value()) << blind.error();
  return trap.mission.profile.energy_wh(blind->cost_s + spare_s);
}

TEST(ContingencyPlanning, TheBlindPlanIsStrandedWhenTheHazardStopsIt) {
  Trap trap;
  trap.mission.profile.battery_wh = battery_for(trap, 60);
  auto blind = plan_mission(trap.map, trap.mission, initial_progress(trap.mission, trap.map),
                            {.select_goals = true, .contingency = false});
  ASSERT_TRUE(blind.has_value()) << blind.error();
  EXPECT_TRUE(blind->dropped.empty());
  // Back at S after the task, SHORT turns out blocked: the far exit needs more than is left.
  domain::MissionProgress at_s = initial_progress(trap.mission, trap.map);
  at_s.done.assign(1, true);
  at_s.energy_used_wh = trap.mission.profile.energy_wh(
      blind->cost_s - trap.mission.profile.manhole_pass_s - 10.0 / trap.mission.profile.speed_mps);
  Mission blocked = trap.mission;
  blocked.blockages.push_back({.pipe = *trap.map.find_pipe("SHORT"), .offset_m = 5});
  auto out = plan_mission(trap.map, blocked, at_s, {.select_goals = true});
  ASSERT_FALSE(out.has_value());
  EXPECT_EQ(out.error().code, ErrorCode::kNoPlan);
}

TEST(ContingencyPlanning, KeepsTheBatteryToBackOutAndTakeTheFarExit) {
  Trap trap;
  trap.mission.profile.battery_wh = battery_for(trap, 60);
  const auto start = initial_progress(trap.mission, trap.map);
  for (Algorithm algorithm : {Algorithm::kAuto, Algorithm::kAstar, Algorithm::kExact,
                              Algorithm::kGbfs, Algorithm::kEhc, Algorithm::kWeightedAstar}) {
    SCOPED_TRACE(std::string(to_string(algorithm)));
    auto safe =
        plan_mission(trap.map, trap.mission, start, {.algorithm = algorithm, .select_goals = true});
    ASSERT_TRUE(safe.has_value()) << safe.error();
    // The task would leave too little to back out of SHORT and drive LONG: it is forgone, and
    // the robot goes out through SHORT with the battery for LONG still in hand.
    ASSERT_EQ(safe->dropped.size(), 1U) << domain::format_plan(safe->plan, trap.map, trap.mission);
    EXPECT_TRUE(safe->contingency_note.empty());
    // SHORT blocked at once: backing out and driving LONG fits what is left.
    domain::MissionProgress backed_out = start;
    backed_out.energy_used_wh = trap.mission.profile.energy_wh(
        trap.mission.profile.manhole_pass_s + 2 * 5.0 / trap.mission.profile.speed_mps);
    Mission blocked = trap.mission;
    blocked.blockages.push_back({.pipe = *trap.map.find_pipe("SHORT"), .offset_m = 5});
    auto out = plan_mission(trap.map, blocked, backed_out, {.select_goals = true});
    ASSERT_TRUE(out.has_value()) << out.error();
  }
}

TEST(ContingencyPlanning, WithBatteryToSpareTheTaskIsDone) {
  Trap trap;
  // Enough to back out of SHORT after the task and still drive LONG.
  trap.mission.profile.battery_wh = battery_for(trap, 800);
  auto plan = plan_mission(trap.map, trap.mission, initial_progress(trap.mission, trap.map),
                           {.select_goals = true});
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_TRUE(plan->dropped.empty());
}

TEST(ContingencyPlanning, NoPlanKeepsTheReserveSoThePlanGoesWithoutIt) {
  Trap trap;
  // Roots near F's end of LONG too, and a battery for six minutes: neither way out keeps the
  // battery to back out and take the other. Rather than no plan, the plan without the reserve
  // (the robot may still drive out), and a note saying so.
  trap.mission.hazards.push_back(
      {.pipe = *trap.map.find_pipe("LONG"), .offset_m = 80, .probability = 0.3, .reason = "roots"});
  trap.mission.profile.battery_wh = trap.mission.profile.energy_wh(360);
  auto plan = plan_mission(trap.map, trap.mission, initial_progress(trap.mission, trap.map),
                           {.select_goals = true});
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_FALSE(plan->contingency_note.empty());
}

TEST(ContingencyPlanning, WithoutHazardsNothingChanges) {
  Trap trap;
  trap.mission.profile.battery_wh = battery_for(trap, 60);
  trap.mission.hazards.clear();
  auto plan = plan_mission(trap.map, trap.mission, initial_progress(trap.mission, trap.map),
                           {.select_goals = true});
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_TRUE(plan->dropped.empty());
}

// Issue 14: with reserves, the cheapest insertion found no place for any goal once more than one
// had to go, and the tour search gave no answer at all (the engines then took seconds on the
// battery trap). Three samples 10 m into short side pipes of S: with the reserve for backing out
// of SHORT and driving LONG, at most one of them fits.
TEST(ContingencyPlanning, TheTourSearchDropsTheGoalsTheReservesLeaveNoRoomFor) {
  Trap trap;
  trap.map = SmallMap()
                 .manhole("S", 0, 0)
                 .manhole("A", 20, 0)
                 .manhole("B", 0, -20)
                 .manhole("C", 14, 14)
                 .manhole("E", -10, 0, /*exit=*/true)
                 .manhole("F", 0, 90, /*exit=*/true)
                 .pipe("SA", "S", "A", 0.5, 20.0)
                 .pipe("SB", "S", "B", 0.5, 20.0)
                 .pipe("SC", "S", "C", 0.5, 20.0)
                 .pipe("SHORT", "S", "E", 0.5, 10.0)
                 .pipe("LONG", "S", "F", 0.5, 90.0)
                 .build();
  Mission& m = trap.mission;
  m = small_mission(trap.map, "S");
  for (const char* pipe : {"SA", "SB", "SC"}) {
    add_task(m, trap.map, std::string("sample in ") + pipe, TaskKind::kTakeWaterSample, pipe, 10.0);
  }
  m.hazards.push_back(
      {.pipe = *trap.map.find_pipe("SHORT"), .offset_m = 5, .probability = 0.3, .reason = "roots"});
  m.profile.battery_wh = battery_for(trap, 60);
  auto compiled = domain::compile_sewer_task(trap.map, m, initial_progress(m, trap.map),
                                             {.select_goals = true, .contingency = true});
  ASSERT_TRUE(compiled.has_value()) << compiled.error();
  const domain::CompiledTask& task = compiled->task();
  auto exact = exact_tour_search(task);
  ASSERT_TRUE(exact.has_value());
  ASSERT_EQ(exact->status, SearchStatus::kSolved);
  const std::size_t fewest = compiled->forgone(exact->plan).size();
  ASSERT_GE(fewest, 2U);  // the case that gave no answer
  auto tour = tour_search(task);
  ASSERT_TRUE(tour.has_value());
  EXPECT_TRUE(task.solves(tour->plan));  // every reserve kept
  EXPECT_EQ(compiled->forgone(tour->plan).size(), fewest);
}

// Issue 34: a bound on the plan's computed stranding risk (PlannerOptions::max_strand_risk). The
// trap with two findings: deposits at 5 m in SHORT, the way out (p = 0.05), and roots at 20 m in
// SX, the task's pipe (p = 0.3). Insuring the deposits costs the task (the battery to back out
// of SHORT and drive LONG), as in the trap; insuring the roots costs little with the deposits
// uninsured (back out of SX, out through SHORT), but with them insured asks for LONG too.
struct TwoFindings : Trap {
  TwoFindings() {
    mission.hazards = {
        {.pipe = *map.find_pipe("SHORT"), .offset_m = 5, .probability = 0.05, .reason = "BBC"},
        {.pipe = *map.find_pipe("SX"), .offset_m = 20, .probability = 0.3, .reason = "BBA"}};
    mission.profile.battery_wh = battery_for(*this, 60);
  }
  static constexpr std::size_t kDeposits = 0;
  static constexpr std::size_t kRoots = 1;
  Result<PlanOutcome> plan(double max_strand_risk, Algorithm algorithm = Algorithm::kAuto) const {
    return plan_mission(
        map, mission, initial_progress(mission, map),
        {.algorithm = algorithm, .select_goals = true, .max_strand_risk = max_strand_risk});
  }
};

TEST(StrandRisk, NoRiskKeepsEveryReserve) {
  const TwoFindings trap;
  for (Algorithm algorithm : {Algorithm::kAuto, Algorithm::kAstar, Algorithm::kGbfs}) {
    SCOPED_TRACE(std::string(to_string(algorithm)));
    auto safe = trap.plan(0, algorithm);
    ASSERT_TRUE(safe.has_value()) << safe.error();
    EXPECT_EQ(safe->dropped.size(), 1U);
    // Out through SHORT past the deposits, with the battery for LONG kept: no risk taken.
    EXPECT_EQ(safe->strand_probability, 0.0);
    EXPECT_TRUE(safe->uninsured.empty());
    // The same plan as contingency alone (max_strand_risk 0 is the default).
    auto plain = plan_mission(trap.map, trap.mission, initial_progress(trap.mission, trap.map),
                              {.algorithm = algorithm, .select_goals = true});
    ASSERT_TRUE(plain.has_value());
    EXPECT_EQ(safe->plan, plain->plan);
  }
}

TEST(StrandRisk, CertainRiskKeepsNoReserve) {
  const TwoFindings trap;
  auto blind = trap.plan(1);
  ASSERT_TRUE(blind.has_value()) << blind.error();
  EXPECT_TRUE(blind->dropped.empty());
  // The task past the roots and out past the deposits, neither insured. The roots come first,
  // with the battery to back out of SX and leave through SHORT: not a stranding risk. The
  // deposits come last, without the battery for LONG.
  EXPECT_EQ(blind->uninsured, std::vector<std::size_t>{TwoFindings::kDeposits});
  EXPECT_NEAR(blind->strand_probability, 0.05, 1e-12);
  // The plan without contingency, which computes no way out: every hazard passed counts.
  auto plain = plan_mission(trap.map, trap.mission, initial_progress(trap.mission, trap.map),
                            {.select_goals = true, .contingency = false});
  ASSERT_TRUE(plain.has_value());
  EXPECT_EQ(blind->plan, plain->plan);
  EXPECT_EQ(plain->uninsured,
            (std::vector<std::size_t>{TwoFindings::kDeposits, TwoFindings::kRoots}));
  EXPECT_NEAR(plain->strand_probability, 1 - 0.95 * 0.7, 1e-12);
}

// Issue 34: a hazard passed early, with the battery left to back out and reach an exit another
// way, is no stranding risk whether or not its reserve was asked for; the same hazard passed
// late, without that battery, is.
TEST(StrandRisk, TheBatteryLeftCoversAHazardWithoutItsReserve) {
  TwoFindings trap;
  // Without reserves (max_strand_risk 1): the roots, passed first, are covered by the battery
  // left (CertainRiskKeepsNoReserve); the deposits, passed last, are not with 60 s to spare.
  auto plan = plan_mission(trap.map, trap.mission, initial_progress(trap.mission, trap.map),
                           {.select_goals = true, .max_strand_risk = 1});
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_EQ(plan->uninsured, std::vector<std::size_t>{TwoFindings::kDeposits});
  // With 400 s to spare (120 m, more than backing out of SHORT and driving LONG costs beyond
  // SHORT), neither is.
  trap.mission.profile.battery_wh = battery_for(trap, 400);
  plan = plan_mission(trap.map, trap.mission, initial_progress(trap.mission, trap.map),
                      {.select_goals = true, .max_strand_risk = 1});
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_TRUE(plan->dropped.empty());
  EXPECT_TRUE(plan->uninsured.empty());
  EXPECT_EQ(plan->strand_probability, 0.0);
}

// A hazard passed with the battery for the way out but not for backing out of the hazards on
// it: stranded only if one of those blocks too. The roots 40 m into SX (p = 0.3), passed first:
// backing out (80 m) and leaving by SHORT (10 m) fits the battery left, backing out of SHORT's
// deposits as well and driving LONG (100 m more) does not: 0.3 x 0.05. The deposits, passed last
// without the battery for LONG: 0.05.
TEST(StrandRisk, AWayOutPastAnotherHazardCountsBothBlocking) {
  TwoFindings trap;
  trap.mission.hazards[TwoFindings::kRoots].offset_m = 40;
  auto plan = trap.plan(1);
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_TRUE(plan->dropped.empty());
  EXPECT_EQ(plan->uninsured,
            (std::vector<std::size_t>{TwoFindings::kDeposits, TwoFindings::kRoots}));
  EXPECT_NEAR(plan->strand_probability, 1 - (1 - 0.3 * 0.05) * 0.95, 1e-12);
}

TEST(StrandRisk, ABoundBetweenTheLevelsInsuresExactlyTheRiskierFinding) {
  const TwoFindings trap;
  for (double bound : {0.05, 0.1, 0.3}) {
    SCOPED_TRACE(bound);
    auto plan = trap.plan(bound);
    ASSERT_TRUE(plan.has_value()) << plan.error();
    // The deposits go uninsured and buy the task; the roots keep their reserve.
    EXPECT_TRUE(plan->dropped.empty()) << domain::format_plan(plan->plan, trap.map, trap.mission);
    EXPECT_EQ(plan->uninsured, std::vector<std::size_t>{TwoFindings::kDeposits});
    EXPECT_NEAR(plan->strand_probability, 0.05, 1e-12);
    EXPECT_LE(plan->strand_probability, bound + 1e-9);
    EXPECT_GE(plan->strand_plans, 1U);
    EXPECT_NE(plan->strand_note.find("0 of 2 hazards keep their reserve"), std::string::npos)
        << plan->strand_note;
  }
}

TEST(StrandRisk, ABoundBelowEveryLevelKeepsTheFullyInsuredPlan) {
  const TwoFindings trap;
  auto plan = trap.plan(0.04);
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_EQ(plan->dropped.size(), 1U);
  EXPECT_EQ(plan->strand_probability, 0.0);
  auto safe = trap.plan(0);
  ASSERT_TRUE(safe.has_value());
  EXPECT_EQ(plan->plan, safe->plan);
}

TEST(StrandRisk, AReserveCoversTheNearerFindingsOfItsDrive) {
  TwoFindings trap;
  // More deposits at 2 m in SHORT, not insured: backing out from 5 m covers them too.
  trap.mission.hazards.push_back(
      {.pipe = *trap.map.find_pipe("SHORT"), .offset_m = 2, .probability = 0.5, .reason = "BBC"});
  trap.mission.profile.battery_wh = battery_for(trap, 60);
  auto plan = plan_mission(trap.map, trap.mission, initial_progress(trap.mission, trap.map),
                           {.select_goals = true, .insured = {true, true, false}});
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_EQ(plan->dropped.size(), 1U);
  EXPECT_EQ(plan->strand_probability, 0.0);
  // Insured alone, the nearer finding's reserve (LONG as well) still costs the task, and then
  // the farther one is passed with the battery to turn back: no risk either.
  plan = plan_mission(trap.map, trap.mission, initial_progress(trap.mission, trap.map),
                      {.select_goals = true, .insured = {false, true, true}});
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_EQ(plan->dropped.size(), 1U);
  EXPECT_TRUE(plan->uninsured.empty());
}

TEST(StrandRisk, AMissionEndingAtATaskKeepsNoReserveAndCountsEveryFinding) {
  TwoFindings trap;
  add_task(trap.mission, trap.map, "end", TaskKind::kGoTo, "SHORT", 8.0);
  trap.mission.tasks.back().final = true;
  trap.mission.profile.battery_wh = trap.mission.profile.energy_wh(3600);
  auto plan = trap.plan(0);
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_EQ(plan->uninsured,
            (std::vector<std::size_t>{TwoFindings::kDeposits, TwoFindings::kRoots}));
  EXPECT_NEAR(plan->strand_probability, 1 - 0.95 * 0.7, 1e-12);
}

TEST(StrandRiskBudget, TasksRiseWithTheBoundAndTheRiskStaysWithinIt) {
  const TwoFindings trap;
  std::size_t dropped_before = 2;
  for (double bound : {0.0, 0.01, 0.04, 0.05, 0.2, 1.0}) {
    SCOPED_TRACE(bound);
    auto plan = trap.plan(bound);
    ASSERT_TRUE(plan.has_value()) << plan.error();
    EXPECT_LE(plan->strand_probability, bound + 1e-9);
    EXPECT_LE(plan->dropped.size(), dropped_before);
    dropped_before = plan->dropped.size();
    // Below 0.05 no plan doing the task is within the bound; from 0.05 on every one does it.
    EXPECT_EQ(plan->dropped.size(), bound < 0.05 ? 1U : 0U);
  }
}

// The greedy allocation goes on from the risk-blind plan: insuring the deposits (the one hazard
// at risk) costs the task and removes all the risk, so a bound below 0.05 takes that plan, which
// is the fully insured one; the plans tried are counted.
TEST(StrandRiskBudget, OverTheBoundTheHazardAtRiskIsInsured) {
  const TwoFindings trap;
  auto plan = trap.plan(0.01);
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_EQ(plan->dropped.size(), 1U);
  EXPECT_EQ(plan->strand_probability, 0.0);
  EXPECT_EQ(plan->strand_plans, 2U);  // none insured, then the deposits
  auto insured = plan_mission(trap.map, trap.mission, initial_progress(trap.mission, trap.map),
                              {.select_goals = true, .insured = {true, false}});
  ASSERT_TRUE(insured.has_value()) << insured.error();
  EXPECT_EQ(plan->dropped.size(), insured->dropped.size());
  EXPECT_EQ(insured->strand_probability, 0.0);
}

// Issue 34: insuring the one hazard a plan passes at risk can move the tour past another hazard
// instead, so that the plan's risk does not fall; the allocation then went no further and gave
// the fully insured plan. Three arms from S (east to MA, north to MB, west to MC, 40 m each),
// a sample 35 m along each, and beyond each arm's manhole an exit pipe with deposits 5 m in:
// MB-EB 10 m (p = 0.3), MA-EA 20 m (p = 0.35), MC-EC 30 m (p = 0.05). The battery fits two
// samples and the longest exit pipe, not the battery to back out of an exit pipe late and drive
// to another exit. Unreserved, the plan leaves by EB (risk 0.3); with EB insured, by EA (0.35:
// more); with both insured, by EC (0.05), doing both samples. (The compile keeps one way out
// from each sample: insuring moves the tour by changing the order of the samples.) The fully
// insured plan does no sample.
struct ThreeExits {
  SewerMap map = SmallMap()
                     .manhole("S", 0, 0)
                     .manhole("MA", 40, 0)
                     .manhole("MB", 0, 40)
                     .manhole("MC", -40, 0)
                     .manhole("EA", 60, 0, /*exit=*/true)
                     .manhole("EB", 0, 50, /*exit=*/true)
                     .manhole("EC", -70, 0, /*exit=*/true)
                     .pipe("SA", "S", "MA", 0.5, 40.0)
                     .pipe("SB", "S", "MB", 0.5, 40.0)
                     .pipe("SC", "S", "MC", 0.5, 40.0)
                     .pipe("XA", "MA", "EA", 0.5, 20.0)
                     .pipe("XB", "MB", "EB", 0.5, 10.0)
                     .pipe("XC", "MC", "EC", 0.5, 30.0)
                     .build();
  Mission mission = make_mission(map);
  static constexpr std::size_t kExitA = 0;
  static constexpr std::size_t kExitB = 1;
  static constexpr std::size_t kExitC = 2;

  static Mission make_mission(const SewerMap& map) {
    Mission m = small_mission(map, "S");
    for (const char* arm : {"SA", "SB", "SC"}) {
      add_task(m, map, std::string("sample in ") + arm, TaskKind::kTakeWaterSample, arm, 35.0);
    }
    m.hazards = {
        {.pipe = *map.find_pipe("XA"), .offset_m = 5, .probability = 0.35, .reason = "BBB"},
        {.pipe = *map.find_pipe("XB"), .offset_m = 5, .probability = 0.3, .reason = "BBB"},
        {.pipe = *map.find_pipe("XC"), .offset_m = 5, .probability = 0.05, .reason = "BBB"}};
    // The battery: the samples in SA and SC and out by EC, with 200 s to spare (from 150 s the
    // fully insured plan leaves at once, not a third sample: up to 300 s the case holds).
    Mission by_c = small_mission(map, "S");
    add_task(by_c, map, "a", TaskKind::kTakeWaterSample, "SA", 35.0);
    add_task(by_c, map, "c", TaskKind::kTakeWaterSample, "SC", 35.0);
    by_c.blockages = {{.pipe = *map.find_pipe("XA"), .offset_m = 1},
                      {.pipe = *map.find_pipe("XB"), .offset_m = 1}};
    auto two = plan_mission(map, by_c, initial_progress(by_c, map), {.contingency = false});
    EXPECT_TRUE(two.has_value()) << two.error();
    if (two.has_value()) m.profile.battery_wh = m.profile.energy_wh(two->cost_s + 200);
    return m;
  }
  Result<PlanOutcome> plan(PlannerOptions options) const {
    options.select_goals = true;
    return plan_mission(map, mission, initial_progress(mission, map), options);
  }
};

TEST(StrandRiskBudget, InsuringTheHazardAtRiskMovesTheTourPastAnother) {
  const ThreeExits trap;
  auto blind = trap.plan({.max_strand_risk = 1});
  ASSERT_TRUE(blind.has_value()) << blind.error();
  EXPECT_EQ(blind->dropped.size(), 1U);
  EXPECT_EQ(blind->uninsured, std::vector<std::size_t>{ThreeExits::kExitB});
  EXPECT_NEAR(blind->strand_probability, 0.3, 1e-12);
  auto b_insured = trap.plan({.insured = {false, true, false}});
  ASSERT_TRUE(b_insured.has_value()) << b_insured.error();
  EXPECT_EQ(b_insured->dropped.size(), 1U);
  EXPECT_EQ(b_insured->uninsured, std::vector<std::size_t>{ThreeExits::kExitA});
  EXPECT_NEAR(b_insured->strand_probability, 0.35, 1e-12);
  auto a_b_insured = trap.plan({.insured = {true, true, false}});
  ASSERT_TRUE(a_b_insured.has_value()) << a_b_insured.error();
  EXPECT_EQ(a_b_insured->dropped.size(), 1U);
  EXPECT_EQ(a_b_insured->uninsured, std::vector<std::size_t>{ThreeExits::kExitC});
  EXPECT_NEAR(a_b_insured->strand_probability, 0.05, 1e-12);
  auto safe = trap.plan({});
  ASSERT_TRUE(safe.has_value()) << safe.error();
  EXPECT_EQ(safe->dropped.size(), 3U);
  EXPECT_TRUE(safe->contingency_note.empty());
  EXPECT_EQ(safe->strand_probability, 0.0);
}

// Issue 34: where no hazard's reserve removes risk (each moves the tour past others), the
// allocation goes on from the plan that loses the fewest tasks and insures what it passes next.
// Until then it stopped there and gave the fully insured plan, no sample where two are within
// the bound (the 2,000-run battery-trap campaign met this in its replans after a blockage).
TEST(StrandRiskBudget, Issue34GoesOnWhereAReserveMovesTheTourPastOtherHazards) {
  const ThreeExits trap;
  auto safe = trap.plan({});
  ASSERT_TRUE(safe.has_value()) << safe.error();
  for (double bound : {0.05, 0.1, 0.2}) {
    SCOPED_TRACE(bound);
    auto plan = trap.plan({.max_strand_risk = bound});
    ASSERT_TRUE(plan.has_value()) << plan.error();
    EXPECT_EQ(plan->dropped.size(), 1U) << domain::format_plan(plan->plan, trap.map, trap.mission);
    EXPECT_LT(plan->dropped.size(), safe->dropped.size());
    EXPECT_EQ(plan->uninsured, std::vector<std::size_t>{ThreeExits::kExitC});
    EXPECT_LE(plan->strand_probability, bound + 1e-9);
    // None insured, then EB (over 0.3), then EA with it.
    EXPECT_EQ(plan->strand_plans, 3U);
  }
  // Below the deposits at EC nothing but the fully insured plan is within the bound.
  auto tight = trap.plan({.max_strand_risk = 0.04});
  ASSERT_TRUE(tight.has_value()) << tight.error();
  EXPECT_EQ(tight->plan, safe->plan);
}

}  // namespace
}  // namespace sewerplan::search
