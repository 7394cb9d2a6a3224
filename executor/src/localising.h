// SPDX-License-Identifier: MIT
// Localising: the action controller's manhole verification, over the topological filter.
//
// Private to executor. The controller tracks the robot by the plan and the jobs' reports
// (DeadReckoning); a robot on a wrong map with slipping wheels may not be where that puts it.
// Localising feeds every job and its report to a localisation::TopologicalFilter (odometry, turns,
// arrivals at detected manholes with their signatures) and, when a job ends at a manhole, checks
// the arrival against the manhole the tracking expects (docs/localisation.md): the arrival
// matches, or it does not, with the filter's most likely place and why.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "sewerplan/core/job.h"
#include "sewerplan/core/manhole_signature.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/robot_state.h"
#include "sewerplan/hal/robot.h"
#include "sewerplan/localisation/topological_filter.h"

namespace sewerplan::executor::detail {

// A job's end at a manhole (or at what the robot took for one), checked.
struct Arrival {
  // The mouth the robot arrived at as the plan's drive expected it: where the tracking has it, or,
  // when that is in a pipe, the far end of that pipe reached sooner than the map says (the
  // arrival then matches). Empty when it stopped at no manhole the drive was going to.
  std::optional<domain::AtSlot> expected;
  localisation::Verification verification;
  std::optional<ManholeSignature> observation;
  // Whether the drive that arrived went forward (the robot's front at the manhole).
  bool forward = true;
  // Whether the controller should log it: the robot observed the manhole, or the check failed.
  bool worth_logging() const { return observation.has_value() || !verification.matches(); }
};

class Localising {
 public:
  // `odometry_sd_fraction`: the odometry's standard deviation per metre driven (the robot
  // profile's: ExecutorOptions::odometry_sd_fraction).
  // `memory`: what earlier missions remembered of the pipes (Learnt::junctions), which the filter
  // starts from; one the filter refuses (check_memory) is not used.
  Localising(const SewerMap& map, double odometry_sd_fraction,
             const localisation::JunctionMemory& memory = {},
             localisation::LocalisationOptions options = {});

  // The robot is at `position` (facing `heading_end` in a pipe), certainly: the mission's start,
  // or a place the controller settled on.
  void reset(const domain::RobotPosition& position, std::uint8_t heading_end);

  // Follows `job` and its report; `before` is where the tracking had the robot before the job,
  // `after` (facing `after_heading_end` in a pipe) where it has it now. Returns the checked
  // arrival when the job ended at a manhole. An update the filter refuses restarts it from
  // `after` (restarts()), so that a later arrival is still checked.
  std::optional<Arrival> follow(const Job& job, const hal::JobReport& report,
                                const domain::RobotPosition& before,
                                const domain::RobotPosition& after, std::uint8_t after_heading_end);

  // The robot refused a job that needs it at a manhole (hal::RobotErrorCause::kNotAtStart for a
  // turn) where the filter had it arrived: the filter's most likely place in a pipe (the stop was
  // a false detection). Empty when the filter has none: it then starts again at the next reset().
  std::optional<localisation::Hypothesis> not_at_manhole();

  // How often the filter had to start again from the tracking's place.
  int restarts() const { return restarts_; }

  // The filter's belief; lost when the filter could explain nothing (then reset()).
  localisation::Estimate estimate() const;

  const localisation::LocalisationOptions& options() const { return options_; }

  // What the filter remembers of the pipes: what it started from and what it learnt since (kept
  // across restarts). Empty without a filter.
  localisation::JunctionMemory memory() const;

 private:
  const SewerMap& map_;
  double odometry_sd_fraction_;
  localisation::LocalisationOptions options_;
  std::optional<localisation::TopologicalFilter> filter_;
  std::optional<Arrival> follow_filter(const Job& job, const hal::JobReport& report,
                                       const domain::RobotPosition& before,
                                       const domain::RobotPosition& after);

  bool usable_ = false;  // the filter follows the robot (false after an update it refused)
  int restarts_ = 0;
  // What the robot saw at its last arrival: a turn by sighting (kBySighting) names its mouths.
  std::optional<ManholeSignature> last_observation_;
};

// The first mouth of the manhole `arrival` expected that the robot's observation lacks (the slot
// counts differ and no sighting pairs with it: a lateral the world lacks), if any.
std::optional<Slot> missing_mouth(const Arrival& arrival, const SewerMap& map,
                                  const SignatureNoise& noise);

// The pass straight on through a manhole the map lacks that a drive in `pipe` arrived at (a robot
// that arrived rear first leaves it front first, facing the way it was backing): into the
// mouth the robot saw most nearly straight ahead, when one is seen within
// `options.straight_through_deg` plus two sightings' noise (noise.direction_deg each), of the
// pipe's size (the map's, or the size seen of the mouth the robot came out of), with a step the
// robot can climb, addressed by sighting (kBySighting); else empty. With the map's size and 30
// degrees alone, a robot backing out through a junction it had passed was shut in behind it where
// the pipe was narrower than mapped, or the way on was seen 32 degrees off (AIS, realistic world,
// seeds 33, 36, 38, 42 and 58).
std::optional<TurnInManhole> straight_through(const Arrival& arrival, const SewerMap& map,
                                              PipeId pipe,
                                              const localisation::LocalisationOptions& options,
                                              const RobotProfile& profile);

// The signature in a log line: "4 slots at 0, 92, 181, 268°".
std::string signature_text(const ManholeSignature& signature);

}  // namespace sewerplan::executor::detail
