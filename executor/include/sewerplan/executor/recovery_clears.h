// SPDX-License-Identifier: MIT
// What staged recovery clears: for each kind of hidden obstacle and the way the robot meets it,
// whether the blockage rows of a RecoveryProfile (recovery.h) that it lets run move it
// out of the way. The manoeuvres and the sides they work from are hal's one table
// (hal/obstacle_clearing.h); here each stage is tied to its manoeuvre and counted by its tries.
// The campaign's oracle asks this, so the oracle and the action controller agree on every
// obstacle, met either way (tests/executor/obstacle_clearing_test.cc drives into each kind both
// ways, with and without pushing).
//
//   RecoveryProfile config;
//   config.push_allowed = true;
//   recovery_clears(config, hal::ObstacleKind::kTransientPush, hal::Approach::kFront);  // true
//   recovery_clears(config, hal::ObstacleKind::kTransientPush, hal::Approach::kRear);   // true
//
// Thread safety: pure functions.
#pragma once

#include "sewerplan/executor/recovery.h"
#include "sewerplan/hal/obstacle_clearing.h"

namespace sewerplan::executor {

// The manoeuvre a stage carries out (hal::Clearing::kNothing for backing up, rebooting, backing
// off).
hal::Clearing manoeuvre_of(RecoveryPhase phase);

// Whether a blockage row that `config` tries clears an obstacle of `kind` met with `approach`.
bool recovery_clears(const RecoveryProfile& config, hal::ObstacleKind kind, hal::Approach approach);

}  // namespace sewerplan::executor
