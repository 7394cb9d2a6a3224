// SPDX-License-Identifier: MIT
// Measurer: turns the jobs a robot ran into measurements of its map (core/map_measurements.h).
//
// The paper's robot is to "measure positions of manholes and pipes ... to improve current maps"
// (section 1). The Measurer watches every job the action controller sends, its report, and where
// the controller had the robot before and after it (the Executor's dead reckoning, so no position
// of its own):
//   - a leg starts when the robot leaves a manhole into a pipe (a turn through the manhole, or
//     leaving the manhole it was lowered into) and ends when it arrives at the pipe's other end by
//     its own report: a sighting of the manhole, or a drive to the manhole (to_manhole) it
//     finished, as the localisation's arrivals (not a scan or drive of the map's distance that
//     the controller tracks to the mouth and that saw none: in a pipe longer than mapped it
//     stopped short, and the drive to the manhole that follows drives the rest; nor, once the
//     robot saw a manhole where the controller has it at the far end and took it for none, an
//     arrival the robot did not see: the controller's word against its sighting); the
//     signed sum of the drives' odometry between (towards the far end positive: a scan driven
//     backward counts back) is one length measurement, with sigma = sqrt((fraction x length)^2 +
//     floor^2), length the pipe's on the map (MeasuringOptions; not the leg's reading, which
//     made a pass that slipped short weigh more). A leg with a push (the wheels turn against the
//     obstacle), a report the link lost part of, or a report whose progress is not a number is not
//     measured, nor one that came back to the end it started from; one with a drive that failed
//     short of its goal (an obstacle, a danger, a fault, its bound without a manhole) is: the
//     robot's odometry counts what it drove, and recovery backs up and drives on by drives it
//     reports;
//   - an arrival with an observation (hal::JobReport::observation) is a signature measurement of
//     that manhole, relative to the slot arrived through; with a measured leg, also a position
//     estimate (map_measurements.h);
//   - a turn through a manhole that the robot measured (hal::JobReport::turn_measured_deg) is a
//     measurement of the angle between its two slots, to turn_sigma_deg (far more precise than a
//     sighting: it finds the slot directions a few degrees off, map_measurements.h);
//   - an observation in the middle of a pipe is a junction the map lacks, at the odometry's offset
//     (MapMeasurements::junctions) unless it is the far manhole seen early: the remaining distance
//     within early_arrival_fraction of the pipe's length and the signature matching that manhole's
//     (compare()): then the pipe is shorter than mapped, and the leg ends there. Nor is one within
//     end_margin_sigmas of the odometry (at least end_margin_m) of a manhole at either end of the
//     pipe: the odometry cannot tell it from that manhole.
// Whether an arrival is at the manhole the controller thinks is the localisation's to verify
// (issue 29); the Measurer takes the controller's positions as given.
//
//   Measurer measurer(map, {.robot = "makro", .mission = "paper", .date = "2026-12-06T07:00:00Z"});
//   executor.subscribe_jobs(measurer.observer());
//   executor.run();
//   MapMeasurements m = measurer.measurements();
//   m.discrepancies = discrepancies(m, map);
//
// Thread safety: not thread-safe; the Executor calls it on the thread that runs the mission.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sewerplan/core/job.h"
#include "sewerplan/core/manhole_signature.h"
#include "sewerplan/core/map_measurements.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/robot_state.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/robot.h"

namespace sewerplan::executor {

struct MeasuringOptions {
  double odometry_sigma_fraction = 0.03;  // of the pipe's length (the drift)
  double odometry_sigma_floor_m = 0.05;   // the wheels' resolution and the manhole's mouth
  // Wheels slip more where the pipe falls steeply (its ends' inverts, from the map): there the
  // fraction is this many times larger (docs/simulation.md has the robot's slip model). With one
  // sigma for every pipe, legs in steep pipes were reported as lengths off.
  double steep_fall_fraction = 0.02;
  double steep_sigma_factor = 2.0;
  // ... and in water (a leg with a drive that reported hal::JobReport::in_water) this many times
  // larger again. With the dry sigma for every leg, 18 of the 58 lengths reported off in 200 AIS
  // runs of the realistic world were right, 15 of them legs whose wheels had slipped in water.
  double water_sigma_factor = 2.0;
  double early_arrival_fraction = 0.25;  // see the header comment
  // A manhole seen in a pipe within this many odometry standard deviations of one of its ends
  // (and at least end_margin_m) is not taken for a junction the map lacks: the odometry cannot tell
  // it from the manhole at that end (a longer pipe, the mouth just left, a signature seen askew).
  double end_margin_sigmas = 3.0;
  double end_margin_m = 0.5;
  // A manhole seen in a pipe with a shaft narrower than this is a false detection (the pipe
  // widening, a joint), not a junction: DIN EN 476's smallest man-entry shaft is 0.8 m, less one
  // sighting's noise (SignatureNoise::shaft_m). On a 1,000-manhole meshed network, 40 runs of the
  // realistic world, such detections were 3 of the 6 false junction reports. (The localisation
  // weighs the same rule: LocalisationOptions::min_junction_shaft_m.)
  double min_junction_shaft_m = 0.7;
  SignatureNoise noise;  // for telling the far manhole from a junction
  // The standard deviation of a turn's angle as the robot's joints measure it
  // (hal::JobReport::turn_measured_deg; the simulated robot's, docs/simulation.md).
  double turn_sigma_deg = 1.0;
};

class Measurer {
 public:
  // `map` must outlive the Measurer.
  Measurer(const SewerMap& map, MeasurementSource source, MeasuringOptions options = {});

  // One job the robot ran: its report, where the controller had the robot before and after it,
  // and which way the job drove along the pipe (+1 towards ends[1], -1 towards ends[0], 0: it
  // does not drive).
  void observe(const Job& job, const hal::JobReport& report, const domain::RobotPosition& before,
               const domain::RobotPosition& after, double direction);
  // observe() as an Executor's job observer (Executor::subscribe_jobs). The Measurer must outlive
  // the Executor's run.
  JobObserver observer();

  const MapMeasurements& measurements() const { return measurements_; }
  // Reports not used, and why: "P5: odometry is not a number", "M6: signature: slot 2: ...".
  const std::vector<std::string>& rejected() const { return rejected_; }

 private:
  struct Leg {
    PipeId pipe{0};
    std::uint8_t from_end = 0;
    double driven_m = 0;  // towards the far end
    bool clean = true;
    bool in_water = false;  // a drive of it reported water
    // The robot saw a manhole where the controller has it at the far end, and the controller
    // took it for none (unlike the far manhole): only an arrival the robot sees ends the leg.
    bool refused_at_end = false;
  };

  void start_leg(const domain::RobotPosition& after);
  void turn(const TurnInManhole& job, const hal::JobReport& report,
            const domain::RobotPosition& before, const domain::RobotPosition& after);
  void drive(const Job& job, const hal::JobReport& report, const domain::RobotPosition& after,
             double direction);
  void end_leg(ManholeId manhole, SlotIndex slot);
  void arrival(ManholeId manhole, SlotIndex slot, const ManholeSignature& seen);
  // The odometry's standard deviation over distance_m in pipe (steep: from the map; in water:
  // as the robot reported).
  double sigma_m(double distance_m, PipeId pipe, bool in_water) const;
  bool valid(const ManholeSignature& seen, const std::string& where);
  // Whether a sighting at `offset_m` in `pipe` (standard deviation `sigma_m`) lies within the end
  // margin of a manhole at one of its ends; if so, says why in rejected().
  bool near_an_end(const Pipe& pipe, double offset_m, double sigma_m);
  // Whether a manhole seen in `pipe` at `offset_m` has a shaft too narrow for a junction; if so,
  // says why in rejected().
  bool too_narrow(const Pipe& pipe, double offset_m, const ManholeSignature& seen);

  const SewerMap& map_;
  MeasuringOptions options_;
  MapMeasurements measurements_;
  std::optional<Leg> leg_;
  std::vector<std::string> rejected_;
};

}  // namespace sewerplan::executor
