// SPDX-License-Identifier: MIT
// Executor: the action controller that runs a mission on a robot (the paper's section 4.6).
//
// It asks the Replanner for a plan, validates it, and runs its fused actions one at a time: each
// action's jobs (fusion/jobs.h) go to the robot (hal/robot.h), and every report is watched. A
// robot error is handled with staged recovery (recovery.h); what recovery cannot clear goes to
// the Replanner as a failure, with where the robot really is, and its answer is followed: a new
// plan, or the locator beacon. Before each action it checks that the plan left still fits the
// battery the robot reports, and replans towards an exit when it does not. Everything that
// happens is an event (events.h), delivered to the observers subscribed before run(): the
// JSON-lines log (event_json.h) and the readable live log (event_text.h) are two of them. The
// robot is the only source of time and energy, so a simulated run is deterministic for its seed.
//
//   SimRobot robot(map, mission.profile, start_pose, faults);
//   Replanner replanner(map, mission);
//   Executor executor(map, replanner, robot);
//   executor.subscribe_log(events_file);  // a LogFile (core/output_file.h)
//   executor.subscribe(readable_writer(std::cout));
//   MissionReport report = executor.run();
//
// halt(), from any thread, stops the mission: the robot's emergency stop ends the job it runs,
// no job or reboot is sent after it, and run() returns a report of outcome kHalted after a last
// mission_end event (outcome "halted", the robot where it stopped, the beacon off).
//
// Thread safety: An Executor is not thread-safe, except halt(): subscribe() and run() on one
// thread; the Replanner and Robot it holds are used by that thread only while it runs, and the
// observers are called on it. halt() may be called from any thread at any time, also from an
// observer, before or during run().
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/output_file.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/robot_state.h"
#include "sewerplan/executor/events.h"
#include "sewerplan/executor/recovery.h"
#include "sewerplan/executor/replanner.h"
#include "sewerplan/hal/robot.h"

namespace sewerplan::executor {

struct MissionReport {
  using Outcome = MissionOutcome;             // kEnded, kBeacon, kHalted (events.h)
  using BeaconCause = executor::BeaconCause;  // why the beacon is on (events.h)
  Outcome outcome = Outcome::kEnded;
  // The Replanner's last decision (replanner.h): "follow-plan", "degraded", "exit-on-reserve",
  // "call-for-recovery", "stuck"; the event log's mission_end and every --json output carry it.
  PlanResponse::Decision decision = PlanResponse::Decision::kFollowPlan;
  BeaconCause beacon_cause = BeaconCause::kNone;
  // Whether the robot confirmed the beacon (kNone: none was asked for); the text says "beacon on"
  // only when it did.
  hal::BeaconState beacon = hal::BeaconState::kNone;
  std::string end;  // "exit M4", why the beacon is on, or where the robot was halted
  std::vector<std::string> tasks_done;                       // in the order done
  std::vector<std::pair<std::string, std::string>> dropped;  // task name, reason
  double time_s = 0;
  double energy_wh = 0;
  std::size_t replans = 0;
  std::vector<double> planning_times_s;  // the first plan's and each replan's
  std::size_t jobs = 0;
  std::size_t recoveries = 0;  // errors cleared by recovery, without a replan
  // Whether the battery left is at least the operator's reserve.
  bool battery_reserve_kept = true;
  // Logs (subscribe_log) that lost events: "cannot write events.jsonl: No space left on device
  // (12 of 340 events lost)". The mission goes on when a log fails; the report says so.
  std::vector<std::string> log_errors;
  // Whether the Replanner sent the robot out on its reserve (kExitOnReserve: no exit could be
  // reached above it): the reserve was spent on purpose, as the last way out.
  bool exit_on_reserve = false;
};

std::ostream& operator<<(std::ostream& os, const MissionReport& report);

// One job the robot ran, for a job observer (Executor::subscribe_jobs): the job, its report, where
// the controller had the robot before and after it, and which way it drove along its pipe (+1
// towards ends[1], -1 towards ends[0], 0: not a drive). The references live for the call only.
struct JobSeen {
  const Job& job;
  const hal::JobReport& report;
  const domain::RobotPosition& before;
  const domain::RobotPosition& after;
  double direction = 0;
};
using JobObserver = std::function<void(const JobSeen&)>;

struct ExecutorOptions {
  RecoveryProfile recovery;
  std::size_t max_replans = 100;  // a bound against a world that keeps changing
  // The robot's odometry: its standard deviation per metre driven (wheels slip in wet pipes),
  // for manhole verification (docs/localisation.md).
  double odometry_sd_fraction = 0.03;
};

class Executor {
 public:
  // All must outlive the executor. The mission is the Replanner's.
  Executor(const SewerMap& map, Replanner& replanner, hal::Robot& robot,
           ExecutorOptions options = {});

  // Adds an observer of every event of run(), called in the order subscribed. Before run() only.
  void subscribe(EventObserver observer);
  // Adds an observer of every plan the Replanner answers (the first and each replan), with its
  // steps and fused actions, called right after the plan's PlanEvent: what the event log does not
  // carry, e.g. the route for an operator's map (the station's server, docs/operator-station.md).
  // Before run() only.
  using PlanObserver = std::function<void(const PlanResponse&)>;
  void subscribe_plans(PlanObserver observer);
  // Adds an observer of every job the robot runs (the map's measuring, executor/measuring.h),
  // called after the job's report, in the order subscribed; it changes nothing of the run. Before
  // run() only.
  void subscribe_jobs(JobObserver observer);
  // Appends every event of run() to `log` as a JSON line (event_json.h), one write per event. A
  // failed write does not stop the mission: the report's log_errors names the log, the first
  // reason and how many events were lost. `log` must outlive run(). Before run() only.
  void subscribe_log(LogFile& log);

  // Runs the mission to its end, the beacon, or a halt. Once per Executor.
  MissionReport run();

  // Asks run() to stop: the robot's emergency stop now (hal::Robot::emergency_stop), and run()
  // returns at its next check (after the job the stop ended), sending the robot nothing more.
  // Called before run(), run() halts before its first job. Thread-safe; returns at once.
  void halt();
  bool halt_requested() const { return halt_.load(); }

 private:
  class Run;
  const SewerMap& map_;
  Replanner& replanner_;
  hal::Robot& robot_;
  ExecutorOptions options_;
  std::vector<EventObserver> observers_;
  std::vector<PlanObserver> plan_observers_;
  std::vector<JobObserver> job_observers_;
  std::vector<LogFile*> logs_;
  std::atomic<bool> halt_{false};
};

}  // namespace sewerplan::executor
