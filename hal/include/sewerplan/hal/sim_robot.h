// SPDX-License-Identifier: MIT
// SimRobot: a simulated robot in a ground-truth sewer with hidden faults, behind hal::Robot.
//
// The executor drives a SimRobot exactly as it would drive MAKRO over the CAN bus: one job
// (core/job.h) at a time, each answered by a JobReport. The simulator knows the truth the planner
// does not: the map, the robot profile (speeds, power, battery), where the robot really is (a
// SimPose), and a FaultScenario (fault_scenario.h) of obstacles, dangers and malfunctions. It
// moves the robot along pipes and through manholes, stops it in front of obstacles and dangers,
// drains the battery and counts odometry and time. The model, its constants and its choices
// (what a drive past a pipe end does, how long a head movement takes, ...) are in
// docs/simulation.md.
//
// Deterministic: no wall clock and no randomness; time is simulated, advanced by each job's
// duration (and, when one is given, on a ManualClock shared with the executor). The same map,
// profile, start, scenario and jobs give the same reports.
//
//   SimRobot robot(map, *builtin_profile("makro-1.1"), InPipe{p12, 3.0, Heading::kTowardsEnd0},
//                  *read_faults("blocked-p5.json", map, diagnostics));
//   JobReport r = robot.execute(DriveForward{.speed_mps = 0.3, .distance_m = 20});
//   // r.error: blockage "obstacle in P5 at 4.00 m", r.progress_m: how far it got
//
// An emergency stop latches: a simulated job takes no wall time, so a stop during execute() takes
// effect when it returns; the next job ends at once, the robot where it is (progress 0), and so
// does every one after it until reboot().
//
// Thread safety: A SimRobot is not thread-safe: one thread drives it (a SimNode's thread, behind
// CAN); emergency_stop() may be called from any thread.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <variant>
#include <vector>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/rng.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/obstacle_clearing.h"
#include "sewerplan/hal/robot.h"

namespace sewerplan::hal {

// Lowered into a manhole, at no pipe mouth (a mission's start).
struct InManhole {
  ManholeId manhole{0};
  friend bool operator==(const InManhole&, const InManhole&) = default;
};

// Which way the robot faces at a pipe mouth.
enum class Facing : std::uint8_t {
  kIntoManhole,  // it drove out of the pipe forward: DriveBackward goes back into the pipe
  kIntoPipe,     // it backed out of the pipe: DriveForward goes back into the pipe
};

// In a manhole at the mouth of a slot's pipe.
struct AtSlot {
  ManholeId manhole{0};
  SlotIndex slot{0};
  Facing facing = Facing::kIntoManhole;
  friend bool operator==(const AtSlot&, const AtSlot&) = default;
};

// Which end of its pipe the robot's front points to; DriveForward moves that way.
enum class Heading : std::uint8_t { kTowardsEnd0, kTowardsEnd1 };

// In a pipe, offset_m from its ends[0].
struct InPipe {
  PipeId pipe{0};
  double offset_m = 0;
  Heading heading = Heading::kTowardsEnd1;
  friend bool operator==(const InPipe&, const InPipe&) = default;
};

using SimPose = std::variant<InManhole, AtSlot, InPipe>;

// "in manhole #2", "at manhole #5 slot 3 facing the manhole", "in pipe #4 at 2.50 m towards end 1"
// (slots numbered from 1, as in the paper).
std::ostream& operator<<(std::ostream& os, const SimPose& pose);
// The same with the map's names: "at M6 slot 3 (P5) facing the manhole".
std::string describe(const SimPose& pose, const SewerMap& map);

// The robot's sensing errors (docs/simulation.md, "Sensing"): odometry that slips, manholes it
// misses or sees where there are none, and noisy observations of manholes. The default is exact
// sensing with no observations: the simulator as it was before issue 29. make_sensing
// (hal/world_errors.h) sets it from a world error profile.
struct SensingModel {
  double drift = 0;  // odometry: standard deviation of a drive's error, share of its length
  // Per pipe of the robot's world: wet (slip x2; a drive in it reports JobReport::in_water).
  // Empty: none.
  std::vector<bool> wet;
  double missed_share = 0;  // of manhole arrivals, not detected
  double false_per_km = 0;  // false manhole detections per km of drives to a manhole
  bool observe = false;     // report the manhole's signature at the end of a drive (JobReport)
  std::optional<SignatureNoise> signature_noise;  // empty: exact observations
  // A turn's angle as the joint encoders measure it (JobReport::turn_measured_deg): the standard
  // deviation of its error, in degrees. Empty: turns are not measured (nothing reported).
  std::optional<double> turn_noise_deg;
  std::uint64_t seed = 0;
};

// The constants of the model (docs/simulation.md).
struct SimOptions {
  double clearance_m = 0.05;  // the robot stops this far before an obstacle or a danger spot
  double lift_reach_m = 0.5;  // a lifted head clears a transient_lift obstacle this close
  double head_move_s = 3;     // LiftHead and LowerHead
  double reboot_s = 30;       // reboot() takes this long and its energy
  // Advanced by every job's and reboot's duration, so that an executor sharing it sees simulated
  // time. Optional, non-owning; must outlive the robot.
  ManualClock* clock = nullptr;
  SensingModel sensing;
};

class SimRobot final : public Robot {
 public:
  // Preconditions (checked): `start` and the scenario's IDs belong to `map`; the profile is
  // valid. `map` must outlive the robot.
  SimRobot(const SewerMap& map, RobotProfile profile, SimPose start, FaultScenario faults = {},
           SimOptions options = {});

  JobReport execute(const Job& job) override;
  RobotStatus status() const override { return status_; }
  Result<void> reboot() override;
  BeaconState activate_beacon() override {
    status_.beacon_on = true;
    return BeaconState::kConfirmed;
  }
  void emergency_stop() override { stopped_.store(true); }
  bool emergency_stopped() const { return stopped_.load(); }

  // Ground truth, for tests and the simulator's log; the executor must not look.
  const SimPose& pose() const { return pose_; }
  // The obstacles not yet cleared.
  std::vector<Obstacle> remaining_obstacles() const;
  std::size_t jobs_executed() const { return jobs_executed_; }

 private:
  struct Fault {
    MalfunctionKind kind;
    std::string reason;
  };
  // A job cut short after_s seconds in: by an empty battery, or by a timed malfunction.
  struct Interrupt {
    double after_s = 0;
    std::optional<std::size_t> malfunction;  // empty: the battery
  };
  struct Move;

  JobReport run(const Job& job);
  JobReport drive(double speed_mps, double distance_m, int direction, bool push,
                  bool to_manhole = false);
  // `push`: how a push meets what it drives against; empty for a drive.
  Move plan_move(const InPipe& from, double distance_m, int sign,
                 std::optional<Approach> push) const;
  JobReport drive_in_pipe(const InPipe& from, double speed_mps, double distance_m, int direction,
                          bool push, bool to_manhole);
  // Sensing (docs/simulation.md): a zero-mean normal draw; the odometry of a true distance; what
  // the robot sees of a manhole, or of a pipe where it takes one for a manhole.
  double normal(double sigma);
  double odometry(double true_m, PipeId pipe);
  // Whether a drive of driven_m in `pipe` went through water (JobReport::in_water).
  bool in_water(double driven_m, PipeId pipe) const;
  // `order`, when given, is the map's slot of each of truth's mouths; it is reordered with them
  // (what the robot saw, in the order it saw it).
  ManholeSignature observe(ManholeSignature truth, std::vector<SlotIndex>* order = nullptr);
  ManholeSignature false_manhole(PipeId pipe);
  // A drive through a missed manhole: the slot straight on from `arrival`, if it has one whose
  // pipe the robot fits (its profile's sizes).
  std::optional<SlotIndex> straight_on(ManholeId manhole, SlotIndex arrival) const;
  JobReport turn(const TurnInManhole& job);
  // A turn addressed by the mouths seen on arrival (kBySighting), as one by slot numbers.
  JobReport turn_by_sighting(const TurnInManhole& job);
  JobReport enter(const EnterPipeFromManhole& job);
  JobReport set_head(bool lifted);
  // A job that keeps the robot where it is for duration_s, unless interrupted.
  JobReport stand(double duration_s);
  std::optional<Interrupt> interrupt_within(double duration_s) const;
  JobReport interrupt(const Interrupt& stop, JobReport report);
  void strike(std::size_t malfunction, const std::string& when);
  static JobReport failure(RobotErrorCause cause, std::string reason);
  static JobReport invalid(const std::string& what);
  // Charges the report's time and energy and adds its progress to the status.
  JobReport finish(JobReport report);

  const SewerMap& map_;
  RobotProfile profile_;
  SimPose pose_;
  FaultScenario faults_;
  std::vector<bool> obstacle_cleared_;
  std::vector<bool> malfunction_struck_;
  SimOptions options_;
  RobotStatus status_;
  std::optional<Fault> fault_;
  bool battery_empty_ = false;
  std::size_t jobs_executed_ = 0;
  std::atomic<bool> stopped_{false};  // the emergency stop, latched until reboot()
  Rng sensing_rng_;
  // The turns' measurement errors: a stream of their own, so that measuring turns leaves every
  // other draw (slip, misses, observations) as it was.
  Rng turn_rng_;
  // The mouths of the last manhole observed, in the order the robot saw them (kBySighting).
  struct Sighting {
    ManholeId manhole;
    SlotIndex arrival;
    std::vector<SlotIndex> order;
  };
  std::optional<Sighting> sighting_;
};

}  // namespace sewerplan::hal
