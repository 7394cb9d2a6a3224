// SPDX-License-Identifier: MIT
// Executor: the action controller that runs a mission on a robot (the paper's section 4.6).
//
// It asks the Replanner for a plan, validates it, and runs its fused actions one at a time: each
// action's jobs (fusion/jobs.h) go to the robot (hal/robot.h), and every report is watched. A
// robot error is handled with staged recovery (recovery.h); what recovery cannot clear goes to
// the Replanner as a failure, with where the robot really is, and its answer is followed: a new
// plan, or the locator beacon. Before each action it checks that the plan left still fits the
// battery the robot reports, and replans towards an exit when it does not. Everything is
// written to the EventLog. The robot is the only source of time and energy, so a simulated run is
// deterministic for its seed.
//
//   SimRobot robot(map, mission.profile, start_pose, faults);
//   Replanner replanner(map, mission);
//   EventLog log(&events_file, &std::cout);
//   MissionReport report = Executor(map, replanner, robot, {}, log).run();
//
// Thread safety: An Executor is not thread-safe: run() on one thread; the Replanner, Robot and
// EventLog it holds are used by that thread only while it runs.
#pragma once

#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/executor/event_log.h"
#include "sewerplan/executor/recovery.h"
#include "sewerplan/executor/replanner.h"
#include "sewerplan/hal/robot.h"

namespace sewerplan::executor {

struct MissionReport {
  enum class Outcome {
    kEnded,   // the plan was carried out: at an exit, or at the mission's end point
    kBeacon,  // no way out: the beacon is on
  };
  // Why the beacon is on, for counting (campaigns show that no limit ever strands a robot).
  enum class BeaconCause {
    kNone,         // "none": not on
    kNoExit,       // "no-exit": a search proved that no exit can be reached
    kStuck,        // "stuck": the robot cannot move (recovery left it stuck, a danger in a manhole)
    kMalfunction,  // "malfunction": a permanent malfunction, a reboot that failed
    kLink,         // "link": the link to the robot failed (CAN)
    kLimit,        // "limit": a bound of the executor (max_replans) or a plan that did not validate
  };
  Outcome outcome = Outcome::kEnded;
  // The Replanner's last decision (replanner.h): "follow-plan", "degraded", "call-for-recovery",
  // "stuck"; the event log's mission_end and every --json output carry it.
  PlanResponse::Decision decision = PlanResponse::Decision::kFollowPlan;
  BeaconCause beacon_cause = BeaconCause::kNone;
  std::string end;                                           // "exit M4", or why the beacon is on
  std::vector<std::string> tasks_done;                       // in the order done
  std::vector<std::pair<std::string, std::string>> dropped;  // task name, reason
  double time_s = 0;
  double energy_wh = 0;
  std::size_t replans = 0;
  std::vector<double> planning_times_s;  // the first plan's and each replan's
  std::size_t jobs = 0;
  std::size_t recoveries = 0;  // errors cleared by recovery, without a replan
  bool battery_reserve_kept = true;
};

std::ostream& operator<<(std::ostream& os, const MissionReport& report);
// "none", "no-exit", "stuck", "malfunction", "link", "limit", and back (empty for other text).
std::string_view to_string(MissionReport::BeaconCause cause);
std::optional<MissionReport::BeaconCause> parse_beacon_cause(std::string_view name);

struct ExecutorOptions {
  RecoveryConfig recovery;
  std::size_t max_replans = 100;  // a bound against a world that keeps changing
};

class Executor {
 public:
  // All must outlive the executor. The mission is the Replanner's.
  Executor(const SewerMap& map, Replanner& replanner, hal::Robot& robot, ExecutorOptions options,
           EventLog& log);

  MissionReport run();

 private:
  class Run;
  const SewerMap& map_;
  Replanner& replanner_;
  hal::Robot& robot_;
  ExecutorOptions options_;
  EventLog& log_;
};

}  // namespace sewerplan::executor
