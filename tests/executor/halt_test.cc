// SPDX-License-Identifier: MIT
// Executor::halt(): the robot stopped where it is, the log closed with mission_end "halted", from
// an observer on run()'s thread and from another thread while a job runs. Part of the concurrent
// tests (sewerplan_concurrency_tests, run under ThreadSanitizer by scripts/tsan.sh).
#include <condition_variable>
#include <functional>
#include <future>
#include <mutex>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "sewerplan/domain/robot_state.h"
#include "sewerplan/executor/event_json.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/sim_robot.h"

#include "support/ais_testbed.h"

namespace sewerplan::executor {
namespace {

struct PaperMission {
  testing::AisTestbed ais = testing::load_ais_testbed();
  ManualClock clock;
  Replanner replanner{ais.map, ais.mission, {.clock = &clock}};
  hal::SimRobot robot{ais.map, ais.mission.profile,
                      hal::InPipe{std::get<domain::InPipe>(replanner.progress().position).pipe,
                                  std::get<domain::InPipe>(replanner.progress().position).offset_m,
                                  hal::Heading::kTowardsEnd1}};
  std::vector<Event> events;
  void record(Executor& executor) {
    executor.subscribe([this](const Event& e) { events.push_back(e); });
  }
};

template <class T>
std::size_t count(const std::vector<Event>& events) {
  std::size_t n = 0;
  for (const Event& e : events) n += std::holds_alternative<T>(e.what) ? 1U : 0U;
  return n;
}

TEST(ExecutorHalt, AHaltFromAnObserverStopsTheMissionAfterThatEvent) {
  PaperMission m;
  Executor executor(m.ais.map, m.replanner, m.robot);
  m.record(executor);
  std::ostringstream json;
  executor.subscribe(json_lines_writer(json));
  executor.subscribe([&](const Event& e) {
    if (std::holds_alternative<TaskDoneEvent>(e.what)) executor.halt();
  });
  const MissionReport report = executor.run();

  EXPECT_EQ(report.outcome, MissionReport::Outcome::kHalted) << report;
  EXPECT_EQ(report.tasks_done, (std::vector<std::string>{"sample"})) << report;
  EXPECT_EQ(report.beacon_cause, MissionReport::BeaconCause::kNone);
  EXPECT_FALSE(m.robot.status().beacon_on);
  EXPECT_TRUE(m.robot.emergency_stopped());
  // The log ends with the halt, after the task: nothing was sent to the robot after it.
  ASSERT_FALSE(m.events.empty());
  const auto* end = std::get_if<MissionEndEvent>(&m.events.back().what);
  ASSERT_NE(end, nullptr);
  EXPECT_EQ(end->outcome, MissionOutcome::kHalted);
  EXPECT_EQ(end->end, report.end);
  EXPECT_TRUE(std::holds_alternative<TaskDoneEvent>(m.events[m.events.size() - 2].what));
  EXPECT_EQ(count<MissionEndEvent>(m.events), 1U);
  EXPECT_EQ(count<BeaconEvent>(m.events), 0U);
  EXPECT_EQ(m.robot.jobs_executed(), report.jobs);
  EXPECT_NE(json.str().find(R"("type":"mission_end","outcome":"halted")"), std::string::npos);
  // Where it stopped: where the Replanner was last told the robot is, in P6 after the sample.
  EXPECT_EQ(report.end, domain::describe(m.replanner.progress().position, m.ais.map)) << report;
  EXPECT_TRUE(report.end.starts_with("in pipe P6")) << report;
}

TEST(ExecutorHalt, AHaltBeforeRunEndsTheMissionBeforeItsFirstJob) {
  PaperMission m;
  Executor executor(m.ais.map, m.replanner, m.robot);
  m.record(executor);
  executor.halt();
  const MissionReport report = executor.run();
  EXPECT_EQ(report.outcome, MissionReport::Outcome::kHalted) << report;
  EXPECT_EQ(report.jobs, 0U);
  EXPECT_EQ(m.robot.jobs_executed(), 0U);
  ASSERT_EQ(m.events.size(), 1U);
  EXPECT_TRUE(std::holds_alternative<MissionEndEvent>(m.events.front().what));
}

// A robot whose `block_at`th job runs until an emergency stop: a job in a long pipe, as the
// executor's thread sees it while another thread halts the mission.
class JobUntilStopped final : public hal::Robot {
 public:
  JobUntilStopped(hal::Robot& robot, std::size_t block_at) : robot_(robot), block_at_(block_at) {}
  hal::JobReport execute(const Job& job) override {
    if (jobs_++ != block_at_) return robot_.execute(job);
    running_.set_value();
    std::unique_lock lock(mutex_);
    stop_.wait(lock, [this] { return stopped_; });
    return {.error = hal::RobotError{hal::RobotErrorKind::kMalfunction, "emergency stop"}};
  }
  hal::RobotStatus status() const override { return robot_.status(); }
  Result<void> reboot() override { return robot_.reboot(); }
  hal::BeaconState activate_beacon() override { return robot_.activate_beacon(); }
  void emergency_stop() override {
    robot_.emergency_stop();
    const std::lock_guard lock(mutex_);
    stopped_ = true;
    stop_.notify_all();
  }
  std::future<void> running() { return running_.get_future(); }

 private:
  hal::Robot& robot_;
  std::size_t block_at_;
  std::size_t jobs_ = 0;
  std::promise<void> running_;
  std::mutex mutex_;
  std::condition_variable stop_;
  bool stopped_ = false;
};

TEST(ExecutorHalt, AnotherThreadHaltsAMissionWhileAJobRuns) {
  PaperMission m;
  JobUntilStopped robot(m.robot, 3);
  std::future<void> running = robot.running();
  Executor executor(m.ais.map, m.replanner, robot);
  m.record(executor);
  std::jthread operator_thread([&] {
    running.wait();
    executor.halt();
  });
  const MissionReport report = executor.run();
  operator_thread.join();

  EXPECT_EQ(report.outcome, MissionReport::Outcome::kHalted) << report;
  EXPECT_EQ(report.jobs, 4U);  // three done, the fourth ended by the stop
  EXPECT_TRUE(m.robot.emergency_stopped());
  EXPECT_FALSE(m.robot.status().beacon_on);
  // The stopped job is logged with the robot's error, and nothing after it but the end: no
  // recovery, no reboot, no replan.
  ASSERT_GE(m.events.size(), 3U);
  const auto* error = std::get_if<ErrorEvent>(&m.events[m.events.size() - 2].what);
  ASSERT_NE(error, nullptr);
  EXPECT_EQ(error->reason, "emergency stop");
  EXPECT_EQ(count<RecoveryEvent>(m.events), 0U);
  EXPECT_EQ(count<PlanEvent>(m.events), 1U);
  const auto* end = std::get_if<MissionEndEvent>(&m.events.back().what);
  ASSERT_NE(end, nullptr);
  EXPECT_EQ(end->outcome, MissionOutcome::kHalted);
}

// A clock that, the first time the Replanner reads it (as a plan starts), lets `on_plan` run and
// waits until it returns: a halt from another thread lands, deterministically, while the plan is
// being computed.
class PlanStartHook final : public Clock {
 public:
  explicit PlanStartHook(std::function<void()> on_plan) : on_plan_(std::move(on_plan)) {}
  double now_s() const override {
    std::call_once(once_, [this] {
      std::future<void> done = std::async(std::launch::async, on_plan_);
      done.wait();
    });
    return 0;
  }

 private:
  std::function<void()> on_plan_;
  mutable std::once_flag once_;
};

// Issue 30: a halt while a plan is computed waited for the plan (12.75 s on a 5,000-manhole
// network with 300 tasks). The halt is the cancel of the planner's StopCondition: the plan is cut
// short, no plan is answered or logged, and the mission ends halted before its first job.
TEST(ExecutorHalt, AHaltFromAnotherThreadCancelsThePlanBeingComputedIssue30) {
  testing::AisTestbed ais = testing::load_ais_testbed();
  Executor* executor_seen = nullptr;
  PlanStartHook clock([&] { executor_seen->halt(); });  // on another thread (std::async)
  Replanner replanner{ais.map, ais.mission, {.clock = &clock}};
  hal::SimRobot robot{ais.map, ais.mission.profile,
                      hal::InPipe{std::get<domain::InPipe>(replanner.progress().position).pipe,
                                  std::get<domain::InPipe>(replanner.progress().position).offset_m,
                                  hal::Heading::kTowardsEnd1}};
  Executor executor(ais.map, replanner, robot);
  executor_seen = &executor;
  std::vector<Event> events;
  executor.subscribe([&](const Event& e) { events.push_back(e); });
  const MissionReport report = executor.run();

  EXPECT_EQ(report.outcome, MissionReport::Outcome::kHalted) << report;
  EXPECT_EQ(report.jobs, 0U);
  EXPECT_EQ(count<PlanEvent>(events), 0U);  // the plan was cancelled, not waited for
  ASSERT_EQ(events.size(), 1U);
  EXPECT_TRUE(std::holds_alternative<MissionEndEvent>(events.back().what));
  // Every task is accounted for: none done, each "not done" for the halt.
  EXPECT_EQ(report.dropped.size(), ais.mission.tasks.size()) << report;
  // The Replanner is usable after the cancel: the next plan is a whole one.
  EXPECT_EQ(replanner.plan().decision, PlanResponse::Decision::kFollowPlan);
}

}  // namespace
}  // namespace sewerplan::executor
