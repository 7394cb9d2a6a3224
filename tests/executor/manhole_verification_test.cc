// SPDX-License-Identifier: MIT
// Issue 29: a robot on a wrong map with slipping wheels. The simulated robot drives a true world
// drawn from the map (hal/world_errors.h) and senses it; the executor plans on the map, takes a
// finished drive to a manhole as the arrival there, and checks every observed arrival against the
// plan's manhole with the topological filter (docs/localisation.md).
#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/sim_robot.h"
#include "sewerplan/hal/world_errors.h"

#include "support/ais_testbed.h"
#include "support/small_map.h"

namespace sewerplan::executor {
namespace {

struct WorldRun {
  MissionReport report;
  std::vector<std::string> replans;  // the reasons of the replans
  std::size_t passes = 0;        // turns by sighting done: passes through a manhole the map lacks
  std::size_t arrivals = 0;      // arrival events the controller settled on a mapped manhole
  std::size_t wrong = 0;         // of those, where the robot really was at another manhole
  std::set<std::string> checks;  // the arrival checks seen
  Learnt learnt;                 // what the Replanner learnt
  std::vector<FailureEvent> failures;
};

// The paper's mission in a world drawn by `spec` and `seed`; every arrival event's manhole is
// compared with the simulator's truth at that moment.
WorldRun run_in_world(const testing::AisTestbed& ais, const std::string& spec, std::uint64_t seed,
                      bool sensing = true) {
  const Result<hal::WorldErrorProfile> profile = hal::parse_world_errors(spec);
  EXPECT_TRUE(profile.has_value()) << spec;
  const Result<hal::TrueWorld> truth = hal::make_true_world(ais.map, *profile, seed);
  EXPECT_TRUE(truth.has_value());
  ManualClock clock;
  Replanner replanner(ais.map, ais.mission, {.clock = &clock});
  const auto& in = std::get<domain::InPipe>(replanner.progress().position);
  hal::SimRobot robot(
      truth->world, ais.mission.profile,
      hal::world_pose(ais.map, *truth,
                      hal::InPipe{in.pipe, in.offset_m, hal::Heading::kTowardsEnd1}),
      {}, sensing ? hal::SimOptions{.sensing = hal::make_sensing(*truth)} : hal::SimOptions{});
  Executor executor(ais.map, replanner, robot);
  WorldRun run;
  executor.subscribe([&](const Event& e) {
    if (const auto* plan = std::get_if<PlanEvent>(&e.what); plan != nullptr && plan->replan)
      run.replans.push_back(plan->reason);
    if (const auto* job = std::get_if<JobEvent>(&e.what)) {
      if (job->ok && job->job.rfind("TurnInManhole(arrival -> mouth", 0) == 0) ++run.passes;
    }
    if (const auto* failure = std::get_if<FailureEvent>(&e.what)) run.failures.push_back(*failure);
    const auto* arrival = std::get_if<ArrivalEvent>(&e.what);
    if (arrival == nullptr) return;
    run.checks.insert(arrival->check);
    if (arrival->manhole.empty()) return;
    ++run.arrivals;
    const auto* at = std::get_if<hal::AtSlot>(&robot.pose());
    if (at == nullptr || truth->world.manhole(at->manhole).name != arrival->manhole) ++run.wrong;
  });
  run.report = executor.run();
  run.learnt = replanner.learnt();
  return run;
}

TEST(ManholeVerification, LengthsOffAndSlippingWheelsStillEndTheMissionAsInAnExactWorld) {
  const testing::AisTestbed ais = testing::load_ais_testbed();
  const WorldRun exact = run_in_world(ais, "none", 1);
  ASSERT_EQ(exact.report.outcome, MissionReport::Outcome::kEnded) << exact.report;
  EXPECT_EQ(exact.arrivals, 0U);  // an exact world observes nothing
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const WorldRun r = run_in_world(ais, "lengths=1,length_rel=0.2,drift=0.03", seed);
    EXPECT_EQ(r.report.outcome, MissionReport::Outcome::kEnded) << "seed " << seed << r.report;
    EXPECT_EQ(r.report.tasks_done, exact.report.tasks_done) << "seed " << seed << r.report;
    EXPECT_GT(r.arrivals, 0U);
    EXPECT_EQ(r.wrong, 0U) << "seed " << seed;
  }
}

// Manholes missed six times as often as the realistic profile's 5 %: the robot drives through
// them where it can; the controller notices from the odometry (a drive to a manhole that went
// past it, the filter placing the robot in the pipe beyond) or at the next manhole from its
// signature. The issue's goal is 99.5 % of arrivals at the true manhole; over these 30 worlds (142
// arrivals) none is wrong. (Before the filter held a robot at the manhole it drove on into, one
// was: in world 26 the robot, put back at M5 after driving through it, oscillated between P4 and
// P13 and settled on M11.)
TEST(ManholeVerification, ArrivalsTheControllerSettlesOnAreTheTrueManholes) {
  const testing::AisTestbed ais = testing::load_ais_testbed();
  std::size_t arrivals = 0;
  std::size_t wrong = 0;
  std::size_t driven_through = 0;
  std::set<std::string> checks;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    const WorldRun r = run_in_world(ais, "realistic,missed=0.3", seed);
    arrivals += r.arrivals;
    wrong += r.wrong;
    checks.insert(r.checks.begin(), r.checks.end());
    driven_through += static_cast<std::size_t>(
        std::count_if(r.replans.begin(), r.replans.end(), [](const std::string& why) {
          return why.rfind("the robot is in pipe", 0) == 0 &&
                 why.find(", the plan has it at M") != std::string::npos;
        }));
    EXPECT_NE(r.report.outcome, MissionReport::Outcome::kHalted);
  }
  EXPECT_GT(arrivals, 100U);
  EXPECT_LE(wrong * 100, arrivals) << wrong << " of " << arrivals << " arrivals";
  // A manhole driven through unseen was noticed, and a manhole the map lacks.
  EXPECT_GT(driven_through, 0U);
  EXPECT_EQ(checks.count("unmapped-junction"), 1U);
}

bool any_starts_with(const std::vector<std::string>& texts, const std::string& prefix) {
  return std::any_of(texts.begin(), texts.end(),
                     [&](const std::string& t) { return t.rfind(prefix, 0) == 0; });
}

// A manhole the map lacks in a pipe the plan drives: the robot stops at it (it sees a manhole),
// passes it straight on by the mouth it saw opposite the one it came out of, and the drive goes
// on beyond it, rear first as front first.
TEST(ManholeVerification, AManholeTheMapLacksIsPassedStraightOn) {
  const testing::AisTestbed ais = testing::load_ais_testbed();
  const WorldRun exact = run_in_world(ais, "none", 1);
  std::size_t passed = 0;
  std::size_t as_exact = 0;
  std::size_t remembered = 0;  // runs whose filter remembered a junction for the next mission
  // What the filter remembered of the pipes joins what the robot learnt (Learnt::junctions).
  EXPECT_FALSE(exact.learnt.junctions.driven.empty());
  EXPECT_TRUE(exact.learnt.junctions.junctions.empty());
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const WorldRun r = run_in_world(ais, "junctions=0.5", seed);
    if (!r.learnt.junctions.junctions.empty()) ++remembered;
    EXPECT_NE(r.report.outcome, MissionReport::Outcome::kHalted) << "seed " << seed;
    if (r.report.outcome == MissionReport::Outcome::kEnded &&
        r.report.tasks_done == exact.report.tasks_done) {
      ++as_exact;
    }
    if (r.passes > 0) ++passed;
  }
  EXPECT_GE(as_exact, 8U);
  EXPECT_GE(passed, 3U);
  EXPECT_GE(remembered, 1U);
}

// A lateral the world lacks at a manhole the plan turns through: the robot sees a mouth fewer,
// takes that pipe as closed at this end and plans again, rather than asking the robot for a turn
// into a mouth that is not there (which it refuses: stuck, the beacon). Every passage into and
// out of that mouth is closed too: with the blockage alone, the mouth itself stayed a place to
// turn through, and on the official ISYBAU sample the plan reversed the robot's heading there.
TEST(ManholeVerification, AMouthTheWorldLacksClosesItsPipeThere) {
  const testing::AisTestbed ais = testing::load_ais_testbed();
  std::size_t closed = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const WorldRun r = run_in_world(ais, "laterals_missing=1", seed);
    EXPECT_NE(r.report.beacon_cause, BeaconCause::kStuck) << "seed " << seed << r.report;
    if (any_starts_with(r.replans, "blockage in")) ++closed;
  }
  EXPECT_GE(closed, 1U);
}

// M1 -P1- M2 -P2- M3 along a street, both ends exits, and P3 north from M2 to M4, with a sample in
// it; in the sewer, M2 has no mouth for P3 (P3 stops blind short of it).
struct StreetWithoutP3Mouth {
  SewerMap map = testing::SmallMap()
                     .manhole("M1", 0, 0, /*exit=*/true)
                     .manhole("M2", 30, 0)
                     .manhole("M3", 60, 0, /*exit=*/true)
                     .manhole("M4", 30, 30)
                     .pipe("P1", "M1", "M2")
                     .pipe("P2", "M2", "M3")
                     .pipe("P3", "M2", "M4")
                     .build();
  Mission mission = sample_in_p3(map);
  Result<hal::TrueWorld> truth = without_laterals(map);
  ManholeId m2 = *map.find_manhole("M2");
  PipeId p3 = *map.find_pipe("P3");

  static Result<hal::TrueWorld> without_laterals(const SewerMap& map) {
    const Result<hal::WorldErrorProfile> profile = hal::parse_world_errors("laterals_missing=1");
    if (!profile.has_value()) return profile.error();
    return hal::make_true_world(map, *profile, 1);
  }
  static Mission sample_in_p3(const SewerMap& map) {
    Mission mission = testing::small_mission(map, "M1");
    testing::add_task(mission, map, "sample", TaskKind::kTakeWaterSample, "P3", 10.0);
    return mission;
  }
  // Every passage of M2 into or out of P3's mouth, as the Replanner learns them closed.
  std::vector<ClosedPassage> passages_through_p3() const {
    const SlotIndex p3_mouth = map.pipe(p3).ends[0].slot;
    std::vector<ClosedPassage> out;
    for (std::uint16_t s = 0; s < 3; ++s) {
      if (s != p3_mouth.value()) out.push_back({m2, p3_mouth, SlotIndex{s}});
    }
    return out;
  }
};

// StreetWithoutP3Mouth: arriving in M2, the robot sees a mouth fewer: P3 is closed just inside it,
// and every passage of M2 into or out of P3's mouth is closed as learnt, so no plan turns through a
// mouth that is not there.
TEST(ManholeVerification, AMouthTheWorldLacksClosesEveryPassageThroughIt) {
  const StreetWithoutP3Mouth street;
  ASSERT_TRUE(street.truth.has_value());
  const SewerMap& map = street.map;
  const Mission& mission = street.mission;
  const Result<hal::TrueWorld>& truth = street.truth;
  const ManholeId m2 = street.m2;
  ASSERT_EQ(truth->world.manhole(m2).slot_count, 2U);  // P3's mouth is gone
  ManualClock clock;
  Replanner replanner(map, mission, {.clock = &clock});
  hal::SimRobot robot(truth->world, mission.profile, hal::InManhole{*map.find_manhole("M1")}, {},
                      hal::SimOptions{.sensing = hal::make_sensing(*truth)});
  Executor executor(map, replanner, robot);
  std::size_t robot_errors = 0;
  executor.subscribe([&](const Event& e) {
    if (std::holds_alternative<ErrorEvent>(e.what)) ++robot_errors;
  });
  const MissionReport report = executor.run();
  EXPECT_EQ(report.outcome, MissionReport::Outcome::kEnded) << report;
  EXPECT_EQ(robot_errors, 0U) << report;
  EXPECT_EQ(replanner.learnt().closed_passages, street.passages_through_p3());
  ASSERT_EQ(replanner.learnt().blockages.size(), 1U);
  EXPECT_EQ(replanner.learnt().blockages.front().pipe, *map.find_pipe("P3"));
}

// The same map and world, on a robot that observes nothing: its arrival in M2 is not checked, and
// the plan turns it into P3's mouth, which the sewer lacks. The robot refuses the turn as no-mouth
// (a blockage of that passage); no recovery row is tried (none makes a mouth), every passage of
// M2 into P3's mouth is closed as learnt, P3 just inside it, and the plan is made again from M2,
// where the robot stands: it gives the sample up and leaves by an exit. Until 2026-12-07 the
// refusal was invalid-job: the robot was held and the beacon called `stuck` (before that, it was
// relocalised into P1, where it was not).
TEST(ManholeVerification, IssueNoMouthATurnIntoAMouthTheSewerLacksClosesItAndGoesOn) {
  const StreetWithoutP3Mouth street;
  ASSERT_TRUE(street.truth.has_value());
  const SewerMap& map = street.map;
  const Mission& mission = street.mission;
  const Result<hal::TrueWorld>& truth = street.truth;
  const ManholeId m2 = street.m2;
  const PipeId p3 = street.p3;
  ASSERT_EQ(truth->world.manhole(m2).slot_count, 2U);  // P3's mouth is gone
  ManualClock clock;
  Replanner replanner(map, mission, {.clock = &clock});
  hal::SimRobot robot(truth->world, mission.profile, hal::InManhole{*map.find_manhole("M1")});
  Executor executor(map, replanner, robot);
  std::vector<ErrorEvent> errors;
  std::vector<FailureEvent> failures;
  std::size_t recoveries = 0;
  executor.subscribe([&](const Event& e) {
    if (const auto* error = std::get_if<ErrorEvent>(&e.what)) errors.push_back(*error);
    if (const auto* failure = std::get_if<FailureEvent>(&e.what)) failures.push_back(*failure);
    if (std::holds_alternative<RecoveryEvent>(e.what)) ++recoveries;
  });
  const MissionReport report = executor.run();
  EXPECT_EQ(report.outcome, MissionReport::Outcome::kEnded) << report;
  ASSERT_EQ(errors.size(), 1U) << report;
  EXPECT_EQ(errors.front().kind, hal::RobotErrorKind::kBlockage);
  EXPECT_EQ(recoveries, 0U) << report;
  ASSERT_EQ(failures.size(), 1U) << report;
  EXPECT_EQ(failures.front().kind, Failure::Kind::kBlockage);
  EXPECT_EQ(failures.front().detail.rfind("no mouth of P3 in M2: ", 0), 0U)
      << failures.front().detail;
  EXPECT_EQ(replanner.learnt().closed_passages, street.passages_through_p3());
  ASSERT_EQ(replanner.learnt().blockages.size(), 1U);
  EXPECT_EQ(replanner.learnt().blockages.front().pipe, p3);
  // At an exit, M1 or M3, by the mouths M2 has.
  const auto* at = std::get_if<hal::AtSlot>(&robot.pose());
  ASSERT_NE(at, nullptr) << report;
  EXPECT_TRUE(at->manhole == *map.find_manhole("M1") || at->manhole == *map.find_manhole("M3"))
      << report;
}

// Laterals missing at half the manholes that have one to lose, on the paper's mission, with a
// robot that observes nothing (no arrival shows a mouth missing): in 6 of these 20 worlds the plan
// turns the robot into M6's mouth of P6, which the sewer lacks. The robot refuses as no-mouth, the
// controller closes that mouth and plans around it, and every run ends at an exit. Until
// 2026-12-07 each such refusal held the robot (invalid-job: beacon `stuck`).
TEST(ManholeVerification, IssueNoMouthUnobservedMissingLateralsNeverHoldTheRobot) {
  const testing::AisTestbed ais = testing::load_ais_testbed();
  std::size_t no_mouth = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const WorldRun r = run_in_world(ais, "laterals_missing=0.5", seed, /*sensing=*/false);
    EXPECT_EQ(r.report.outcome, MissionReport::Outcome::kEnded) << "seed " << seed << r.report;
    no_mouth += static_cast<std::size_t>(std::count_if(
        r.failures.begin(), r.failures.end(),
        [](const FailureEvent& f) { return f.detail.rfind("no mouth of P6 in M6: ", 0) == 0; }));
  }
  EXPECT_GE(no_mouth, 5U);
}

// M1 -P1 (40 m)- M2, M1 the only exit, a sample 36 m along P1; in the sewer, P1 has a manhole the
// map lacks 12-28 m along, and an obstacle 1.5 m beyond it. The robot passes the junction, meets
// the obstacle, gives the sample up and backs out to M1: it meets the junction again, rear first,
// passes it and drives on, now front first, to the exit. The junction was closed as a blockage
// behind the robot instead (the robot, shut in between it and the obstacle, called for recovery),
// and before that the plan sent it backing into the junction's shaft, which it refused (stuck).
TEST(ManholeVerification, BackingOutPastAManholeTheMapLacksReachesTheExit) {
  const SewerMap map = testing::SmallMap()
                           .manhole("M1", 0, 0, /*exit=*/true)
                           .manhole("M2", 40, 0)
                           .pipe("P1", "M1", "M2")
                           .build();
  Mission mission = testing::small_mission(map, "M1");
  testing::add_task(mission, map, "sample", TaskKind::kTakeWaterSample, "P1", 36.0);
  const Result<hal::WorldErrorProfile> profile = hal::parse_world_errors("junctions=1");
  ASSERT_TRUE(profile.has_value());
  const Result<hal::TrueWorld> truth = hal::make_true_world(map, *profile, 1);
  ASSERT_TRUE(truth.has_value());
  ASSERT_EQ(truth->splits.size(), 1U);
  hal::FaultScenario faults;
  faults.obstacles.push_back({.pipe = truth->splits.front().rest, .offset_m = 1.5});
  ManualClock clock;
  Replanner replanner(map, mission, {.clock = &clock});
  hal::SimRobot robot(truth->world, mission.profile, hal::InManhole{*map.find_manhole("M1")},
                      std::move(faults), hal::SimOptions{.sensing = hal::make_sensing(*truth)});
  Executor executor(map, replanner, robot);
  std::size_t passes = 0;
  executor.subscribe([&](const Event& e) {
    if (const auto* job = std::get_if<JobEvent>(&e.what)) {
      if (job->ok && job->job.rfind("TurnInManhole(arrival -> mouth", 0) == 0) ++passes;
    }
  });
  const MissionReport report = executor.run();
  EXPECT_EQ(report.outcome, MissionReport::Outcome::kEnded) << report;
  EXPECT_EQ(passes, 2U) << report;
  EXPECT_EQ(
      robot.pose(),
      (hal::SimPose{hal::AtSlot{*map.find_manhole("M1"), SlotIndex{0}, hal::Facing::kIntoManhole}}))
      << report;
}

// M1 -P1 (20 m)- M2 -P2 (20 m)- M3, both ends exits, a task in P2; the robot starts in the middle
// of P1 facing M2, on a simulated robot that sees no manhole at all (every arrival missed).
struct MissingEveryManhole {
  SewerMap map = testing::SmallMap()
                     .manhole("M1", 0, 0, /*exit=*/true)
                     .manhole("M2", 20, 0)
                     .manhole("M3", 40, 0, /*exit=*/true)
                     .pipe("P1", "M1", "M2")
                     .pipe("P2", "M2", "M3")
                     .build();
  Mission mission = [this] {
    Mission m = testing::small_mission(map, "P1");
    testing::add_task(m, map, "inspect-P2", TaskKind::kInspectPipe, "P2");
    return m;
  }();
  ManualClock clock;
  Replanner replanner{map, mission, {.clock = &clock}};

  hal::SimRobot robot(hal::FaultScenario faults = {}) const {
    const auto& in = std::get<domain::InPipe>(replanner.progress().position);
    return hal::SimRobot(
        map, mission.profile, hal::InPipe{in.pipe, in.offset_m, hal::Heading::kTowardsEnd1},
        std::move(faults), hal::SimOptions{.sensing = {.missed_share = 1.0, .observe = true}});
  }
};

// The robot drives through M2 without seeing it (every manhole goes unseen here) and meets an
// obstacle 4 m into P2. The tracking has it at the end of P1 (a drive to M2 that saw none); the
// filter, by the distance driven, in P2. The blockage is P2's: closing P1 instead cut the robot's
// own way back (a 1,000-manhole meshed campaign: beacons where an exit was in reach).
TEST(ManholeVerification, AnObstacleBeyondAManholePassedUnseenClosesThePipeItIsIn) {
  MissingEveryManhole w;
  hal::FaultScenario faults;
  faults.obstacles.push_back({.pipe = *w.map.find_pipe("P2"), .offset_m = 4.0});
  hal::SimRobot robot = w.robot(faults);
  Executor executor(w.map, w.replanner, robot);
  std::vector<FailureEvent> failures;
  executor.subscribe([&](const Event& e) {
    if (const auto* f = std::get_if<FailureEvent>(&e.what)) failures.push_back(*f);
  });
  const MissionReport report = executor.run();
  EXPECT_NE(report.outcome, MissionReport::Outcome::kHalted);
  ASSERT_FALSE(failures.empty());
  const auto* where = std::get_if<FailureEvent::InPipe>(&failures.front().where);
  ASSERT_NE(where, nullptr);
  EXPECT_EQ(where->pipe, "P2") << failures.front().detail;
  EXPECT_NEAR(where->offset_m, 3.95, 0.5) << failures.front().detail;
  EXPECT_NE(failures.front().detail.find("not in pipe P1"), std::string::npos)
      << failures.front().detail;
}

// The robot drives through M2 unseen and on, 4.5 m into P2, where its drive to M2 reaches its
// bound: "no manhole seen". The localisation believes it in P2, past M2; the controller plans
// again from there at once. It used to back up and retry, driving on 2 m each time, away from
// the manhole it missed, and then closed the pipe as blocked.
TEST(ManholeVerification, ADriveThatMissedItsManholeIsPlannedOnFromBeyondIt) {
  MissingEveryManhole w;
  hal::SimRobot robot = w.robot();
  Executor executor(w.map, w.replanner, robot);
  std::vector<std::string> replans;
  std::size_t recoveries_before = 0;
  std::size_t failures_before = 0;
  executor.subscribe([&](const Event& e) {
    if (const auto* plan = std::get_if<PlanEvent>(&e.what); plan != nullptr && plan->replan)
      replans.push_back(plan->reason);
    if (!replans.empty()) return;
    if (std::holds_alternative<RecoveryEvent>(e.what)) ++recoveries_before;
    if (std::holds_alternative<FailureEvent>(e.what)) ++failures_before;
  });
  (void)executor.run();
  ASSERT_FALSE(replans.empty());
  EXPECT_NE(replans.front().find("the robot is in pipe P2"), std::string::npos) << replans.front();
  EXPECT_EQ(recoveries_before, 0U) << replans.front();
  EXPECT_EQ(failures_before, 0U) << replans.front();
}

// M1 (an exit) -P1 (20 m)- M2 -P2 (20 m)- M3, and P3 from M2 north to M4; a task in P3. A danger
// in P2 was learnt at 3.0 m (from M3's side, before). The robot starts in the middle of P1 facing
// M2 and sees no manhole: it drives through M2 straight on into P2 and meets a danger at 4.0 m,
// the one learnt, from this side. The filter settles it 0.95 m beyond the learnt danger (the
// learning was 1 m off), but it cannot have passed that: it is there, and it backs out to M1.
// Closed where the filter put it, the robot sat between two dangers: the beacon (the meshed
// 1,000-manhole network, realistic world, seed 4, run 19).
TEST(ManholeVerification, ADangerMetAgainPastAMissedManholeIsWhereItWasLearnt) {
  const SewerMap map = testing::SmallMap()
                           .manhole("M1", 0, 0, /*exit=*/true)
                           .manhole("M2", 20, 0)
                           .manhole("M3", 40, 0)
                           .manhole("M4", 20, 20)
                           .pipe("P1", "M1", "M2")
                           .pipe("P2", "M2", "M3")
                           .pipe("P3", "M2", "M4")
                           .build();
  Mission mission = testing::small_mission(map, "P1");
  testing::add_task(mission, map, "inspect-P3", TaskKind::kInspectPipe, "P3");
  ManualClock clock;
  Replanner replanner{map, mission, {.clock = &clock}};
  const PipeId p2 = *map.find_pipe("P2");
  ASSERT_TRUE(replanner.learn(Learnt{.danger_spots = {{p2, 3.0}}}).has_value());
  hal::FaultScenario faults;
  faults.danger_spots.push_back({.pipe = p2, .offset_m = 4.0});
  const auto& in = std::get<domain::InPipe>(replanner.progress().position);
  hal::SimRobot robot(map, mission.profile,
                      hal::InPipe{in.pipe, in.offset_m, hal::Heading::kTowardsEnd1}, faults,
                      hal::SimOptions{.sensing = {.missed_share = 1.0, .observe = true}});
  Executor executor(map, replanner, robot);
  std::vector<FailureEvent> failures;
  executor.subscribe([&](const Event& e) {
    if (const auto* f = std::get_if<FailureEvent>(&e.what)) failures.push_back(*f);
  });
  const MissionReport report = executor.run();
  EXPECT_EQ(report.outcome, MissionReport::Outcome::kEnded) << report;
  EXPECT_EQ(report.end, "exit M1") << report;
  ASSERT_FALSE(failures.empty());
  const auto* where = std::get_if<FailureEvent::InPipe>(&failures.front().where);
  ASSERT_NE(where, nullptr);
  EXPECT_EQ(where->pipe, "P2") << failures.front().detail;
  EXPECT_DOUBLE_EQ(where->offset_m, 3.0) << failures.front().detail;
}

}  // namespace
}  // namespace sewerplan::executor
