// SPDX-License-Identifier: MIT
// Probabilities that learn (issue 34; docs/executor.md): a hazard of the condition data the robot
// drives past safely has its blockage probability lowered by the Beta update of learnt.h, one it
// meets as a blockage becomes certain; the Replanner keeps both in what it learnt, a replan weighs
// them, and the executor logs each update as a "hazard" event.
#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/core/clock.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/executor/event_json.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/executor/learnt.h"
#include "sewerplan/executor/replanner.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"

#include "support/small_map.h"

namespace sewerplan::executor {
namespace {

// S (the exit) -- X -- T in a line: from S to X a short pipe with roots at 5 m (p0 = 0.1) and a
// safe one 90 m longer (300 s more at makro-1.1's 0.3 m/s); a task halfway along P, the pipe
// from X to the dead end T.
// Risk-aware (domain::kDefaultRiskCosts): on the way to T a stop in RISKY costs 0.1 x 600 s = 60 s
// expected, less than the detour: RISKY. On the way back to the exit it costs 0.1 x 3600 s = 360 s,
// more than the detour: SAFE. After one safe pass (prior strength 2) the probability is
// 0.1 x 2 / 3 = 0.0667, 240 s expected back: RISKY is worth it.
struct RootsNet {
  SewerMap map = testing::SmallMap()
                     .manhole("S", 0, 0, /*exit=*/true)
                     .manhole("X", 10, 0)
                     .manhole("T", 20, 0)
                     .pipe("RISKY", "S", "X", 0.5, 10.0)
                     .pipe("SAFE", "S", "X", 0.5, 100.0)
                     .pipe("P", "X", "T", 0.5, 10.0)
                     .build();
  PipeId risky = *map.find_pipe("RISKY");
  Mission mission = make_mission(map);

  static Mission make_mission(const SewerMap& map) {
    Mission m = testing::small_mission(map, "S");
    testing::add_task(m, map, "in P", TaskKind::kGoTo, "P", 5.0);
    m.hazards.push_back({.pipe = *map.find_pipe("RISKY"),
                         .offset_m = 5,
                         .probability = 0.1,
                         .reason = "BBA roots"});
    return m;
  }

  ReplannerOptions options() const {
    ReplannerOptions o{.clock = &clock};
    o.planner.risk = domain::kDefaultRiskCosts;
    return o;
  }

  // The robot at its task in P, the task done, having driven there.
  domain::MissionProgress at_task() const {
    domain::MissionProgress p = domain::initial_progress(mission, map);
    p.position = domain::InPipe{*map.find_pipe("P"), 5};
    p.done = {true};
    p.energy_used_wh = 1;
    return p;
  }

  std::vector<std::string> pipes_driven(const domain::Plan& plan) const {
    std::vector<std::string> names;
    for (const domain::PlanStep& step : plan.steps) {
      if (const auto* d = std::get_if<domain::DrivePipeToManhole>(&step)) {
        names.push_back(map.pipe(d->pipe).name);
      }
    }
    return names;
  }

  ManualClock clock;
};

TEST(HazardLearning, APassLowersTheProbabilityByTheBetaUpdate) {
  // k p0 / (k + n): the prior's mean p0 = a / (a + b), a + b = k; each pass adds 1 to b.
  EXPECT_DOUBLE_EQ(hazard_probability_after_pass(0.1, 0, 2), 0.1 * 2 / 3);
  EXPECT_DOUBLE_EQ(hazard_probability_after_pass(0.1 * 2 / 3, 1, 2), 0.1 * 2 / 4);
  EXPECT_DOUBLE_EQ(hazard_probability_after_pass(0.3, 0, 0), 0);  // no prior: one pass proves it
  EXPECT_DOUBLE_EQ(hazard_probability_after_pass(0.3, 5, std::numeric_limits<double>::infinity()),
                   0.3);  // a prior nothing moves
  EXPECT_DOUBLE_EQ(hazard_probability_after_pass(0, 3, 2), 0);

  RootsNet net;
  Replanner replanner(net.map, net.mission, net.options());
  const auto first = replanner.observe_pass(net.risky, 0, 10);
  ASSERT_TRUE(first.has_value()) << first.error();
  ASSERT_EQ(first->size(), 1U);
  EXPECT_DOUBLE_EQ((*first)[0].probability_before, 0.1);
  EXPECT_DOUBLE_EQ((*first)[0].belief.probability, 0.1 * 2 / 3);
  EXPECT_EQ((*first)[0].belief.passes, 1U);
  EXPECT_FALSE((*first)[0].belief.blocked);
  // The way back is a pass of the same hazard: the same belief, a second observation.
  const auto back = replanner.observe_pass(net.risky, 10, 0);
  ASSERT_TRUE(back.has_value()) << back.error();
  ASSERT_EQ(back->size(), 1U);
  EXPECT_DOUBLE_EQ((*back)[0].belief.probability, 0.1 * 2 / 4);
  EXPECT_EQ((*back)[0].belief.passes, 2U);
  ASSERT_EQ(replanner.learnt().hazards.size(), 1U);
  EXPECT_EQ(replanner.learnt().hazards[0], (*back)[0].belief);
  // The Replanner's view of the mission weighs it; the operator's mission is not where it went.
  EXPECT_DOUBLE_EQ(replanner.mission().hazards[0].probability, 0.05);
  EXPECT_DOUBLE_EQ(net.mission.hazards[0].probability, 0.1);
}

TEST(HazardLearning, OnlyAHazardDrivenPastIsObserved) {
  RootsNet net;
  Replanner replanner(net.map, net.mission, net.options());
  // Up to the hazard, or from it on, is not past it; another pipe is not it.
  for (const auto& [from, to] : {std::pair{0.0, 5.0}, {5.0, 10.0}, {0.0, 4.9}}) {
    const auto updates = replanner.observe_pass(net.risky, from, to);
    ASSERT_TRUE(updates.has_value()) << updates.error();
    EXPECT_TRUE(updates->empty()) << from << " to " << to;
  }
  const auto other = replanner.observe_pass(*net.map.find_pipe("SAFE"), 0, 100);
  ASSERT_TRUE(other.has_value());
  EXPECT_TRUE(other->empty());
  EXPECT_TRUE(replanner.learnt().empty());
  // A report off the map is refused, and changes nothing.
  for (const auto& [pipe, to] : {std::pair{net.risky, 10.5},
                                 {net.risky, -1.0},
                                 {net.risky, std::numeric_limits<double>::quiet_NaN()},
                                 {PipeId{99}, 1.0}}) {
    const auto bad = replanner.observe_pass(pipe, 0, to);
    ASSERT_FALSE(bad.has_value());
    EXPECT_NE(bad.error().message.find("invalid pass report"), std::string::npos);
  }
  EXPECT_TRUE(replanner.learnt().empty());
}

TEST(HazardLearning, ABlockageMetThereMakesItCertain) {
  RootsNet net;
  Replanner replanner(net.map, net.mission, net.options());
  (void)replanner.plan();
  // The robot stops short of the roots: the blockage is reported just before them.
  const PlanResponse r = replanner.report_failure(
      {.kind = Failure::Kind::kBlockage, .pipe = net.risky, .offset_m = 4.951});
  ASSERT_EQ(r.hazard_updates.size(), 1U);
  EXPECT_DOUBLE_EQ(r.hazard_updates[0].probability_before, 0.1);
  EXPECT_DOUBLE_EQ(r.hazard_updates[0].belief.probability, 1);
  EXPECT_TRUE(r.hazard_updates[0].belief.blocked);
  EXPECT_DOUBLE_EQ(replanner.mission().hazards[0].probability, 1);
  // ... and closed, as every learnt blockage is.
  EXPECT_EQ(replanner.learnt().blockages, (std::vector<Blockage>{{net.risky, 4.951}}));
  EXPECT_EQ(net.pipes_driven(r.plan), (std::vector<std::string>{"SAFE", "P", "SAFE"}));
  // A later pass (what a push cleared) does not make it less certain.
  const auto pass = replanner.observe_pass(net.risky, 0, 10);
  ASSERT_TRUE(pass.has_value());
  EXPECT_TRUE(pass->empty());
  EXPECT_DOUBLE_EQ(replanner.mission().hazards[0].probability, 1);
}

TEST(HazardLearning, ABlockageFarFromTheHazardIsNotIt) {
  RootsNet net;
  Replanner replanner(net.map, net.mission, net.options());
  const PlanResponse r = replanner.report_failure(
      {.kind = Failure::Kind::kBlockage, .pipe = net.risky, .offset_m = 2});
  EXPECT_TRUE(r.hazard_updates.empty());
  EXPECT_DOUBLE_EQ(replanner.mission().hazards[0].probability, 0.1);
  EXPECT_TRUE(replanner.learnt().hazards.empty());
}

// RootsNet with a second hazard in RISKY, a crack at 8 m, behind the roots from S.
Mission with_crack(const RootsNet& net) {
  Mission m = net.mission;
  m.hazards.push_back(
      {.pipe = net.risky, .offset_m = 8, .probability = 0.1, .reason = "BAB crack"});
  return m;
}

TEST(HazardLearning, AStoppedDriveObservesTheHazardsBehindTheStop) {
  RootsNet net;
  Replanner replanner(net.map, with_crack(net), net.options());
  // From S, stopped 5 cm short of the crack: the roots are behind, the crack is what stopped it.
  const auto stopped = replanner.observe_stop(net.risky, 0, 7.95);
  ASSERT_TRUE(stopped.has_value()) << stopped.error();
  ASSERT_EQ(stopped->size(), 1U);
  EXPECT_EQ((*stopped)[0].belief.reason, "BBA roots");
  EXPECT_DOUBLE_EQ((*stopped)[0].belief.probability, 0.1 * 2 / 3);
  EXPECT_EQ((*stopped)[0].belief.passes, 1U);
  // A hazard within the blockage match distance (1 m) of the stop, behind or ahead, may be what
  // stopped the robot: not observed. Nor one the drive did not get past.
  for (const auto& [from, stop] : {std::pair{0.0, 5.5}, {0.0, 4.5}, {10.0, 8.9}, {0.0, 4.0}}) {
    const auto none = replanner.observe_stop(net.risky, from, stop);
    ASSERT_TRUE(none.has_value()) << none.error();
    EXPECT_TRUE(none->empty()) << from << " to " << stop;
  }
  // Backing from X, stopped past the crack: the crack was passed, the roots lie ahead.
  const auto back = replanner.observe_stop(net.risky, 10, 6.5);
  ASSERT_TRUE(back.has_value()) << back.error();
  ASSERT_EQ(back->size(), 1U);
  EXPECT_EQ((*back)[0].belief.reason, "BAB crack");
  // A finished drive over the same stretch passes both, each once more; a stop off the map is
  // refused as a pass is.
  const auto pass = replanner.observe_pass(net.risky, 0, 10);
  ASSERT_TRUE(pass.has_value());
  EXPECT_EQ(pass->size(), 2U);
  const auto bad = replanner.observe_stop(net.risky, 0, 11);
  ASSERT_FALSE(bad.has_value());
  EXPECT_NE(bad.error().message.find("invalid pass report"), std::string::npos);
}

TEST(HazardLearning, TheReplanAfterASafePassTakesTheOnceRiskyPipeBack) {
  RootsNet net;
  Replanner replanner(net.map, net.mission, net.options());
  const PlanResponse first = replanner.plan();
  ASSERT_TRUE(has_plan(first.decision)) << first.reason;

  EXPECT_EQ(net.pipes_driven(first.plan), (std::vector<std::string>{"RISKY", "P", "SAFE"}));

  // Without what the pass taught, the way back from T stays the safe one ...
  Replanner unaware(net.map, net.mission, net.options());
  ASSERT_TRUE(unaware.update(net.at_task(), 0).has_value());
  EXPECT_EQ(net.pipes_driven(unaware.plan("at the task").plan),
            (std::vector<std::string>{"P", "SAFE"}));

  // ... with it, 0.0667 x 3600 s = 240 s expected is less than the 300 s detour.
  ASSERT_TRUE(replanner.observe_pass(net.risky, 0, 10).has_value());
  ASSERT_TRUE(replanner.update(net.at_task(), 0).has_value());
  const PlanResponse back = replanner.plan("at the task");
  ASSERT_TRUE(has_plan(back.decision)) << back.reason;
  EXPECT_EQ(net.pipes_driven(back.plan), (std::vector<std::string>{"P", "RISKY"}));
}

TEST(HazardLearning, BeliefsAreSavedAndASecondMissionStartsFromThem) {
  RootsNet net;
  Replanner first(net.map, net.mission, net.options());
  ASSERT_TRUE(first.observe_pass(net.risky, 0, 10).has_value());
  Diagnostics d;
  const std::string text = learnt_json(first.learnt(), net.map);
  EXPECT_NE(text.find("\"version\": 4"), std::string::npos);
  const auto back = read_learnt_json(text, "learnt.json", net.map, d);
  ASSERT_TRUE(back.has_value()) << d.error_summary();
  EXPECT_EQ(*back, first.learnt());

  Replanner second(net.map, net.mission, net.options());
  ASSERT_TRUE(second.learn(*back).has_value());
  EXPECT_DOUBLE_EQ(second.mission().hazards[0].probability, 0.1 * 2 / 3);
  // It goes on learning from there: the strength is the prior's and the passes'.
  const auto pass = second.observe_pass(net.risky, 10, 0);
  ASSERT_TRUE(pass.has_value());
  ASSERT_EQ(pass->size(), 1U);
  EXPECT_DOUBLE_EQ((*pass)[0].belief.probability, 0.05);
  EXPECT_EQ((*pass)[0].belief.passes, 2U);
  // A belief about the same hazard replaces the one learnt before.
  ASSERT_TRUE(second.learn(*back).has_value());
  ASSERT_EQ(second.learnt().hazards.size(), 1U);
  EXPECT_EQ(second.learnt().hazards[0], back->hazards[0]);
  EXPECT_DOUBLE_EQ(second.mission().hazards[0].probability, 0.1 * 2 / 3);
}

TEST(HazardLearning, ABeliefAboutNoHazardOfTheMissionChangesNothing) {
  RootsNet net;
  Learnt learnt;
  learnt.hazards.push_back({net.risky, 5, "BBC deposits", 0.01, 3, false});  // another finding
  learnt.hazards.push_back({net.risky, 6, "BBA roots", 0.01, 3, false});     // another place
  const Mission m = with_learnt(net.mission, learnt);
  EXPECT_EQ(m.hazards, net.mission.hazards);
}

TEST(HazardLearning, ABadProbabilityIsAClearError) {
  RootsNet net;
  const std::vector<std::pair<std::string, std::string>> bad{
      {R"({"format": "sewerplan-learnt", "version": 2, "hazards": [{"pipe": "RISKY",
           "offset_m": 5, "reason": "BBA roots", "probability": 1.5, "passes": 1,
           "blocked": false}]})",
       "learnt.json:$.hazards[0].probability: error: expected a probability from 0 to 1, got 1.5"},
      {R"({"format": "sewerplan-learnt", "version": 2, "hazards": [{"pipe": "RISKY",
           "offset_m": 5, "reason": "BBA roots", "probability": -0.1, "passes": 1,
           "blocked": false}]})",
       "learnt.json:$.hazards[0].probability: error: expected a probability from 0 to 1, got -0.1"},
      // JSON has no NaN: what a writer makes of one (null, or the bare word) is refused.
      {R"({"format": "sewerplan-learnt", "version": 2, "hazards": [{"pipe": "RISKY",
           "offset_m": 5, "reason": "BBA roots", "probability": null, "passes": 1,
           "blocked": false}]})",
       "learnt.json:$.hazards[0].probability: error: expected a number, got null"},
      {R"({"format": "sewerplan-learnt", "version": 2, "hazards": [{"pipe": "RISKY",
           "offset_m": 5, "reason": "BBA roots", "probability": NaN, "passes": 1,
           "blocked": false}]})",
       "learnt.json:2:"},
      {R"({"format": "sewerplan-learnt", "version": 2, "hazards": [{"pipe": "RISKY",
           "offset_m": 5, "reason": "BBA roots", "probability": 0.5, "passes": 1,
           "blocked": true}]})",
       "learnt.json:$.hazards[0].probability: error: a hazard met as a blockage has probability 1"},
      {R"({"format": "sewerplan-learnt", "version": 2, "hazards": [{"pipe": "RISKY",
           "offset_m": 5, "reason": "BBA roots", "probability": 0.5, "passes": 1.5,
           "blocked": false}]})",
       "learnt.json:$.hazards[0].passes"},
      {R"({"format": "sewerplan-learnt", "version": 2, "hazards": [{"pipe": "P99",
           "offset_m": 5, "reason": "BBA roots", "probability": 0.5, "passes": 1,
           "blocked": false}]})",
       "learnt.json:$.hazards[0].pipe: error: unknown pipe \"P99\""},
      {R"({"format": "sewerplan-learnt", "version": 2, "hazards": [{"pipe": "RISKY",
           "offset_m": 50, "reason": "BBA roots", "probability": 0.5, "passes": 1,
           "blocked": false}]})",
       "learnt.json:$.hazards[0].offset_m"},
      {R"({"format": "sewerplan-learnt", "version": 2, "hazards": [{"pipe": "RISKY",
           "offset_m": 5, "probability": 0.5, "passes": 1, "blocked": false}]})",
       "learnt.json:$.hazards[0]: error: missing required field 'reason'"},
      // Version 1 knew no hazards.
      {R"({"format": "sewerplan-learnt", "version": 1, "hazards": []})",
       "learnt.json:$.hazards: error: learnt hazards need version 2"},
  };
  for (const auto& [text, where] : bad) {
    Diagnostics d;
    const auto learnt = read_learnt_json(text, "learnt.json", net.map, d);
    ASSERT_FALSE(learnt.has_value()) << text;
    EXPECT_NE(learnt.error().message.find(where), std::string::npos) << learnt.error().message;
  }
  // The same through the library: learn() refuses it, naming the hazard, and learns nothing.
  Replanner replanner(net.map, net.mission, net.options());
  for (const double p : {1.5, -0.1, std::numeric_limits<double>::quiet_NaN()}) {
    Learnt learnt;
    learnt.hazards.push_back({net.risky, 5, "BBA roots", p, 1, false});
    const auto refused = replanner.learn(learnt);
    ASSERT_FALSE(refused.has_value()) << p;
    EXPECT_NE(refused.error().message.find("'BBA roots' in pipe RISKY at 5 m has probability"),
              std::string::npos)
        << refused.error().message;
  }
  EXPECT_TRUE(replanner.learnt().empty());
  EXPECT_DOUBLE_EQ(replanner.mission().hazards[0].probability, 0.1);
}

TEST(HazardLearning, AVersion1FileReadsAsBefore) {
  RootsNet net;
  Diagnostics d;
  const auto learnt = read_learnt_json(
      R"({"format": "sewerplan-learnt", "version": 1, "blockages": [{"pipe": "P", "offset_m": 2}]})",
      "learnt.json", net.map, d);
  ASSERT_TRUE(learnt.has_value()) << d.error_summary();
  EXPECT_EQ(learnt->blockages.size(), 1U);
  EXPECT_TRUE(learnt->hazards.empty());
}

struct SimRun {
  MissionReport report;
  std::vector<Event> events;
  Learnt learnt;
};

SimRun simulate(RootsNet& net, const Mission& mission, const std::string& faults_json);

SimRun simulate(RootsNet& net, const std::string& faults_json) {
  return simulate(net, net.mission, faults_json);
}

SimRun simulate(RootsNet& net, const Mission& mission, const std::string& faults_json) {
  Diagnostics d;
  auto faults = hal::read_faults_json(faults_json, "faults.json", net.map, d);
  EXPECT_TRUE(faults.has_value()) << d.error_summary();
  Replanner replanner(net.map, mission, net.options());
  hal::SimRobot robot(net.map, net.mission.profile, hal::InManhole{*net.map.find_manhole("S")},
                      faults.has_value() ? *faults : hal::FaultScenario{});
  Executor executor(net.map, replanner, robot);
  SimRun run;
  executor.subscribe([&run](const Event& e) { run.events.push_back(e); });
  run.report = executor.run();
  run.learnt = replanner.learnt();
  return run;
}

std::vector<std::string> types(const SimRun& run) {
  std::vector<std::string> names;
  for (const Event& e : run.events) {
    if (type_name(e) != "action" && type_name(e) != "job") names.emplace_back(type_name(e));
  }
  return names;
}

// The event of the first safe pass of the roots in pipe RISKY (p 0.1 at 5 m): the Beta update
// with a prior of strength 2 takes 0.1 to 0.1 x 2/3.
HazardEvent first_pass_of_the_roots() {
  return {.pipe = "RISKY",
          .offset_m = 5,
          .reason = "BBA roots",
          .observed = HazardEvent::Observed::kPassed,
          .probability_before = 0.1,
          .probability = 0.1 * 2 / 3,
          .passes = 1};
}

TEST(HazardLearning, TheExecutorLogsAPassRightAfterItsJob) {
  RootsNet net;
  const SimRun run = simulate(net, R"({"format": "sewerplan-faults", "version": 1})");
  EXPECT_EQ(run.report.outcome, MissionReport::Outcome::kEnded);
  const HazardEvent* pass = nullptr;
  for (std::size_t i = 0; i < run.events.size(); ++i) {
    if (const auto* h = std::get_if<HazardEvent>(&run.events[i].what)) {
      ASSERT_EQ(pass, nullptr) << "one pass: the plan comes back by SAFE";
      pass = h;
      ASSERT_GT(i, 0U);
      const auto* job = std::get_if<JobEvent>(&run.events[i - 1].what);
      ASSERT_NE(job, nullptr);
      EXPECT_TRUE(job->ok);
    }
  }
  ASSERT_NE(pass, nullptr);
  EXPECT_EQ(*pass, first_pass_of_the_roots());
  ASSERT_EQ(run.learnt.hazards.size(), 1U);
  EXPECT_EQ(run.learnt.hazards[0].passes, 1U);
  // The log line, and the same event read back.
  const std::string line = to_json_line(Event{1, *pass});
  EXPECT_NE(line.find(R"("type":"hazard","pipe":"RISKY","offset_m":5.0,"reason":"BBA roots",)"
                      R"("observed":"passed","probability_before":0.1,)"),
            std::string::npos)
      << line;
  Diagnostics d;
  const auto events = read_event_log(line + "\n", "log.jsonl", d);
  ASSERT_TRUE(events.has_value()) << d.error_summary();
  ASSERT_EQ(events->size(), 1U);
  EXPECT_EQ(std::get<HazardEvent>((*events)[0].what).observed, HazardEvent::Observed::kPassed);
}

TEST(HazardLearning, TheExecutorLogsABlockageMetBeforeTheReplan) {
  RootsNet net;
  const SimRun run = simulate(net, R"({"format": "sewerplan-faults", "version": 1,
      "obstacles": [{"pipe": "RISKY", "offset_m": 5.0, "kind": "permanent"}]})");
  // Backed out to S, the robot cannot turn into SAFE there (a U-turn): the task is dropped.
  EXPECT_EQ(run.report.outcome, MissionReport::Outcome::kEnded);
  const std::vector<std::string> names = types(run);
  const auto failure = std::find(names.begin(), names.end(), "failure");
  ASSERT_NE(failure, names.end());
  ASSERT_LT(failure + 1, names.end());
  EXPECT_EQ(*(failure + 1), "hazard");
  EXPECT_NE(std::find(failure + 1, names.end(), "replan"), names.end());
  EXPECT_EQ(std::count(names.begin(), names.end(), "hazard"), 1);
  ASSERT_EQ(run.learnt.hazards.size(), 1U);
  EXPECT_TRUE(run.learnt.hazards[0].blocked);
  EXPECT_DOUBLE_EQ(run.learnt.hazards[0].probability, 1);
  EXPECT_EQ(run.learnt.blockages.size(), 1U);
}

TEST(HazardLearning, ADriveStoppedFurtherOnRecordsTheHazardsItPassed) {
  // The robot drives RISKY from S past the roots and is stopped at the crack for good. The roots
  // were passed: logged right after the job that stopped, before the failure and its replan
  // (which then weighs them lowered), and the crack met. Only finished jobs counted: the roots'
  // pass went unrecorded until the robot backed over them, and never when it did not.
  RootsNet net;
  const SimRun run = simulate(net, with_crack(net), R"({"format": "sewerplan-faults", "version": 1,
      "obstacles": [{"pipe": "RISKY", "offset_m": 8.0, "kind": "permanent"}]})");
  std::vector<const HazardEvent*> hazards;
  std::size_t first_failure = run.events.size();
  for (std::size_t i = 0; i < run.events.size(); ++i) {
    if (type_name(run.events[i]) == "failure" && first_failure == run.events.size()) {
      first_failure = i;
    }
    const auto* h = std::get_if<HazardEvent>(&run.events[i].what);
    if (h == nullptr) continue;
    if (hazards.empty()) {
      EXPECT_LT(i, first_failure) << "the roots passed before the failure is reported";
      // Right after the job that was stopped (and its error).
      ASSERT_GE(i, 2U);
      const auto* job = std::get_if<JobEvent>(&run.events[i - 2].what);
      ASSERT_NE(job, nullptr);
      EXPECT_FALSE(job->ok);
      EXPECT_EQ(type_name(run.events[i - 1]), "error");
    }
    hazards.push_back(h);
  }
  ASSERT_GE(hazards.size(), 2U);
  EXPECT_EQ(*hazards[0], first_pass_of_the_roots());
  const auto crack = std::find_if(hazards.begin(), hazards.end(),
                                  [](const HazardEvent* h) { return h->reason == "BAB crack"; });
  ASSERT_NE(crack, hazards.end());
  EXPECT_EQ((*crack)->observed, HazardEvent::Observed::kBlocked);
  EXPECT_EQ((*crack)->passes, 0U);
  // What it learnt, as the campaigns record it: the roots passed, the crack blocked, each once.
  ASSERT_EQ(run.learnt.hazards.size(), 2U);
  for (const HazardBelief& b : run.learnt.hazards) {
    if (b.reason == "BBA roots") {
      EXPECT_FALSE(b.blocked);
      EXPECT_GE(b.passes, 1U);
    } else {
      EXPECT_TRUE(b.blocked);
      EXPECT_EQ(b.passes, 0U);
    }
  }
}

TEST(HazardLearning, ARobotThatBreaksDownMidDriveRecordsTheHazardsItPassed) {
  // Broken down for good in RISKY 2 m past the roots (the drive starts at 20 s, at 0.3 m/s): the
  // robot never drives back over them, and only its stopped drive can tell they did not block.
  RootsNet net;
  const SimRun run = simulate(net, R"({"format": "sewerplan-faults", "version": 1,
      "malfunctions": [{"at_time_s": 43.3, "kind": "permanent"}]})");
  EXPECT_EQ(run.report.outcome, MissionReport::Outcome::kBeacon);
  ASSERT_EQ(run.learnt.hazards.size(), 1U);
  EXPECT_EQ(run.learnt.hazards[0].reason, "BBA roots");
  EXPECT_FALSE(run.learnt.hazards[0].blocked);
  EXPECT_EQ(run.learnt.hazards[0].passes, 1U);
}

}  // namespace
}  // namespace sewerplan::executor
