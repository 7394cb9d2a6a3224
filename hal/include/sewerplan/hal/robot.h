// SPDX-License-Identifier: MIT
// Robot: the interface between the action controller and a robot, simulated or real.
//
// The executor (executor/) sends one job (core/job.h) at a time and waits for its report: done,
// or failed with an error the robot classifies as the paper does (section 4.7): BLOCKAGE (the path
// is blocked), DANGER (going on could damage the robot) or MALFUNCTION (a software or hardware
// fault). A report says how far the job got, so that the controller knows where the robot is. The
// robot behind this interface may be the seeded simulator (sim_robot.h) or the CAN bus; the
// executor cannot tell them apart.
//
//   JobReport r = robot.execute(DriveForward{.speed_mps = 0.3, .distance_m = 12});
//   if (!r.ok() && r.error->kind == RobotErrorKind::kMalfunction) robot.reboot();
//   if (!r.ok() && r.error->cause == RobotErrorCause::kLink) ...  // the link failed, not the robot
//
// Thread safety: A Robot is not thread-safe unless an implementation says so: one thread drives it.
// The exception is emergency_stop(), which every implementation must allow from any thread, also
// while execute() runs on another (Executor::halt calls it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>

#include "sewerplan/core/job.h"
#include "sewerplan/core/manhole_signature.h"
#include "sewerplan/core/result.h"

namespace sewerplan::hal {

enum class RobotErrorKind { kBlockage, kDanger, kMalfunction };

// "blockage", "danger", "malfunction"; and back (empty for any other text).
std::string_view to_string(RobotErrorKind kind);
std::optional<RobotErrorKind> parse_robot_error_kind(std::string_view name);

// What stopped a job, typed by the robot beside the paper's kind: the controller decides by it
// (the executor's beacon says whether the robot failed itself, or its link did), never by the
// words of the reason, which are for people and may change. Each cause is of one kind
// (kind_of). The kOther* causes are errors of a kind the robot did not type further: a CAN node
// of an earlier version sends the kind alone (docs/can-protocol.md).
enum class RobotErrorCause : std::uint8_t {
  // BLOCKAGE
  kObstacle,       // "obstacle": something in the pipe stops the drive
  kBlindEnd,       // "blind-end": the pipe ends where the map has it go on
  kNoManholeSeen,  // "no-manhole-seen": a drive to a manhole went its bound and saw none
  kNoMouth,        // "no-mouth": a turn into a mouth the manhole does not have (no way through)
  kOtherBlockage,  // "blockage"
  // DANGER
  kDangerSpot,        // "danger-spot": a spot in the pipe the robot must not drive onto
  kDangerousPassage,  // "dangerous-passage": a way through a manhole it must not take
  kOtherDanger,       // "danger"
  // MALFUNCTION
  kFault,             // "fault": the robot's hardware or software failed (motor, sensor, crash)
  kBatteryEmpty,      // "battery-empty"
  kInvalidJob,        // "invalid-job": a job it cannot run anywhere (bad numbers, a limit)
  kNotAtStart,        // "not-at-start": it is not where the job starts (no mouth, no manhole)
  kEmergencyStop,     // "emergency-stop": stopped (emergency_stop(), a stop latched in a node)
  kLink,              // "link": the link to the robot failed (CAN, can_robot.h): not the robot
  kOtherMalfunction,  // "malfunction" (stays the last)
};
inline constexpr std::size_t kRobotErrorCauses =
    static_cast<std::size_t>(RobotErrorCause::kOtherMalfunction) + 1;

// The kind a cause is of.
constexpr RobotErrorKind kind_of(RobotErrorCause cause) {
  switch (cause) {
    case RobotErrorCause::kObstacle:
    case RobotErrorCause::kBlindEnd:
    case RobotErrorCause::kNoManholeSeen:
    case RobotErrorCause::kNoMouth:
    case RobotErrorCause::kOtherBlockage:
      return RobotErrorKind::kBlockage;
    case RobotErrorCause::kDangerSpot:
    case RobotErrorCause::kDangerousPassage:
    case RobotErrorCause::kOtherDanger:
      return RobotErrorKind::kDanger;
    case RobotErrorCause::kFault:
    case RobotErrorCause::kBatteryEmpty:
    case RobotErrorCause::kInvalidJob:
    case RobotErrorCause::kNotAtStart:
    case RobotErrorCause::kEmergencyStop:
    case RobotErrorCause::kLink:
    case RobotErrorCause::kOtherMalfunction:
      return RobotErrorKind::kMalfunction;
  }
  return RobotErrorKind::kMalfunction;
}

// The cause of an error known by its kind alone: kOtherBlockage, kOtherDanger, kOtherMalfunction.
constexpr RobotErrorCause other_cause(RobotErrorKind kind) {
  switch (kind) {
    case RobotErrorKind::kBlockage:
      return RobotErrorCause::kOtherBlockage;
    case RobotErrorKind::kDanger:
      return RobotErrorCause::kOtherDanger;
    case RobotErrorKind::kMalfunction:
      return RobotErrorCause::kOtherMalfunction;
  }
  return RobotErrorCause::kOtherMalfunction;
}

// The names in the comments above ("obstacle", "link", ...); and back (empty for any other text).
std::string_view to_string(RobotErrorCause cause);
std::optional<RobotErrorCause> parse_robot_error_cause(std::string_view name);

// An error of the robot: its kind and cause agree by construction (a cause gives its kind; a
// kind alone, its kOther* cause).
struct RobotError {
  RobotError() = default;
  RobotError(RobotErrorCause c, std::string why)
      : kind(kind_of(c)), cause(c), reason(std::move(why)) {}
  RobotError(RobotErrorKind k, std::string why)
      : kind(k), cause(other_cause(k)), reason(std::move(why)) {}

  RobotErrorKind kind = RobotErrorKind::kMalfunction;
  RobotErrorCause cause = RobotErrorCause::kOtherMalfunction;
  std::string reason;  // "obstacle 0.20 m ahead", "motor 3 over current", ...: for people
  friend bool operator==(const RobotError&, const RobotError&) = default;
};

// What became of a request to switch the locator beacon on: the robot says it is on, or the
// request went out and no answer confirmed it (it may be on), or it could not even be sent (the
// line is closed: most likely off). kNone: no beacon was asked for.
enum class BeaconState { kNone, kConfirmed, kUnconfirmed, kNotSent };

// "none", "confirmed", "unconfirmed", "not-sent"; and back (empty for any other text).
std::string_view to_string(BeaconState state);
std::optional<BeaconState> parse_beacon_state(std::string_view name);

struct JobReport {
  std::optional<RobotError> error;  // empty: the job was done
  // Distance driven by this job (drives and scans), as the wheels measured it: odometry, which
  // slips (the truth stays in the robot, or the simulator).
  double progress_m = 0;
  double duration_s = 0;  // time the job took
  double energy_wh = 0;   // energy it used
  // What the robot saw of the manhole a drive ended at, when it detected one (also a false
  // detection: something it took for a manhole). Empty after every other job, when the robot
  // missed the manhole, and from a robot that does not observe (the exact simulated world,
  // hal/sim_robot.h SensingModel). Over CAN it crosses in the job's RESULT (docs/can-protocol.md).
  std::optional<ManholeSignature> observation;
  // What the robot's joint encoders measured of a TurnInManhole it made: the direction of the
  // mouth it left by, counter-clockwise from the mouth it came from, in [0, 360): a SlotSighting's
  // relative_deg (core/manhole_signature.h), the heading change through the manhole plus 180
  // degrees. Far more precise than a sighting of the mouth (about 1 degree against 8). Empty after
  // every other job, after a turn that failed, and from a robot that does not measure its turns
  // (the exact simulated world, hal/sim_robot.h SensingModel). Over CAN in the job's RESULT
  // (docs/can-protocol.md).
  std::optional<double> turn_measured_deg;
  // The robot drove through water in this job: standing or flowing water in the pipe, as its
  // camera sees it (EN 13508-2's water level, which every inspection records). Wheels slip more
  // in water, so its odometry is less certain there (hal/sim_robot.h SensingModel::wet). False:
  // dry, every job that drives nothing, and a robot that does not tell. Over CAN a flag of the
  // job's RESULT (docs/can-protocol.md).
  bool in_water = false;
  bool ok() const { return !error.has_value(); }
  friend bool operator==(const JobReport&, const JobReport&) = default;
};

// What the robot knows of itself.
struct RobotStatus {
  double battery_wh = 0;  // left
  double odometry_m = 0;  // distance driven since start
  double elapsed_s = 0;   // mission time since start
  bool head_lifted = false;
  bool beacon_on = false;
  friend bool operator==(const RobotStatus&, const RobotStatus&) = default;
};

class Robot {
 public:
  virtual ~Robot() = default;

  // Runs `job` to its end or to the first error; never throws.
  virtual JobReport execute(const Job& job) = 0;
  virtual RobotStatus status() const = 0;
  // Restarts the robot's control software; the error, if the fault was permanent, reads
  // "reboot failed: why".
  virtual Result<void> reboot() = 0;
  // The report of the last job when the one execute() returned was not the robot's own: a link
  // that lost the job's result (CanRobot: a MALFUNCTION "CAN link: ..." with the progress last
  // heard) asks the robot for it when it reboots, so that the job goes on from where the robot
  // really is. Empty otherwise (every in-process robot), and after it was taken once.
  virtual std::optional<JobReport> recovered_report() { return std::nullopt; }
  // Switches on the locator beacon, so that the robot can be found and recovered; says whether the
  // robot confirmed it.
  virtual BeaconState activate_beacon() = 0;
  // Stops the robot where it is: the job running ends early (its report, a MALFUNCTION
  // "emergency stop", says how far it got), and every job after it fails the same way, the robot
  // not moving, until reboot() clears the stop. Thread-safe (above); returns at once.
  virtual void emergency_stop() = 0;
};

std::ostream& operator<<(std::ostream& os, const RobotError& error);

}  // namespace sewerplan::hal
