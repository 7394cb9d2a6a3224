// SPDX-License-Identifier: MIT
// What clears an obstacle: the one table of which manoeuvre moves each kind of hidden obstacle out
// of the way, and from which side.
//
// MAKRO drives both ways along a pipe, so it meets an obstacle either with its front (driving
// forward) or with its rear (backing). Lifting the head frees an obstacle within reach on either
// side of it; a push moves an obstacle met either way, with the front head driving forward or the
// rear head backing (core/job.h, Push::backward: the robot cannot turn in a pipe, so an obstacle
// met while backing is pushed backward); a permanent obstacle never clears. (Until issue 30 the
// robot pushed with its front head only, and an obstacle only a push clears, met while backing,
// stayed.) The simulated robot (sim_robot.h) clears obstacles by this
// table, the action controller's staged recovery tries the manoeuvres it names
// (executor/recovery_clears.h), and the campaign's oracle knows in advance which obstacles the
// recovery clears from both sides, from one side only, or from neither (campaign/run.h): the
// three agree on every obstacle, met either way.
//
//   clears_from(ObstacleKind::kTransientPush, Approach::kRear);  // true: a backward push
//   clears_from(ObstacleKind::kPermanent, Approach::kFront);     // false
//
// Thread safety: constants and pure functions.
#pragma once

#include <array>
#include <cstdint>

#include "sewerplan/hal/fault_scenario.h"

namespace sewerplan::hal {

// The manoeuvre that clears an obstacle.
enum class Clearing : std::uint8_t {
  kNothing,   // nothing the robot does: the pipe is blocked there
  kLiftHead,  // lifting the head within lift reach of it
  kPush,      // driving against it with a Push job
};

// How the robot meets an obstacle: front first (driving forward) or rear first (backing).
enum class Approach : std::uint8_t { kFront, kRear };

struct ObstacleClearing {
  ObstacleKind kind;
  Clearing by;
  bool from_front;
  bool from_rear;
};

inline constexpr std::array<ObstacleClearing, 3> kObstacleClearing{{
    {ObstacleKind::kTransientLift, Clearing::kLiftHead, true, true},
    // The robot pushes with its front head forward, with its rear head backward (core/job.h, Push).
    {ObstacleKind::kTransientPush, Clearing::kPush, true, true},
    {ObstacleKind::kPermanent, Clearing::kNothing, false, false},
}};

constexpr const ObstacleClearing& clearing_of(ObstacleKind kind) {
  for (const ObstacleClearing& row : kObstacleClearing) {
    if (row.kind == kind) return row;
  }
  return kObstacleClearing.back();
}

// The manoeuvre that clears `kind`.
constexpr Clearing cleared_by(ObstacleKind kind) { return clearing_of(kind).by; }

// Whether that manoeuvre clears `kind` met with `approach`.
constexpr bool clears_from(ObstacleKind kind, Approach approach) {
  const ObstacleClearing& row = clearing_of(kind);
  return row.by != Clearing::kNothing &&
         (approach == Approach::kFront ? row.from_front : row.from_rear);
}

// Whether the manoeuvre `by` clears some kind of obstacle met with `approach`: whether a robot
// that met an obstacle of a kind it cannot tell that way should try it (staged recovery does).
constexpr bool works_from(Clearing by, Approach approach) {
  for (const ObstacleClearing& row : kObstacleClearing) {
    if (row.by == by && clears_from(row.kind, approach)) return true;
  }
  return false;
}

}  // namespace sewerplan::hal
