// SPDX-License-Identifier: MIT
// The Replanner's answers: typed decisions the robot software switches on, on the paper's test
// environment (datasets/ais-testbed).
#include "sewerplan/executor/replanner.h"

#include <atomic>
#include <limits>

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/domain/mission_generator.h"
#include "sewerplan/domain/validator.h"

#include "support/ais_testbed.h"

namespace sewerplan::executor {
namespace {

using Decision = PlanResponse::Decision;

PipeId pipe_named(const SewerMap& map, std::string_view name) {
  for (PipeId p : map.pipe_ids()) {
    if (map.pipe(p).name == name) return p;
  }
  ADD_FAILURE() << "no pipe " << name;
  return PipeId{0};
}

TEST(ReplannerDecision, EveryDecisionHasAStableNameThatParsesBack) {
  const std::vector<std::pair<Decision, std::string_view>> names{
      {Decision::kFollowPlan, "follow-plan"},
      {Decision::kDegraded, "degraded"},
      {Decision::kCallForRecovery, "call-for-recovery"},
      {Decision::kStuck, "stuck"},
      {Decision::kInvalidReport, "invalid-report"}};
  for (const auto& [decision, name] : names) {
    EXPECT_EQ(to_string(decision), name);
    EXPECT_EQ(parse_decision(name), decision) << name;
  }
  EXPECT_EQ(parse_decision("follow"), std::nullopt);
  EXPECT_EQ(parse_decision("call for recovery"), std::nullopt);
}

TEST(ReplannerDecision, OnlyFollowAndDegradedCarryAPlanAndOnlyRecoveryAndStuckCallTheBeacon) {
  EXPECT_TRUE(has_plan(Decision::kFollowPlan));
  EXPECT_TRUE(has_plan(Decision::kDegraded));
  EXPECT_FALSE(has_plan(Decision::kCallForRecovery));
  EXPECT_FALSE(has_plan(Decision::kStuck));
  EXPECT_FALSE(has_plan(Decision::kInvalidReport));
  EXPECT_TRUE(calls_beacon(Decision::kCallForRecovery));
  EXPECT_TRUE(calls_beacon(Decision::kStuck));
  EXPECT_FALSE(calls_beacon(Decision::kFollowPlan));
  EXPECT_FALSE(calls_beacon(Decision::kDegraded));
  EXPECT_FALSE(calls_beacon(Decision::kInvalidReport));
}

TEST(ReplannerDecision, TheWholeMissionIsFollowPlan) {
  const auto ais = testing::load_ais_testbed();
  Replanner replanner(ais.map, ais.mission);
  const PlanResponse r = replanner.plan();
  EXPECT_EQ(r.decision, Decision::kFollowPlan) << r.reason;
  EXPECT_FALSE(r.plan.steps.empty());
}

TEST(ReplannerDecision, ABlockageThatCostsATaskIsDegraded) {
  const auto ais = testing::load_ais_testbed();
  Replanner replanner(ais.map, ais.mission);
  (void)replanner.plan();
  // P4 blocked in its middle: it cannot be inspected any more.
  const PipeId p4 = pipe_named(ais.map, "P4");
  const PlanResponse r = replanner.report_failure(
      {.kind = Failure::Kind::kBlockage, .pipe = p4, .offset_m = ais.map.pipe(p4).length_m / 2});
  ASSERT_EQ(r.newly_dropped.size(), 1U) << r.reason;
  EXPECT_EQ(r.decision, Decision::kDegraded) << r.reason;
  // Nothing more is lost on the next replan: following the plan again.
  EXPECT_EQ(replanner.plan("again").decision, Decision::kFollowPlan);
}

TEST(ReplannerDecision, ARobotThatCannotMoveIsStuck) {
  const auto ais = testing::load_ais_testbed();
  Replanner replanner(ais.map, ais.mission);
  const PlanResponse r =
      replanner.report_failure({.kind = Failure::Kind::kStuck, .detail = "motor 3 dead"});
  EXPECT_EQ(r.decision, Decision::kStuck);
  EXPECT_NE(r.reason.find("motor 3 dead"), std::string::npos);
}

// A blockage learnt where the robot has since driven through is gone (a transient obstacle, or a
// failure placed where the robot was not): it leaves the world model and the next plan says so;
// one at the ends of the stretch driven, an operator's closure and a bad report stay as they were.
TEST(ReplannerDecision, ABlockageTheRobotDroveThroughIsDropped) {
  const auto ais = testing::load_ais_testbed();
  Mission mission = ais.mission;
  const PipeId p4 = pipe_named(ais.map, "P4");
  const double length = ais.map.pipe(p4).length_m;
  mission.blockages.push_back({p4, length / 4});  // the operator's
  Replanner replanner(ais.map, mission);
  (void)replanner.plan();
  const PlanResponse blocked = replanner.report_failure(
      {.kind = Failure::Kind::kBlockage, .pipe = p4, .offset_m = length / 2});
  ASSERT_EQ(replanner.learnt().blockages.size(), 1U) << blocked.reason;

  EXPECT_FALSE(replanner.drove_through(p4, length, length + 1).has_value());  // off the pipe
  const auto short_of_it = replanner.drove_through(p4, length, length / 2);   // to it, not through
  ASSERT_TRUE(short_of_it.has_value());
  EXPECT_TRUE(short_of_it->empty());
  ASSERT_EQ(replanner.learnt().blockages.size(), 1U);

  const auto through = replanner.drove_through(p4, length, 0);
  ASSERT_TRUE(through.has_value());
  ASSERT_EQ(through->size(), 1U);
  EXPECT_DOUBLE_EQ(through->front().offset_m, length / 2);
  EXPECT_TRUE(replanner.learnt().blockages.empty());
  const std::vector<Blockage>& closures = replanner.mission().blockages;
  ASSERT_EQ(closures.size(), 1U);  // the operator's stays
  EXPECT_DOUBLE_EQ(closures.front().offset_m, length / 4);
  const PlanResponse next = replanner.plan("on");
  EXPECT_NE(next.reason.find("the blockage in P4 at"), std::string::npos) << next.reason;
  EXPECT_EQ(replanner.plan("again").reason.find("the blockage in P4"), std::string::npos);
}

// A blockage or danger learnt at one place that an arrival showed was elsewhere moves there, in
// the world model and in what was learnt, and the next plan says so; an operator's closure, a
// place nothing was learnt at and a place off the map are left alone.
TEST(ReplannerDecision, ALearntClosureMovesWhereTheRobotFoundItWas) {
  const auto ais = testing::load_ais_testbed();
  Mission mission = ais.mission;
  const PipeId p4 = pipe_named(ais.map, "P4");
  const PipeId p6 = pipe_named(ais.map, "P6");
  mission.blockages.push_back({p4, 1.0});  // the operator's
  Replanner replanner(ais.map, mission);
  (void)replanner.plan();
  (void)replanner.report_failure({.kind = Failure::Kind::kBlockage, .pipe = p4, .offset_m = 7.9});
  (void)replanner.report_failure(
      {.kind = Failure::Kind::kDangerInPipe, .pipe = p4, .offset_m = 0.1});
  ASSERT_EQ(replanner.learnt().blockages.size(), 1U);
  ASSERT_EQ(replanner.learnt().danger_spots.size(), 1U);

  constexpr Failure::Kind kBlockage = Failure::Kind::kBlockage;
  constexpr Failure::Kind kDanger = Failure::Kind::kDangerInPipe;
  EXPECT_FALSE(replanner.move_learnt(kBlockage, {p4, 1.0}, {p6, 2.0}, "why"));   // the operator's
  EXPECT_FALSE(replanner.move_learnt(kBlockage, {p4, 5.0}, {p6, 2.0}, "why"));   // nothing there
  EXPECT_FALSE(replanner.move_learnt(kBlockage, {p4, 7.9}, {p6, 60.0}, "why"));  // beyond P6
  EXPECT_FALSE(replanner.move_learnt(kDanger, {p4, 7.9}, {p6, 2.0}, "why"));     // a blockage
  EXPECT_FALSE(replanner.move_learnt(kBlockage, {p4, 0.1}, {p6, 2.0}, "why"));   // a danger
  EXPECT_EQ(replanner.learnt().blockages.front(), (Blockage{p4, 7.9}));

  ASSERT_TRUE(replanner.move_learnt(kBlockage, {p4, 7.9}, {p6, 2.0}, "arrived at M6 out of P6"));
  ASSERT_TRUE(replanner.move_learnt(kDanger, {p4, 0.1}, {p6, 5.0}, "arrived at M7 out of P6"));
  EXPECT_EQ(replanner.learnt().blockages.front(), (Blockage{p6, 2.0}));
  EXPECT_EQ(replanner.learnt().danger_spots.front(), (Blockage{p6, 5.0}));
  const std::vector<Blockage>& closures = replanner.mission().blockages;
  ASSERT_EQ(closures.size(), 3U);
  EXPECT_EQ(closures[0], (Blockage{p4, 1.0}));  // the operator's stays
  EXPECT_EQ(closures[1], (Blockage{p6, 2.0}));
  EXPECT_EQ(closures[2], (Blockage{p6, 5.0}));
  const PlanResponse next = replanner.plan("on");
  EXPECT_NE(next.reason.find("the blockage in P4 at 7.90 m is in P6 at 2.00 m: arrived at M6"),
            std::string::npos)
      << next.reason;
  EXPECT_NE(next.reason.find("the danger in P4 at 0.10 m is in P6 at 5.00 m"), std::string::npos)
      << next.reason;
}

// Issue 14: a failure report with an unknown pipe aborted the whole process, even in a release
// build. Each bad report is now answered, naming what is wrong, and changes nothing.
TEST(ReplannerIssue14, BadFailureReportsAreAnsweredAsInvalidAndChangeNothing) {
  const auto ais = testing::load_ais_testbed();
  const PipeId p4 = pipe_named(ais.map, "P4");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<std::pair<Failure, std::string_view>> bad{
      {{.kind = Failure::Kind::kBlockage, .pipe = PipeId{9999}}, "unknown pipe #9999"},
      {{.kind = Failure::Kind::kDangerInPipe, .pipe = p4, .offset_m = -0.1}, "outside pipe P4"},
      {{.kind = Failure::Kind::kBlockage, .pipe = p4, .offset_m = 1e6}, "outside pipe P4"},
      {{.kind = Failure::Kind::kBlockage, .pipe = p4, .offset_m = nan}, "outside pipe P4"},
      {{.kind = Failure::Kind::kBlockage, .pipe = p4, .offset_m = inf}, "outside pipe P4"},
      {{.kind = Failure::Kind::kDangerousPassage, .manhole = ManholeId{4242}},
       "unknown manhole #4242"},
      {{.kind = Failure::Kind::kDangerousPassage,
        .manhole = ManholeId{0},
        .from = SlotIndex{0},
        .to = SlotIndex{77}},
       "not slot 78"},
      {{.kind = Failure::Kind::kDangerousPassage,
        .manhole = ManholeId{0},
        .from = SlotIndex{0},
        .to = SlotIndex{0}},
       "to itself"},
  };
  Replanner replanner(ais.map, ais.mission);
  const PlanResponse first = replanner.plan();
  for (const auto& [failure, message] : bad) {
    EXPECT_FALSE(check_failure(failure, ais.map).has_value()) << message;
    const PlanResponse r = replanner.report_failure(failure);
    EXPECT_EQ(r.decision, Decision::kInvalidReport) << message;
    EXPECT_NE(r.reason.find(message), std::string::npos) << r.reason;
  }
  EXPECT_EQ(replanner.mission().blockages, ais.mission.blockages);
  EXPECT_EQ(replanner.mission().closed_passages, ais.mission.closed_passages);
  EXPECT_EQ(replanner.plan().plan.steps, first.plan.steps);
}

TEST(ReplannerIssue14, BadProgressReportsAreErrorsAndKeepTheLastProgress) {
  const auto ais = testing::load_ais_testbed();
  Replanner replanner(ais.map, ais.mission);
  const domain::MissionProgress before = replanner.progress();
  const PipeId p4 = pipe_named(ais.map, "P4");
  auto with = [&](domain::RobotPosition position) {
    domain::MissionProgress p = before;
    p.position = position;
    return p;
  };
  domain::MissionProgress short_done = before;
  short_done.done.pop_back();
  domain::MissionProgress final_done_elsewhere = before;
  final_done_elsewhere.done.back() = true;  // 'end' is in P9; the robot starts in P12
  domain::MissionProgress nan_energy = before;
  nan_energy.energy_used_wh = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<domain::MissionProgress, std::string_view>> bad{
      {with(domain::InPipe{PipeId{123}, 0}), "unknown pipe #123"},
      {with(domain::InPipe{p4, -1}), "outside pipe P4"},
      {with(domain::InPipe{p4, std::numeric_limits<double>::infinity()}), "outside pipe P4"},
      {with(domain::AtSlot{ManholeId{0}, SlotIndex{50}}), "no slot 51"},
      {with(domain::InManhole{ManholeId{500}}), "unknown manhole #500"},
      {short_done, "2 done flags for 3 tasks"},
      {nan_energy, "energy used"},
      {final_done_elsewhere, "the final task 'end' is done, but the robot is in pipe P12"},
  };
  for (const auto& [progress, message] : bad) {
    const Result<void> r = replanner.update(progress, 1);
    ASSERT_FALSE(r.has_value()) << message;
    EXPECT_NE(r.error().message.find(message), std::string::npos) << r.error().message;
  }
  EXPECT_FALSE(replanner.update(before, 2).has_value());
  EXPECT_EQ(replanner.progress(), before);
  EXPECT_TRUE(replanner.update(with(domain::InPipe{p4, 1.0}), 0).has_value());
}

// A clock that moves on by a second each time it is read: any time limit is over at the first
// look, deterministically.
class TickingClock final : public Clock {
 public:
  double now_s() const override { return now_s_ += 1.0; }

 private:
  mutable double now_s_ = 0;
};

// Issue 14: a replan that reached its time limit was answered with the beacon. The acceptance
// case (a 1 microsecond limit on a generated network) answers degraded, heading to an exit along
// a valid route; the 100,000-manhole case is bench/executor/deadline_bench.cc.
TEST(ReplannerIssue14, AReplanOutOfTimeAnswersWithAValidPlanInsteadOfCallingTheBeacon) {
  auto map = generate_network({.manholes = 2000, .seed = 7, .topology = Topology::kMeshed});
  ASSERT_TRUE(map.has_value()) << map.error();
  auto mission = domain::generate_mission(*map, {.tasks = 8, .seed = 3});
  ASSERT_TRUE(mission.has_value()) << mission.error();
  TickingClock clock;
  // Greedy best-first search: an engine that asks its stop condition at every expansion.
  Replanner replanner(*map, *mission,
                      {.planner = {.algorithm = search::Algorithm::kGbfs,
                                   .time_limit_s = 1e-6,
                                   .improvement_expansions = 0},
                       .clock = &clock});
  const PlanResponse r = replanner.plan();
  // Issue 34: not the nearest exit any more, but the greedy insertion of the tasks, as safe.
  ASSERT_TRUE(has_plan(r.decision)) << r.reason;
  EXPECT_EQ(r.rung, PlanResponse::Rung::kGreedy) << r.reason;
  EXPECT_LT(r.newly_dropped.size(), mission->tasks.size());
  for (const auto& d : r.newly_dropped) {
    EXPECT_NE(d.reason.find("time ran out"), std::string::npos) << d.reason;
  }
  domain::MissionProgress start = replanner.progress();
  for (const auto& d : replanner.dropped()) start.done[d.task.index()] = true;
  const auto report = domain::validate_plan(r.plan, *map, replanner.mission(), start);
  EXPECT_TRUE(report.valid) << report.error;
  // Without a limit the same mission does tasks.
  Replanner unlimited(*map, *mission);
  EXPECT_TRUE(has_plan(unlimited.plan().decision));
}

// Issue 34: the anytime ladder. A clock that stands still until the test lets it tick: the plans
// before that never reach their time limit, every one after it does at the first look.
class StepClock final : public Clock {
 public:
  double now_s() const override { return now_s_ += step_s_; }
  void tick() { step_s_ = 1.0; }

 private:
  double step_s_ = 0;
  mutable double now_s_ = 0;
};

// What every answer of the ladder must be: a plan valid on the world model as it is now, from
// where the robot is, ending the mission (at an exit or its end point) within the battery left
// above the reserve.
void expect_safe(const PlanResponse& r, const Replanner& replanner, const SewerMap& map) {
  ASSERT_TRUE(has_plan(r.decision)) << r.reason;
  domain::MissionProgress start = replanner.progress();
  for (const auto& d : replanner.dropped()) start.done[d.task.index()] = true;
  const auto report = domain::validate_plan(r.plan, map, replanner.mission(), start);
  EXPECT_TRUE(report.valid) << report.error;
  const Mission& m = replanner.mission();
  EXPECT_LE(report.energy_wh,
            m.profile.battery_wh * (1 - m.battery_reserve_fraction) - start.energy_used_wh + 1e-9);
}

TEST(ReplannerAnytime, EveryRungHasAStableNameThatParsesBack) {
  using Rung = PlanResponse::Rung;
  const std::vector<std::pair<Rung, std::string_view>> names{{Rung::kSearch, "search"},
                                                             {Rung::kBestSoFar, "best-so-far"},
                                                             {Rung::kCurrentPlan, "current-plan"},
                                                             {Rung::kRepairedPlan, "repaired-plan"},
                                                             {Rung::kGreedy, "greedy"},
                                                             {Rung::kNearestExit, "nearest-exit"}};
  for (const auto& [rung, name] : names) {
    EXPECT_EQ(to_string(rung), name);
    EXPECT_EQ(parse_rung(name), rung) << name;
  }
  EXPECT_EQ(parse_rung("nearest exit"), std::nullopt);
}

// Out of time at the first plan, with no current plan to keep or repair: the greedy insertion
// does the tasks (before issue 34 the robot headed for the nearest exit and did none).
TEST(ReplannerAnytime, OutOfTimeWithoutACurrentPlanTheGreedyInsertionDoesTheTasks) {
  const auto ais = testing::load_ais_testbed();
  StepClock clock;
  clock.tick();
  Replanner replanner(
      ais.map, ais.mission,
      {.planner = {.time_limit_s = 1e-6, .improvement_expansions = 0}, .clock = &clock});
  const PlanResponse r = replanner.plan();
  EXPECT_EQ(r.rung, PlanResponse::Rung::kGreedy) << r.reason;
  EXPECT_EQ(r.decision, Decision::kFollowPlan) << r.reason;
  EXPECT_EQ(r.goals.size(), ais.mission.tasks.size());
  EXPECT_NE(r.reason.find("cheapest insertion"), std::string::npos) << r.reason;
  expect_safe(r, replanner, ais.map);
  // The same inputs, the same answer.
  StepClock again;
  again.tick();
  Replanner twin(ais.map, ais.mission,
                 {.planner = {.time_limit_s = 1e-6, .improvement_expansions = 0}, .clock = &again});
  EXPECT_EQ(twin.plan().plan.steps, r.plan.steps);
}

// Out of time where the current plan no longer holds (the robot is somewhere it never went): its
// tasks left, in its order, on new routes from there.
TEST(ReplannerAnytime, OutOfTimeWhereTheCurrentPlanNoLongerHoldsItIsRepaired) {
  auto map = generate_network({.manholes = 300, .seed = 2, .topology = Topology::kMeshed});
  ASSERT_TRUE(map.has_value()) << map.error();
  auto mission = domain::generate_mission(
      *map, {.tasks = 6, .seed = 2, .spread = domain::MissionSpread::kNearExit});
  ASSERT_TRUE(mission.has_value()) << mission.error();
  StepClock clock;
  Replanner replanner(
      *map, *mission,
      {.planner = {.time_limit_s = 1e-6, .improvement_expansions = 0}, .clock = &clock});
  const PlanResponse first = replanner.plan();
  ASSERT_EQ(first.rung, PlanResponse::Rung::kSearch) << first.reason;
  ASSERT_TRUE(has_plan(first.decision)) << first.reason;
  // The robot is halfway along a pipe at its start manhole: no state of the plan.
  domain::MissionProgress moved = replanner.progress();
  const domain::RobotPosition& was = moved.position;
  ASSERT_FALSE(std::holds_alternative<domain::InPipe>(was));
  const ManholeId m = std::holds_alternative<domain::InManhole>(was)
                          ? std::get<domain::InManhole>(was).manhole
                          : std::get<domain::AtSlot>(was).manhole;
  std::optional<PipeId> beside;
  for (PipeId p : map->pipe_ids()) {
    for (const auto& end : map->pipe(p).ends) {
      if (end.manhole == m && !beside) beside = p;
    }
  }
  ASSERT_TRUE(beside.has_value());
  moved.position = domain::InPipe{*beside, map->pipe(*beside).length_m / 2};
  ASSERT_TRUE(replanner.update(moved, 0).has_value());
  clock.tick();
  const PlanResponse r = replanner.plan("moved");
  EXPECT_EQ(r.rung, PlanResponse::Rung::kRepairedPlan) << r.reason;
  expect_safe(r, replanner, *map);
  EXPECT_FALSE(r.goals.empty());
  // The tasks it does are the first plan's, in the first plan's order.
  auto order = [&](const PlanResponse& p, const domain::MissionProgress& from) {
    domain::MissionProgress start = from;
    for (const auto& d : replanner.dropped()) start.done[d.task.index()] = true;
    domain::PlanReplay replay(*map, replanner.mission(), start);
    std::vector<TaskId> done;
    for (const auto& step : p.plan.steps) {
      if (!replay.apply(step).has_value()) break;
      for (TaskId t : replanner.mission().task_ids()) {
        if (!start.done[t.index()] && replay.done()[t.index()] &&
            std::find(done.begin(), done.end(), t) == done.end()) {
          done.push_back(t);
        }
      }
    }
    return done;
  };
  const std::vector<TaskId> before = order(first, domain::initial_progress(*mission, *map));
  const std::vector<TaskId> after = order(r, replanner.progress());
  EXPECT_EQ(after, before);
}

TEST(ReplannerIssue14, AReplanThatIsCancelledHeadsForAnExitInsteadOfCallingTheBeacon) {
  const auto ais = testing::load_ais_testbed();
  std::atomic<bool> cancel{true};
  Replanner replanner(ais.map, ais.mission,
                      {.planner = {.cancel = &cancel, .improvement_expansions = 0}});
  const PlanResponse r = replanner.plan();
  ASSERT_EQ(r.decision, Decision::kDegraded) << r.reason;
  // The cancel stops the repaired plan and the greedy insertion too: the nearest exit.
  EXPECT_EQ(r.rung, PlanResponse::Rung::kNearestExit);
  EXPECT_EQ(r.end.rfind("exit ", 0), 0U) << r.end;
  EXPECT_NE(r.newly_dropped.front().reason.find("cancelled"), std::string::npos);
  expect_safe(r, replanner, ais.map);
}

TEST(ReplannerIssue14, OnlyAProofThatNoExitCanBeReachedCallsTheBeacon) {
  const auto ais = testing::load_ais_testbed();
  Replanner replanner(ais.map, ais.mission);
  (void)replanner.plan();
  // The robot starts in P12: both ends of it blocked.
  const PipeId p12 = pipe_named(ais.map, "P12");
  const double x = std::get<domain::InPipe>(replanner.progress().position).offset_m;
  (void)replanner.report_failure(
      {.kind = Failure::Kind::kBlockage, .pipe = p12, .offset_m = x + 0.5});
  const PlanResponse r = replanner.report_failure(
      {.kind = Failure::Kind::kBlockage, .pipe = p12, .offset_m = x - 0.5});
  EXPECT_EQ(r.decision, Decision::kCallForRecovery) << r.reason;
}

// Issue 35: a Replanner given the map's routing index made beforehand (domain/route_index.h)
// plans and replans as one without it, and refuses an index of another robot.
TEST(ReplannerRouteIndex, PlansAndReplansAsWithoutOneAndRefusesAStaleOne) {
  const SewerMap map =
      *generate_network({.manholes = 1500, .seed = 4, .topology = Topology::kMeshed});
  const Mission mission = *domain::generate_mission(
      map, {.tasks = 10, .seed = 3, .spread = domain::MissionSpread::kUniform});
  const Result<domain::RouteIndex> index =
      domain::RouteIndex::build(map, mission.profile, mission.passage_motion);
  ASSERT_TRUE(index.has_value()) << index.error().message;
  Replanner with(map, mission);
  ASSERT_TRUE(with.use_route_index(*index).has_value());
  Replanner without(map, mission);
  const PlanResponse a = with.plan();
  const PlanResponse b = without.plan();
  ASSERT_EQ(a.decision, b.decision) << a.reason;
  EXPECT_EQ(a.plan.steps, b.plan.steps);
  // A blockage half-way along the first pipe the plan drives after its fifth step.
  std::optional<PipeId> blocked;
  for (std::size_t i = 5; i < a.plan.steps.size() && !blocked; ++i) {
    if (const auto* d = std::get_if<domain::DrivePipeToManhole>(&a.plan.steps[i]))
      blocked = d->pipe;
  }
  ASSERT_TRUE(blocked.has_value());
  const Failure failure{.kind = Failure::Kind::kBlockage,
                        .pipe = *blocked,
                        .offset_m = map.pipe(*blocked).length_m / 2};
  const PlanResponse c = with.report_failure(failure);
  const PlanResponse d = without.report_failure(failure);
  EXPECT_EQ(c.decision, d.decision) << c.reason;
  EXPECT_EQ(c.plan.steps, d.plan.steps);
  // An index of another robot's moves.
  Mission plus = mission;
  plus.profile =
      *builtin_profile(mission.profile.name == "makro-plus" ? "makro-1.1" : "makro-plus");
  Replanner other(map, plus);
  const Result<void> stale = other.use_route_index(*index);
  ASSERT_FALSE(stale.has_value());
  EXPECT_NE(stale.error().message.find("is stale"), std::string::npos) << stale.error().message;
}

}  // namespace
}  // namespace sewerplan::executor
