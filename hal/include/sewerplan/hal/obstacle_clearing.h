// SPDX-License-Identifier: MIT
// What clears an obstacle: the one table of which manoeuvre moves each kind of hidden obstacle out
// of the way, and from which side.
//
// MAKRO drives both ways along a pipe, so it meets an obstacle either with its front (driving
// forward) or with its rear (backing). Lifting the head frees an obstacle within reach on either
// side of it; pushing is done with the head, so it moves only an obstacle met front first; a
// permanent obstacle never clears. The simulated robot (sim_robot.h) clears obstacles by this
// table, the action controller's staged recovery tries the manoeuvres it names
// (executor/recovery_clears.h), and the campaign's oracle knows in advance which obstacles the
// recovery clears from both sides, from one side only, or from neither (campaign/run.h): the
// three agree on every obstacle, met either way.
//
//   if (clears_from(ObstacleKind::kTransientPush, Approach::kRear)) ...  // false: no push backward
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
    // The robot pushes with its head (core/job.h, Push): only what it meets front first.
    {ObstacleKind::kTransientPush, Clearing::kPush, true, false},
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

}  // namespace sewerplan::hal
