// SPDX-License-Identifier: MIT
// Staged recovery as data: the table of what the action controller does for each robot error,
// stage by stage (kRecoveryTable), and the numbers it uses (RecoveryConfig) (the paper, 6).
//
// BLOCKAGE (the path is blocked): phase 1 backs up a few centimetres and retries, phase 2 lifts
// the head and retries (light waste may be flushed away), phase 3 pushes, only where allowed:
// pushing is risky in a real sewer (the obstacle may get stuck between two segments), so it is
// off by default. DANGER (going on could damage the robot): back off to the last safe position.
// MALFUNCTION: reboot the robot and resume if the fault was temporary. Every phase has a bounded
// number of tries; when all fail, the planning system changes its world model and replans.
// The executor's run loop (executor.cc) only sends jobs; staged_recovery.cc carries this table out.
//
//   RecoveryConfig config;              // the defaults: no push
//   config.push_allowed = true;         // a test bed where pushing is safe
//   Result<RecoveryConfig> c = read_recovery_json(text, "recovery.json");
//
// Thread safety: RecoveryConfig is a plain value; read_recovery_json shares nothing.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "sewerplan/core/result.h"
#include "sewerplan/hal/robot.h"

namespace sewerplan::executor {

struct RecoveryConfig {
  int backup_retries = 2;     // phase 1: back up and retry, this often
  double backup_m = 0.05;     // how far
  int lift_retries = 1;       // phase 2: lift the head, lower it, retry
  bool push_allowed = false;  // phase 3: push the obstacle
  int push_retries = 1;
  double danger_backoff_m = 0.3;  // DANGER: back this far along the way the robot came
  int max_reboots = 2;            // MALFUNCTION: reboots per job before giving up
  friend bool operator==(const RecoveryConfig&, const RecoveryConfig&) = default;
};

// One manoeuvre of staged recovery.
enum class RecoveryPhase : std::uint8_t {
  kReboot,            // MALFUNCTION: reboot, resume the rest of the job
  kBackUpAndRetry,    // BLOCKAGE 1: back up backup_m, drive the rest again
  kLiftHeadAndRetry,  // BLOCKAGE 2: lift the head, lower it, drive the rest again
  kPush,              // BLOCKAGE 3: push over the rest (push_allowed only)
  kBackOffToSafety,   // DANGER in a pipe: drive danger_backoff_m back the way the robot came
  kBackOutOfManhole,  // DANGER in a manhole: back into the pipe the robot came by
};

// One row of the table: for `error`, the manoeuvre, how often (a RecoveryConfig field), and what
// happens when every try has failed.
struct RecoveryStage {
  hal::RobotErrorKind error;
  RecoveryPhase phase;
  std::string_view logged;    // the "recovery" event's `phase` (docs/executor.md)
  std::string_view tries;     // the RecoveryConfig field that bounds it
  std::string_view gives_up;  // after the last try
};

// The staged recovery table, in the order the stages are tried for each error.
inline constexpr std::array<RecoveryStage, 6> kRecoveryTable{{
    {hal::RobotErrorKind::kMalfunction, RecoveryPhase::kReboot, "reboot", "max_reboots",
     "stuck: the Replanner is told the robot cannot move (beacon)"},
    {hal::RobotErrorKind::kBlockage, RecoveryPhase::kBackUpAndRetry, "1: back up and retry",
     "backup_retries", "on to stage 2 (at once when there is no room to back up)"},
    {hal::RobotErrorKind::kBlockage, RecoveryPhase::kLiftHeadAndRetry, "2: lift the head and retry",
     "lift_retries", "on to stage 3"},
    {hal::RobotErrorKind::kBlockage, RecoveryPhase::kPush, "3: push", "push_retries",
     "blockage 1 mm ahead of the robot: the Replanner disconnects the pipe there"},
    {hal::RobotErrorKind::kDanger, RecoveryPhase::kBackOffToSafety, "back off to safety", "1",
     "danger 1 mm ahead of where the robot stopped: the Replanner disconnects the pipe there"},
    {hal::RobotErrorKind::kDanger, RecoveryPhase::kBackOutOfManhole, "back out of the manhole", "1",
     "the passage is closed both ways"},
}};

// The stage's name as logged ("1: back up and retry").
constexpr std::string_view logged_name(RecoveryPhase phase) {
  for (const RecoveryStage& stage : kRecoveryTable) {
    if (stage.phase == phase) return stage.logged;
  }
  return "?";
}

// {"backup_retries": 2, "backup_m": 0.05, "lift_retries": 1, "push_allowed": false,
//  "push_retries": 1, "danger_backoff_m": 0.3, "max_reboots": 2}; every field optional. Unknown
// fields, wrong types and out-of-range values (negative counts or distances) are errors naming
// the file and field.
Result<RecoveryConfig> read_recovery_json(std::string_view text, const std::string& file_name);

}  // namespace sewerplan::executor
