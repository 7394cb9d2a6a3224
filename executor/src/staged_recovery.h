// SPDX-License-Identifier: MIT
// StagedRecovery: carries out the recovery table (recovery.h) for one job that failed.
//
// Private to executor. The Executor's run loop hands it each job of an action; it runs the job
// through its host (which sends it to the robot, logs it and moves the dead reckoning), and when
// the robot reports an error it works through the profile's rows for that error: reboot and
// resume; the blockage rows in their order (back up and retry, lift the head and retry, push);
// back off from a danger, back out of a manhole. What the stages cannot clear comes back as a
// Failure for the Replanner, placed where the dead reckoning puts the robot.
//
//   StagedRecovery recovery(map, profile, speed_mps, tracker, host);
//   if (std::optional<Failure> f = recovery.run_job(job, action)) replan(*f);
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "sewerplan/core/job.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/executor/recovery.h"
#include "sewerplan/executor/replanner.h"
#include "sewerplan/fusion/robot_action.h"
#include "sewerplan/hal/robot.h"

#include "dead_reckoning.h"

namespace sewerplan::executor::detail {

// What recovery needs from the run loop: a job sent, logged and tracked; a reboot; an event.
struct RecoveryHost {
  std::function<hal::JobReport(const Job&)> execute_job;
  std::function<Result<void>()> reboot;
  // After a reboot: the robot's own report of `job` when the one heard (`heard`) was the link's
  // (hal::Robot::recovered_report), logged, and the tracking moved on to it; else empty.
  std::function<std::optional<hal::JobReport>(const Job& job, const hal::JobReport& heard)>
      recovered_report;
  std::function<void(RecoveryPhase phase, bool ok)> log_recovery;
  // After a drive to a manhole that went its bound and saw none: true when the tracking moved to
  // where the localisation believes the robot is, in another pipe (a manhole driven through
  // unseen). Empty: never.
  std::function<bool()> settle_elsewhere;
};

class StagedRecovery {
 public:
  // All must outlive this object.
  StagedRecovery(const SewerMap& map, const RecoveryProfile& profile, double speed_mps,
                 const DeadReckoning& tracker, RecoveryHost host)
      : map_(map),
        profile_(profile),
        speed_mps_(speed_mps),
        tracker_(tracker),
        host_(std::move(host)) {}

  // Runs `job` (of `action`) with staged recovery; a failure for the Replanner when recovery
  // fails.
  std::optional<Failure> run_job(const Job& job, const fusion::RobotAction& action);

  // Errors cleared by recovery without a replan, so far.
  std::size_t cleared() const { return cleared_; }

 private:
  struct Cleared;
  struct Try;
  hal::JobReport recovery_job(const Job& job);
  // After a reboot for the malfunction `r` of `job`: true when `r` was the link's (the job's
  // result was lost) and is now the robot's own report of the job.
  bool take_recovered(const Job& job, hal::JobReport& r);
  Cleared clear_blockage(Job rest);
  Try try_stage(const RecoveryStage& stage, Job& rest);
  std::optional<Failure> danger(const Job& job, const fusion::RobotAction& action,
                                const hal::JobReport& r);
  void back_out_of_manhole();
  Failure blocked_here(Failure::Kind kind, const Job& job, const hal::RobotError& error) const;

  const SewerMap& map_;
  const RecoveryProfile& profile_;
  double speed_mps_;
  const DeadReckoning& tracker_;
  RecoveryHost host_;
  std::size_t cleared_ = 0;
};

}  // namespace sewerplan::executor::detail
