// SPDX-License-Identifier: MIT
// Staged recovery as data: the recovery profile, the table of what the action controller does for
// each robot error, stage by stage, each row a manoeuvre and its bound (the paper, 6). The
// profile is the running policy: staged_recovery.cc walks its rows, and nothing else says what
// is tried or how often. An operator changes it in a file (docs/formats/recovery-json.md).
//
// BLOCKAGE (the path is blocked): back up a few centimetres and retry, lift the head and retry
// (light waste may be flushed away), push, only where allowed: pushing is risky in a real sewer
// (the obstacle may get stuck between two segments), so it is off by default. The blockage rows
// are tried in the profile's order. DANGER (going on could damage the robot): back off to the
// last safe position, in a pipe, or back out of the manhole after a dangerous passage (two rows:
// which applies depends on where the robot is). MALFUNCTION: reboot the robot and resume if the
// fault was temporary. Every row has a bounded number of tries; when all fail, the planning
// system changes its world model and replans.
//
//   RecoveryProfile profile;              // the default table: no push
//   profile.push_allowed = true;          // a test bed where pushing is safe
//   Result<RecoveryProfile> p = read_recovery_json(text, "recovery.json");
//   for (const RecoveryStage& stage : p->stages) ...   // in the order they are tried
//
// Thread safety: RecoveryProfile is a plain value; read_recovery_json shares nothing.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/result.h"
#include "sewerplan/hal/robot.h"

namespace sewerplan::executor {

// One manoeuvre of staged recovery.
enum class RecoveryPhase : std::uint8_t {
  kReboot,            // MALFUNCTION: reboot, resume the rest of the job
  kBackUpAndRetry,    // BLOCKAGE: back up the row's distance, drive the rest again
  kLiftHeadAndRetry,  // BLOCKAGE: lift the head, lower it, drive the rest again
  kPush,              // BLOCKAGE: push over the rest (push_allowed only)
  kBackOffToSafety,   // DANGER in a pipe: drive the row's distance back the way the robot came
  kBackOutOfManhole,  // DANGER in a manhole: back the row's distance into the pipe it came by
};

// What a manoeuvre is, whatever a profile says of it: the error it answers, its names, whether a
// row of it drives a distance, how often it can be tried at most, and what follows its last try.
struct RecoveryManoeuvre {
  RecoveryPhase phase;
  hal::RobotErrorKind error;
  std::string_view name;      // in a profile file ("back-up")
  std::string_view logged;    // the "recovery" event's `phase` (docs/executor.md)
  bool drives;                // its row's distance_m is how far it drives
  int max_tries;              // a row's bound is at most this
  std::string_view gives_up;  // after the last try
};

inline constexpr std::array<RecoveryManoeuvre, 6> kRecoveryManoeuvres{{
    {RecoveryPhase::kReboot, hal::RobotErrorKind::kMalfunction, "reboot", "reboot", false, 1000,
     "stuck: the Replanner is told the robot cannot move (beacon)"},
    {RecoveryPhase::kBackUpAndRetry, hal::RobotErrorKind::kBlockage, "back-up",
     "1: back up and retry", true, 1000,
     "on to the next blockage row (at once when there is no room to back up)"},
    {RecoveryPhase::kLiftHeadAndRetry, hal::RobotErrorKind::kBlockage, "lift-head",
     "2: lift the head and retry", false, 1000, "on to the next blockage row"},
    {RecoveryPhase::kPush, hal::RobotErrorKind::kBlockage, "push", "3: push", false, 1000,
     "on to the next blockage row (at once when a push cannot work from this side)"},
    {RecoveryPhase::kBackOffToSafety, hal::RobotErrorKind::kDanger, "back-off",
     "back off to safety", true, 1,
     "danger 1 mm ahead of where the robot stopped: the Replanner disconnects the pipe there"},
    {RecoveryPhase::kBackOutOfManhole, hal::RobotErrorKind::kDanger, "back-out-of-manhole",
     "back out of the manhole", true, 1, "the passage is closed both ways"},
}};

// The manoeuvre of `phase` (every phase has one row in kRecoveryManoeuvres).
constexpr const RecoveryManoeuvre& manoeuvre(RecoveryPhase phase) {
  for (const RecoveryManoeuvre& m : kRecoveryManoeuvres) {
    if (m.phase == phase) return m;
  }
  return kRecoveryManoeuvres[0];
}

// The stage's name as logged ("1: back up and retry").
constexpr std::string_view logged_name(RecoveryPhase phase) { return manoeuvre(phase).logged; }

// One row of a recovery profile: a manoeuvre, how often it is tried (for a reboot: reboots in a
// row that did not let the robot work, at most 20 per job in all), and how far it drives.
struct RecoveryStage {
  RecoveryPhase phase = RecoveryPhase::kReboot;
  int tries = 0;
  double distance_m = 0;  // for a manoeuvre that drives, else 0
  friend bool operator==(const RecoveryStage&, const RecoveryStage&) = default;
};

// The default table: the stages in the order they are tried for each error.
inline constexpr std::array<RecoveryStage, 6> kRecoveryTable{{
    {RecoveryPhase::kReboot, 2, 0},
    {RecoveryPhase::kBackUpAndRetry, 2, 0.05},
    {RecoveryPhase::kLiftHeadAndRetry, 1, 0},
    {RecoveryPhase::kPush, 1, 0},
    {RecoveryPhase::kBackOffToSafety, 1, 0.3},
    {RecoveryPhase::kBackOutOfManhole, 1, 0.3},
}};

// The running policy of staged recovery: its rows, and whether pushing is allowed at all.
struct RecoveryProfile {
  std::vector<RecoveryStage> stages{kRecoveryTable.begin(), kRecoveryTable.end()};
  bool push_allowed = false;  // the push rows run only with this (the CLI's --allow-push)

  // The first row of `phase`, or null when the profile has none.
  const RecoveryStage* stage(RecoveryPhase phase) const;
  // How often `stage` runs under this profile: its tries, 0 for a push without push_allowed.
  int tries(const RecoveryStage& stage) const;
  // The tries of the first row of `phase` (0: none).
  int tries(RecoveryPhase phase) const;

  friend bool operator==(const RecoveryProfile&, const RecoveryProfile&) = default;
};

// A recovery profile (docs/formats/recovery-json.md):
//   {"format": "sewerplan-recovery", "version": 1,
//    "malfunction": [{"manoeuvre": "reboot", "tries": 2}],
//    "blockage": [{"manoeuvre": "back-up", "tries": 2, "distance_m": 0.05}, ...],
//    "danger": [{"manoeuvre": "back-off", "distance_m": 0.3}, ...],
//    "push_allowed": false}
// An error's list, when given, replaces that error's default rows, in its order. Unknown fields,
// wrong types, a manoeuvre of another error or given twice, out-of-range tries or distances and
// a distance for a manoeuvre that does not drive are errors naming the file and field, all of them.
Result<RecoveryProfile> read_recovery_json(std::string_view text, const std::string& file_name);

}  // namespace sewerplan::executor
