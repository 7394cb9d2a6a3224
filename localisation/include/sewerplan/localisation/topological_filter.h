// SPDX-License-Identifier: MIT
// TopologicalFilter: where on the sewer network the robot is, as a Bayes filter over places.
//
// A robot in a sewer knows its place only by counting wheel turns (odometry that drifts with the
// distance driven) and by the manholes it stops in, each seen as a signature relative to the pipe
// it came from (core/manhole_signature.h). The map it was given is itself wrong: pipe lengths off
// by up to about 20 %, junctions it lacks. The filter holds a small set of weighted hypotheses
// about the robot's place: in a pipe (which pipe, which end it faces, how far from the end it
// entered by, with the variance of that distance), at a mapped manhole's mouth, at a manhole the
// map lacks (an unmapped junction in a pipe), or in a manhole at the start. Each hypothesis may
// also carry what it had to assume about the map or the sensing: an unmapped junction in pipe P
// at d m, a manhole driven through without being seen, a detection that was no manhole.
//
// Updates follow the robot's own actions and what it sensed (docs/localisation.md):
//   reset(pose)                  a known start;
//   enter(slot)                  out of the start manhole into a slot's pipe;
//   drive(odometry, dir, sigma)  a drive, its odometry and the odometry's standard deviation;
//   arrive(signature)            the drive ended at a detected manhole (signature if observed):
//                                every hypothesis is scored at the mapped mouths ahead (the next
//                                one, or the one after a missed manhole), at an unmapped junction
//                                where it is, and as a false detection; each by the odometry's
//                                distance to the mouth and by compare()'s log-likelihood;
//   turn(relative_deg) / pass()  the robot left a manhole through a mouth;
//   no_manhole_within(d)         the last d m were driven without detecting a manhole;
//   not_at_manhole()             the robot refused a turn: it stopped at no manhole.
// An update touches only the hypotheses and the pipes and manholes near them: its cost does not
// depend on the network's size (bench/localisation/topological_filter_bench.cc).
//
// The model is a Bayes filter over the places of a graph (topological localisation, as in Kuipers
// and Byun 1991, "A robot exploration and mapping strategy based on a semantic hierarchy of spatial
// representations"), kept as a short list of hypotheses, each with a Gaussian for the distance
// along its pipe. It is deterministic: no sampling.
//
//   auto filter = TopologicalFilter::create(map);
//   filter->reset({.position = domain::AtSlot{m1, SlotIndex{0}}});
//   filter->pass(m1, SlotIndex{0}, SlotIndex{1});
//   filter->drive(report.odometry_m, DriveDirection::kForward, 0.03 * report.odometry_m);
//   filter->arrive(report.observation);
//   Verification v = *filter->verify_arrival(m2, SlotIndex{0}, report.observation);
//   if (!v.matches()) ... v.kind, v.reason
//
// Thread safety: a filter is a plain value; one thread updates it at a time. The map must outlive
// it and is only read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sewerplan/core/manhole_signature.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/robot_state.h"

namespace sewerplan::localisation {

// The priors and limits of the filter. Every rate is a number the campaign's error profile can
// set (docs/localisation.md explains each).
struct LocalisationOptions {
  // Standard deviation of a map pipe's length, as a fraction of it: 0.10 puts lengths off by 20 %
  // at two standard deviations.
  double length_sd_fraction = 0.10;
  // Probability that the robot drives through a mapped manhole without detecting it.
  double miss_probability = 0.05;
  // Manholes the map lacks, per metre of pipe (an unmapped junction ahead of a mapped mouth):
  // one per kilometre, about 4 % of the manholes where they are 40 m apart (the realistic error
  // profile of issue 29 has 3 % of junctions missing from the map).
  double unmapped_junctions_per_m = 0.001;
  // A manhole the map lacks is a shaft of its own between two pipe pieces: it lies at least this
  // far from either end of the pipe it splits. A sighting nearer an end is that end's manhole
  // (seen with a mouth the map lacks, say), never a junction beside it: one 0.4 m from a mapped
  // manhole was closed as a blockage there and cut the robot's way out.
  double min_junction_spacing_m = 1.0;
  // ... and is a manhole: its shaft at least this wide (DIN EN 476's smallest man-entry shaft). A
  // narrower one is the pipe widening, a false detection: on a 1,000-manhole meshed network a
  // detection with a 0.28 m shaft, in a pipe the robot had driven through, read as a junction and
  // the pipe was closed behind it.
  double min_junction_shaft_m = 0.8;
  // Detections where there is no manhole, per metre driven.
  double false_detections_per_m = 0.0002;
  // Odometry with heavy tails: this share of drives is off by odometry_outlier_scale times the
  // standard deviation given with the drive (a wet pipe slips twice as much, a wet and steep one
  // four times: docs/simulation.md). Without it one drive off by 4 sigma made an arrival at the
  // right manhole read as a missed manhole and a junction the map lacks.
  double odometry_outlier_share = 0.1;
  double odometry_outlier_scale = 4;
  // Consecutive missed manholes an arrival may explain (0: none).
  int max_misses = 2;
  // A manhole can be driven through unseen, or a false detection or an unmapped junction passed,
  // only straight on: a mouth within this many degrees of straight ahead (a manhole's mouth up
  // to direction_off_max_deg beyond, at the share of the map's slots that are off that much).
  double straight_through_deg = 30;
  // Hypotheses below this fraction of the most likely are dropped, and at most max_hypotheses
  // kept.
  double prune_ratio = 1e-6;
  std::size_t max_hypotheses = 64;
  // Hypotheses in the same pipe, facing the same way, closer than this are merged.
  double merge_distance_m = 1.0;
  // The belief is ambiguous when two or more places each have at least this probability.
  double ambiguity_probability = 0.05;
  // verify_arrival() says "matches" only when the expected mouth has at least this probability.
  double verify_probability = 0.9;
  // A mouth seen at a mapped manhole where the map has none is remembered (KnownMouth) when that
  // manhole is the most likely place with at least this probability. A majority, not
  // verify_probability: the arrival that sees a lateral the map lacks is the one the filter is
  // least sure of (meshed 1,000 manholes, seed 1: M998 at p=0.86, and its next arrival taken for a
  // junction). A mouth remembered wrongly costs little: it is weighed by its sightings, and
  // forgotten when confident arrivals do not see it.
  double remember_mouth_probability = 0.5;
  // The measurement noise of the signatures (what compare() scores with), and the share of the
  // map's mouths that are wrong beyond it: a manhole seen with one mouth unlike the map's is still
  // that manhole. (On AIS, 200 runs of the realistic world, a mapped manhole 0.2 m ahead, with a
  // lateral the map has at 225 degrees seen at 262 and narrower, read as no manhole at all; the
  // robot drove on 0 m and arrived there again 22 times.) And the share of mapped manholes with a
  // mouth the map lacks (unmapped_mouth_share): such a mouth scores as that share of one nothing
  // predicts, on the scale of a manhole the map lacks (docs/localisation.md, "Explaining an
  // arrival"). A third of the realistic profile's 3 %: at 3 % a junction the map lacks 3 standard
  // deviations short of the mapped manhole ahead read as that manhole (meshed 1,000 manholes,
  // seed 1, run 24). Before (kSlotCountLogPenalty, e^-12), a mapped manhole with a lateral the map
  // lacks, reached by a pipe a tenth shorter than mapped, read as a junction (seed 1, runs 11, 21).
  SignatureNoise noise{.mouth_off_share = 0.1, .unmapped_mouth_share = 0.01};
  // A turn's angle as the robot's joints measure it (hal::JobReport::turn_measured_deg): its
  // standard deviation, and the map's direction error model that the angle is weighed with (this
  // share of the map's slots leave their manhole up to direction_off_max_deg off their mapped
  // azimuth: the realistic error profile's 10 % and 20 degrees, docs/simulation.md).
  double turn_sd_deg = 1.0;
  double direction_off_share = 0.10;
  double direction_off_max_deg = 20;
};

// Every option finite and in range; the error names the option.
Result<void> check_options(const LocalisationOptions& options);

enum class DriveDirection : std::uint8_t { kForward, kBackward };

// A place on the map as the planner names it (domain::RobotPosition), plus the end of the pipe the
// robot faces (the end a forward drive approaches) when it is in a pipe.
struct Pose {
  domain::RobotPosition position;
  std::optional<std::uint8_t> heading_end;  // 0 or 1, in a pipe only
  // The robot is at a manhole the map lacks, at position (an InPipe).
  bool at_unmapped_junction = false;
  friend bool operator==(const Pose&, const Pose&) = default;
};

// "in pipe P3 at 12.40 m facing M4", "at M6 slot 3 (P5)", "at an unmapped junction in P3 at 12.40
// m"
std::string describe(const Pose& pose, const SewerMap& map);

// What a hypothesis had to assume to explain what the robot sensed.
struct Assumption {
  enum class Kind : std::uint8_t {
    kUnmappedJunction,  // a manhole the map lacks in `pipe` at `offset_m` (from its ends[0])
    kMissedManhole,     // the robot drove through `manhole` without detecting it
    kFalseDetection,    // a detection in `pipe` at `offset_m` where there was no manhole
  };
  Kind kind = Kind::kUnmappedJunction;
  std::optional<PipeId> pipe;
  std::optional<ManholeId> manhole;
  double offset_m = 0;
  friend bool operator==(const Assumption&, const Assumption&) = default;
};

// "unmapped-junction", "missed-manhole", "false-detection".
std::string_view to_string(Assumption::Kind kind);

// What the filter learnt of the map's pipes in this mission: the manholes the map lacks that it
// became confident of (the most likely place at an arrival, with verify_probability, and clear of
// the pipe's ends by three standard deviations of its mapped length: nearer one, it is not told
// apart from that end's manhole with a lateral the map lacks), and the stretches it drove without
// detecting one (each leg to an arrival it was confident of). Distances count from a
// pipe end (`from_end`, 0 or 1) as the robot drove them; a later arrival in the pipe is weighed
// by the distance to the known junctions there, and the prior of a junction not yet known is
// cut to the miss rate in a stretch already driven (docs/localisation.md, "What the filter
// remembers"). It outlives reset(): a restart in the same mission keeps it.
struct KnownJunction {
  PipeId pipe{0};
  std::uint8_t from_end = 0;
  double distance_m = 0;  // from the end from_end
  double var_m2 = 0;      // variance of distance_m
  int sightings = 1;      // confident arrivals merged into it
  friend bool operator==(const KnownJunction&, const KnownJunction&) = default;
};

struct DrivenStretch {
  PipeId pipe{0};
  std::uint8_t from_end = 0;
  double from_m = 0;  // from the end from_end
  double to_m = 0;
  friend bool operator==(const DrivenStretch&, const DrivenStretch&) = default;
};

// A mouth seen at a mapped manhole where the map has none (a lateral the map lacks), at an
// arrival the filter was confident of: a later arrival there expects it too, so that the manhole
// is not taken for a junction the map lacks because the same lateral is missing from the map
// again (meshed 1,000 manholes, realistic world: 8 of 11 wrong arrivals over 120 runs). Held in the
// map's frame: the arrival slot's direction plus the direction seen, the arrival mouth's invert
// plus the step seen.
struct KnownMouth {
  ManholeId manhole{0};
  double azimuth_deg = 0;  // [0, 360), counter-clockwise as the map's slots
  double invert_z_m = 0;
  double diameter_m = 0;
  int sightings = 1;  // confident arrivals that saw it
  friend bool operator==(const KnownMouth&, const KnownMouth&) = default;
};

struct JunctionMemory {
  std::vector<KnownJunction> junctions;  // by pipe, then distance
  std::vector<DrivenStretch> driven;     // by pipe, in the order driven
  std::vector<KnownMouth> mouths;        // by manhole, then azimuth
  bool empty() const { return junctions.empty() && driven.empty() && mouths.empty(); }
  friend bool operator==(const JunctionMemory&, const JunctionMemory&) = default;
};

// Whether `memory` fits `map`: known pipes, ends 0 or 1, distances finite and within the pipe's
// mapped length, a positive finite variance, at least one sighting, and stretches with from_m
// below to_m; mouths at known manholes, with a direction in [0, 360), a finite invert, a size > 0
// and at least one sighting. The error names the junction, stretch or mouth and what is wrong.
Result<void> check_memory(const JunctionMemory& memory, const SewerMap& map);

struct Hypothesis {
  Pose pose;
  double probability = 0;
  // Standard deviation of the place along its pipe (0 at a mouth or in a manhole).
  double sd_m = 0;
  // The latest assumptions first; at most kMaxAssumptions.
  std::vector<Assumption> assumptions;
  friend bool operator==(const Hypothesis&, const Hypothesis&) = default;
};

inline constexpr std::size_t kMaxAssumptions = 8;

struct Estimate {
  // Empty when the filter is lost (every hypothesis ruled out: reset() it).
  std::vector<Hypothesis> hypotheses;  // most likely first
  bool ambiguous = false;              // two or more hypotheses above ambiguity_probability
  bool lost() const { return hypotheses.empty(); }
  // The most likely hypothesis; precondition: !lost().
  const Hypothesis& best() const { return hypotheses.front(); }
};

// The outcome of checking an arrival against the manhole the plan expected.
struct Verification {
  enum class Kind : std::uint8_t {
    kMatches,           // the expected manhole, through the expected slot
    kWrongManhole,      // another mapped manhole (or mouth)
    kUnmappedJunction,  // a manhole the map lacks
    kMissedManhole,     // a later manhole: the robot drove through one unseen
    kFalseDetection,    // no manhole at all
    kSignatureDiffers,  // the expected manhole by the odometry, but it looks unlike its map
  };
  Kind kind = Kind::kMatches;
  bool matches() const { return kind == Kind::kMatches; }
  double probability = 0;        // of the expected mouth
  std::string reason;            // empty when it matches
  std::optional<Pose> believed;  // the most likely place, when the robot is not lost
};

// "matches", "wrong-manhole", "unmapped-junction", "missed-manhole", "false-detection",
// "signature-differs".
std::string_view to_string(Verification::Kind kind);

// One passage through a manhole on the way to a distinguishing manhole.
struct Passage {
  ManholeId manhole{0};
  SlotIndex from{0};
  SlotIndex to{0};
  friend bool operator==(const Passage&, const Passage&) = default;
};

// A manhole the robot can drive to that tells the likely hypotheses apart: under the most likely
// hypothesis the route reaches `manhole` through `arrival`; under each other likely hypothesis the
// same drives and turns reach a manhole whose signature differs (or no manhole at all).
struct DistinguishingManhole {
  ManholeId manhole{0};
  SlotIndex arrival{0};
  std::vector<Passage> route;  // under the most likely hypothesis, from its next mouth
  double distance_m = 0;       // driven from the robot's most likely place
  std::size_t separated = 0;   // other likely hypotheses it tells apart from the most likely
  friend bool operator==(const DistinguishingManhole&, const DistinguishingManhole&) = default;
};

class TopologicalFilter {
 public:
  // A filter on `map` (which must outlive it), lost until reset(). Error: an option out of range.
  static Result<TopologicalFilter> create(const SewerMap& map, LocalisationOptions options = {});

  // The robot is at `pose`, certainly. Error: an unknown manhole, pipe or slot, an offset outside
  // the pipe, a pose in a pipe without heading_end. Runtime: O(1).
  Result<void> reset(const Pose& pose);

  // Out of the start manhole (reset() to an InManhole) into the pipe of `slot`. Error: not in a
  // manhole, no such slot. Runtime: O(hypotheses).
  Result<void> enter(SlotIndex slot);

  // The robot drove `odometry_m` (>= 0) with a standard deviation of `sigma_m` (>= 0; the
  // sensing model's drift, proportional to the distance). Forward: away from the mouth it
  // entered by. At a manhole, back into the pipe it arrived by (backward after a forward
  // arrival, forward after a backward one), or on the way it arrived, as a robot does that takes
  // the manhole for a false detection: a hypothesis in the pipe drives on, and one at a mouth or
  // at a junction facing it is held there by the pipe's end (its next arrival is there again, at
  // the odometry's likelihood of having driven nothing). Error: a negative or non-finite number,
  // in the start manhole, lost. Runtime: O(hypotheses).
  Result<void> drive(double odometry_m, DriveDirection direction, double sigma_m);

  // The last drive ended at a detected manhole, seen as `observation` (nullopt: detected, but
  // its signature not observed). Error: a signature check_signature() refuses, not after a drive,
  // lost. Runtime: O(hypotheses * (max_misses + 1) * slots log slots).
  Result<void> arrive(const std::optional<ManholeSignature>& observation);

  // The robot left the manhole it arrived at through the mouth `relative_deg` counter-clockwise
  // from its arrival mouth (its own view, as in a signature). Hypotheses at a mouth take the slot
  // nearest that direction (none within noise.max_direction_deg: ruled out); at an unmapped
  // junction or a false detection only straight on continues. With `measured_deg`, the angle the
  // robot's joints measured for the turn (same convention), each hypothesis takes the slot
  // nearest it and is weighed by how well it fits the angle its map has between the two mouths
  // (turn_sd_deg, and the map's direction error model): mouths too close for a sighting to tell
  // apart are told apart by the turn. Error: not at a manhole, a direction outside [0, 360),
  // lost. Runtime: O(hypotheses * slots).
  Result<void> turn(double relative_deg, std::optional<double> measured_deg = std::nullopt);

  // As turn(), from the plan's passage: hypotheses at `manhole`'s slot `from` take slot `to`,
  // the others the direction of `to` relative to `from` (the measured angle when given). Error: an
  // unknown manhole or slot, from equal to to, not at a manhole, a measured angle outside [0,
  // 360).
  Result<void> pass(ManholeId manhole, SlotIndex from, SlotIndex to,
                    std::optional<double> measured_deg = std::nullopt);

  // The robot drove its last `distance_m` (> 0) without detecting a manhole: hypotheses that
  // would have passed a mouth there now carry a missed manhole, or stay before their mouth.
  // Error: not in a pipe, a negative or non-finite distance, lost.
  Result<void> no_manhole_within(double distance_m);

  // The robot refused a job that needs it at a manhole (a turn through one): it is at none. The
  // hypotheses in a pipe stay (the detection it stopped at was a false one), and those at a
  // junction the map lacks become false detections at that place; those at a mapped mouth are
  // ruled out (none left: lost). Error: not at a manhole, lost. Runtime: O(hypotheses).
  Result<void> not_at_manhole();

  // The belief. Runtime: O(hypotheses).
  Estimate estimate() const;

  // Checks the arrival that arrive() just scored against the manhole and arrival slot the plan
  // expected. Error: an unknown manhole or slot, a bad signature, not at a manhole.
  Result<Verification> verify_arrival(ManholeId expected, SlotIndex arrival,
                                      const std::optional<ManholeSignature>& observation) const;

  // Manholes that tell the likely hypotheses apart, reached from the robot's place by at most
  // `max_passes` passages under the most likely hypothesis (driving on first, in a pipe); those
  // separating the most first, then the nearest; at most `max_results`. Empty when the belief is
  // not ambiguous. Runtime: O(likely hypotheses * slots^max_passes).
  std::vector<DistinguishingManhole> distinguishing_manholes(std::size_t max_passes = 3,
                                                             std::size_t max_results = 8) const;

  const LocalisationOptions& options() const { return options_; }
  const SewerMap& map() const { return *map_; }

  // What the filter learnt of the pipes in this mission (kept across reset()).
  const JunctionMemory& memory() const { return memory_; }
  // Starts from what an earlier mission remembered (executor::Learnt::junctions): it replaces the
  // memory, kept in the filter's order (by pipe; junctions by distance). Error: check_memory()'s.
  // Runtime: O(n log n) in the memory's size.
  Result<void> recall(JunctionMemory memory);

  // The log-density (per metre) of a manhole the map lacks at `distance_m` (variance `var_m2`)
  // from end `from_end` of `pipe`: near a known junction its Gaussian, else the per-metre prior,
  // cut to the miss rate in a stretch already driven. Runtime: O(what is known of the pipe).
  double junction_log_density(PipeId pipe, std::uint8_t from_end, double distance_m,
                              double var_m2) const;

  // The log-likelihood (compare()'s) of `observed` at the map's manhole `manhole` entered through
  // `arrival`: against the map's signature, and where the memory knows mouths there the map
  // lacks, against the signature with them too, each mouth set weighed by how often it was seen
  // (n sightings: n / (n + 1) that the mouths are there). Runtime: O(slots^2) and a search of the
  // memory's mouths.
  double mapped_log_likelihood(ManholeId manhole, SlotIndex arrival,
                               const ManholeSignature& observed) const;

  // One hypothesis as the filter keeps it (public for the implementation's helpers; use
  // estimate()).
  struct Track {
    enum class Kind : std::uint8_t { kInManhole, kAtMouth, kInPipe, kAtJunction };
    Kind kind = Kind::kInPipe;
    // In a pipe, at a junction, and at a mouth (the pipe it arrived by):
    PipeId pipe{0};
    std::uint8_t heading_end = 1;  // the end the robot faces
    std::uint8_t moving_end = 1;   // the end the last drive went towards
    double travelled_m = 0;        // from the end opposite heading_end
    double odometry_var_m2 = 0;    // variance of travelled_m from the odometry
    // ... and from the map's lengths of the pipes it passed unseen or was placed by (a merge):
    // the odometry's heavy tails widen the first only (LocalisationOptions::odometry_outlier_*).
    double map_var_m2 = 0;
    // Where the place was last known on the map (a mouth, a reset), in the travelled coordinate:
    // the map's distance from here to a mouth is off by length_sd_fraction of it.
    double anchor_m = 0;
    double cleared_m = 0;   // no mouth was detected up to here (travelled coordinate)
    double leg_from_m = 0;  // where the robot last stopped or entered this pipe (travelled)
    // At a mouth or in a manhole:
    ManholeId manhole{0};
    SlotIndex slot{0};
    double log_weight = 0;
    std::vector<Assumption> assumptions;  // latest first
    // How the latest arrival was explained (for verify_arrival).
    std::uint8_t arrival_misses = 0;
    // At a mouth or a junction, driven on into it since the arrival (drive() on the way the robot
    // arrived): the pipe's end holds it there; odometry_var_m2 is then that drive's variance.
    bool held = false;
    double held_m = 0;
  };

 private:
  enum class Mode : std::uint8_t { kLost, kInManhole, kAtManhole, kInPipe };

  TopologicalFilter(const SewerMap& map, LocalisationOptions options)
      : map_(&map), options_(std::move(options)) {}
  Result<void> usable() const;
  void normalise_and_prune();
  // After an arrival the filter is confident of: the junction it is at, the stretch driven, and
  // the mouths seen that the map's manhole lacks.
  void remember_arrival(const std::optional<ManholeSignature>& observation);
  void remember_mouths(ManholeId manhole, SlotIndex arrival, const ManholeSignature& observed);

  const SewerMap* map_;  // never null
  LocalisationOptions options_;
  Mode mode_ = Mode::kLost;
  DriveDirection last_drive_ = DriveDirection::kForward;
  // How the drive that ended at the manhole went: at a manhole, only the other way is a drive
  // (back into the pipe it arrived by).
  DriveDirection arrived_by_ = DriveDirection::kForward;
  std::vector<Track> tracks_;
  std::vector<Track> scratch_;  // reused between updates
  JunctionMemory memory_;
};

}  // namespace sewerplan::localisation
