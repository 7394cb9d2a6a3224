// SPDX-License-Identifier: MIT
// RecoveryConfig: how the action controller reacts to a robot error, as data (the paper, 6).
//
// BLOCKAGE (the path is blocked): phase 1 backs up a few centimetres and retries, phase 2 lifts
// the head and retries (light waste may be flushed away), phase 3 pushes, only where allowed:
// pushing is risky in a real sewer (the obstacle may get stuck between two segments), so it is
// off by default. DANGER (going on could damage the robot): back off to the last safe position.
// MALFUNCTION: reboot the robot and resume if the fault was temporary. Every phase has a bounded
// number of tries; when all fail, the planning system changes its world model and replans.
//
//   RecoveryConfig config;              // the defaults: no push
//   config.push_allowed = true;         // a test bed where pushing is safe
//   Result<RecoveryConfig> c = read_recovery_json(text, "recovery.json");
//
// Thread safety: RecoveryConfig is a plain value; read_recovery_json shares nothing.
#pragma once

#include <string>
#include <string_view>

#include "sewerplan/core/result.h"

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

// {"backup_retries": 2, "backup_m": 0.05, "lift_retries": 1, "push_allowed": false,
//  "push_retries": 1, "danger_backoff_m": 0.3, "max_reboots": 2}; every field optional. Unknown
// fields, wrong types and out-of-range values (negative counts or distances) are errors naming
// the file and field.
Result<RecoveryConfig> read_recovery_json(std::string_view text, const std::string& file_name);

}  // namespace sewerplan::executor
