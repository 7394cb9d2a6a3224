// SPDX-License-Identifier: MIT
// Job: one command of the robot's base machine, what the action controller sends to a robot.
//
// MAKRO's low-level controller executes short manoeuvres (paper, sections 2.3 and 4.6): drive a
// distance forward or back at a speed, turn through a manhole from one pipe mouth to another, lift
// and lower the head, take a water sample, scan while driving, stop. Fusion (fusion/) expands each
// parameterised action of a plan into jobs; a robot (hal/: simulated, or over the CAN bus) runs
// them one at a time. Jobs are relative to where the robot is: a drive follows the pipe it is in,
// a turn starts at the mouth it is at. They are plain values, so that a log can record them and a
// bus can carry them.
//
//   Job j = DriveForward{.speed_mps = 0.3, .distance_m = 12.5};
//   std::cout << j;  // "DriveForward(0.30 m/s, 12.50 m)"
//
// Thread safety: Plain values: const access from several threads is safe; a value being changed
// must not be read at the same time.
#pragma once

#include <cstdint>
#include <ostream>
#include <string_view>
#include <variant>
#include <vector>

namespace sewerplan {

// Drive along the pipe, away from the mouth the robot entered by (forward) or back towards it.
//
// `to_manhole`: the drive ends at a manhole's mouth (fusion sets it for every drive to a manhole).
// distance_m is then the map's distance, and the map may be wrong: the robot stops at the manhole
// when it detects it sooner, and where it has not seen it after distance_m, it drives on, at most
// beyond_manhole_limit_m(distance_m) further, until it does (docs/simulation.md). Not shown by
// operator<< (the event log's job text stays as it was).
struct DriveForward {
  double speed_mps = 0;
  double distance_m = 0;
  bool to_manhole = false;
  friend bool operator==(const DriveForward&, const DriveForward&) = default;
};

struct DriveBackward {
  double speed_mps = 0;
  double distance_m = 0;
  bool to_manhole = false;
  friend bool operator==(const DriveBackward&, const DriveBackward&) = default;
};

// How much farther than the map's distance a drive `to_manhole` may go looking for the manhole:
// a quarter of the distance and 2 m (the realistic world profile's lengths are off by up to 20 %
// and 0.5 m, its odometry by 3 %: hal/world_errors.h).
constexpr double beyond_manhole_limit_m(double distance_m) { return 0.25 * distance_m + 2.0; }

// Drive against an obstacle to move it (recovery phase 3; risky in a real sewer): forward, pushing
// with the front head, or backward, pushing with the rear head (for an obstacle met while backing:
// the robot cannot turn in a pipe).
struct Push {
  double speed_mps = 0;
  double distance_m = 0;
  bool backward = false;
  friend bool operator==(const Push&, const Push&) = default;
};

// A point of a turning manoeuvre's path, in the manhole's frame: metres from its axis at the
// floor, z up; heading in degrees (azimuth convention of map slots).
struct Waypoint {
  double x_m = 0;
  double y_m = 0;
  double z_m = 0;
  double heading_deg = 0;
  friend bool operator==(const Waypoint&, const Waypoint&) = default;
};

// Pass a manhole from the mouth of slot `from_slot` into the pipe of slot `to_slot` (slots from 0),
// turning `turn_deg` and climbing `step_m` (negative: down). `waypoints` is the motion planned for
// the body, when there is one; the controller otherwise uses its own manoeuvre.
//
// A manhole the map lacks has no slot numbers: with `from_slot` kBySighting the robot leaves by
// the mouths as it saw them on arriving (a ManholeSignature's order): from the mouth it arrived
// by into the `to_slot`-th counter-clockwise from it (1 .. slots - 1).
inline constexpr std::uint16_t kBySighting = 0xFFFF;

struct TurnInManhole {
  std::uint16_t from_slot = 0;
  std::uint16_t to_slot = 0;
  double turn_deg = 0;
  double step_m = 0;
  double manhole_diameter_m = 0;
  double duration_s = 0;
  std::vector<Waypoint> waypoints;
  friend bool operator==(const TurnInManhole&, const TurnInManhole&) = default;
};

// Leave the manhole the robot was lowered into, into the pipe of slot `slot`.
struct EnterPipeFromManhole {
  std::uint16_t slot = 0;
  double duration_s = 0;
  friend bool operator==(const EnterPipeFromManhole&, const EnterPipeFromManhole&) = default;
};

struct LiftHead {
  friend bool operator==(const LiftHead&, const LiftHead&) = default;
};

struct LowerHead {
  friend bool operator==(const LowerHead&, const LowerHead&) = default;
};

struct TakeSample {
  double duration_s = 0;
  friend bool operator==(const TakeSample&, const TakeSample&) = default;
};

// Drive while scanning the pipe wall: forward, or backward (an inspection that finishes at the end
// the robot came in by).
struct Scan {
  double speed_mps = 0;
  double distance_m = 0;
  bool backward = false;
  friend bool operator==(const Scan&, const Scan&) = default;
};

struct Stop {
  friend bool operator==(const Stop&, const Stop&) = default;
};

using Job = std::variant<DriveForward, DriveBackward, Push, TurnInManhole, EnterPipeFromManhole,
                         LiftHead, LowerHead, TakeSample, Scan, Stop>;

// "drive_forward", "drive_backward", "push", "turn_in_manhole", "enter_pipe", "lift_head",
// "lower_head", "take_sample", "scan", "stop".
std::string_view job_kind(const Job& job);

// "DriveForward(0.30 m/s, 12.50 m)", "TurnInManhole(slot 3 -> 4, 45.0 deg, step -0.10 m)" (with
// ", 31 waypoints" when it has a planned motion), "Push(0.10 m/s, 2.00 m, backward)", ...
std::ostream& operator<<(std::ostream& os, const Job& job);

}  // namespace sewerplan
