// SPDX-License-Identifier: MIT
// MapMeasurements: what robots measured of a sewer map, and the corrected map that follows.
//
// MAKRO's first jobs include to "measure positions of manholes and pipes ... to improve current
// maps of sewer systems" (Adria, Streich and Hertzberg 2004, section 1). A robot measures a pipe's
// length when it drives it whole from one manhole to the next (the sum of its wheel odometry), and
// a manhole's signature (manhole_signature.h) each time it arrives in one. MapMeasurements keeps
// those raw measurements with their uncertainty and where they came from (robot, mission, date),
// tied to one map by its geometry fingerprint (map_fingerprint.h):
//   - per driven pipe: the inverse-variance mean of its length measurements, their variance and
//     count;
//   - per visited manhole: each observed signature with the map slot it was seen from, each turn
//     through it with the angle the robot's joints measured, and a position estimate (below);
//   - junctions seen inside pipes: a manhole the robot detected where the map has none;
//   - the discrepancies derived from them (map_discrepancy.h), each with its sigma and sources.
//
// merge() pools two missions' measurements of the same map; discrepancies() derives what differs
// from the map (thresholds below); corrected_map() applies what is sound to apply. The executor's
// Measurer (executor/measuring.h) fills one during a mission; the file format is
// docs/formats/measurements-json.md (measurements_json.h).
//
//   Result<MapMeasurements> all = merge(first, second);  // refused if of another map
//   all->discrepancies = discrepancies(*all, map, DiscrepancyThresholds{});
//   Result<CorrectedMap> fixed = corrected_map(map, *all);
//
// Position estimates: a robot has no absolute positioning. A manhole reached by a whole pipe
// drive is estimated at the map position of the manhole it came from plus the pipe's map chord
// (the horizontal line between the two manholes) scaled by measured length / map length; its
// variance is the length variance scaled alike. Each estimate thus carries one pipe's error,
// anchored on the map, and errors do not accumulate along a route. Such an estimate cannot tell a
// displaced manhole from a pipe that is longer than its chord, so position-off is reported only
// when asked (DiscrepancyThresholds::report_positions).
//
// Thread safety: plain value types and pure functions.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/manhole_signature.h"
#include "sewerplan/core/map_discrepancy.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

// Who measured: one mission of one robot.
struct MeasurementSource {
  std::string robot;    // the robot profile's name
  std::string mission;  // the mission's name (its file, when it has none)
  std::string date;     // when, ISO 8601 UTC ("2026-12-06T07:12:00Z")
  friend bool operator==(const MeasurementSource&, const MeasurementSource&) = default;
};

// Indices into MapMeasurements::sources, ascending.
using SourceList = std::vector<std::uint32_t>;

// A quantity measured `count` times, pooled by inverse variance.
struct PooledValue {
  double mean = 0;
  double variance = 0;  // of the mean; > 0
  std::uint32_t count = 0;
  friend bool operator==(const PooledValue&, const PooledValue&) = default;
};

// Pools two independent estimates: the inverse-variance mean, variance 1/(1/va + 1/vb).
PooledValue pool(const PooledValue& a, const PooledValue& b);

struct PipeMeasurement {
  PipeId pipe{0};
  PooledValue length_m;
  SourceList sources;
  friend bool operator==(const PipeMeasurement&, const PipeMeasurement&) = default;
};

// One arrival in a manhole: the signature seen, relative to the map slot the robot came through.
struct SignatureObservation {
  SlotIndex arrival{0};
  ManholeSignature signature;
  std::uint32_t source = 0;
  friend bool operator==(const SignatureObservation&, const SignatureObservation&) = default;
};

// One turn through a manhole: the angle the robot's joints measured between the mouth it came from
// and the one it left by (hal::JobReport::turn_measured_deg), with its standard deviation.
struct TurnMeasurement {
  SlotIndex from{0};
  SlotIndex to{0};
  double relative_deg = 0;  // `to`'s direction counter-clockwise from `from`'s, in [0, 360)
  double sigma_deg = 0;     // > 0
  std::uint32_t source = 0;
  friend bool operator==(const TurnMeasurement&, const TurnMeasurement&) = default;
};

struct PositionEstimate {
  PooledValue x_m;  // the variance is that of each horizontal coordinate
  PooledValue y_m;
  friend bool operator==(const PositionEstimate&, const PositionEstimate&) = default;
};

struct ManholeMeasurement {
  ManholeId manhole{0};
  std::vector<SignatureObservation> observations;
  std::vector<TurnMeasurement> turns;
  std::optional<PositionEstimate> position;
  SourceList sources;
  friend bool operator==(const ManholeMeasurement&, const ManholeMeasurement&) = default;
};

// A manhole detected inside a pipe, where the map has none.
struct JunctionSighting {
  PipeId pipe{0};
  double offset_m = 0;  // from the pipe's ends[0], by odometry
  double sigma_m = 0;
  ManholeSignature signature;
  std::uint32_t source = 0;
  friend bool operator==(const JunctionSighting&, const JunctionSighting&) = default;
};

struct FoundDiscrepancy {
  Discrepancy discrepancy;
  SourceList sources;  // the missions whose measurements show it
  friend bool operator==(const FoundDiscrepancy&, const FoundDiscrepancy&) = default;
};

struct MapMeasurements {
  std::string map_name;
  std::string map_fingerprint;  // map_geometry_fingerprint of the map measured
  std::vector<MeasurementSource> sources;
  std::vector<PipeMeasurement> pipes;        // ascending by pipe, one per pipe
  std::vector<ManholeMeasurement> manholes;  // ascending by manhole, one per manhole
  std::vector<JunctionSighting> junctions;
  std::vector<FoundDiscrepancy> discrepancies;  // derived: discrepancies()
  friend bool operator==(const MapMeasurements&, const MapMeasurements&) = default;
};

// Empty measurements of `map`, by `source`.
MapMeasurements measurements_of(const SewerMap& map, MeasurementSource source);

// Adds one length measurement of `pipe` (pooled with those before) / one arrival / one turn / one
// position estimate, by source `source` (an index into m.sources).
void add_length(MapMeasurements& m, PipeId pipe, double length_m, double variance_m2,
                std::uint32_t source);
void add_observation(MapMeasurements& m, ManholeId manhole, SlotIndex arrival,
                     ManholeSignature signature, std::uint32_t source);
void add_turn(MapMeasurements& m, ManholeId manhole, TurnMeasurement turn);
void add_position(MapMeasurements& m, ManholeId manhole, double x_m, double y_m, double variance_m2,
                  std::uint32_t source);

// The measurements of both: sources appended (b's after a's), lengths and positions pooled by
// inverse variance, observations, turns and sightings joined. The discrepancies are left empty:
// derive them again from the pooled measurements. kInvalidArgument, naming both maps and
// fingerprints, if `a` and `b` were measured on different maps.
Result<MapMeasurements> merge(const MapMeasurements& a, const MapMeasurements& b);

// When a measurement counts as a discrepancy. A value is reported only when it is off by more than
// k_sigma of its standard deviation AND by more than a floor. With the measurement's own sigma
// honest, k_sigma = 3 reports 0.27 % of correct objects: on a network whose map has 10 % of its
// pipe lengths wrong, about 2.4 % of the length reports are then false. The floors keep
// differences too small to matter to a map (a few centimetres on a long, well-measured pipe) out.
struct DiscrepancyThresholds {
  double k_sigma = 3.0;
  double length_floor_m = 0.3;
  double length_floor_fraction = 0.02;  // of the map length
  // A turn's angle measured by the robot's joints is good to about a degree: a slot 4 degrees off
  // (3.5 cm at the mouth of a 1 m manhole, about a turn's clearance) is worth a report. It was 10
  // when sightings (8 degrees each) were all there was.
  double direction_floor_deg = 4;
  double diameter_floor_m = 0.05;
  double position_floor_m = 2.0;
  bool report_positions = false;  // see the header comment
  // The sensing noise (per observation) of the signatures, for directions and diameters; its
  // max_direction_deg also pairs observed with mapped slots (farther apart: not the same mouth).
  SignatureNoise noise;
  // An unmapped lateral is reported when seen in at least this share of the arrivals in its
  // manhole (a mouth seen once in five arrivals is more likely noise than a pipe).
  double lateral_share = 0.5;
  // A mouth seen where the map has none, in an arrival that did not see a mouth the map has
  // within this many degrees of it, is that mouth, off (its direction weighed by the fit), not a
  // lateral the map lacks (map_measurements.cc, pair_leftovers).
  double leftover_direction_deg = 60;
};

// What `measurements` (of `map`) show to differ from it, in a fixed order (kind, then object):
//   length-off       a driven pipe's pooled length, beyond k_sigma and its floors;
//   direction-off    a slot's direction, from every observation and every turn in its manhole
//                    (a weighted least-squares fit of each slot's deviation from the map: the
//                    robot sees directions only relative to the slot it came from, so the common
//                    rotation is taken as the one that leaves the most slots as mapped; when two
//                    rotations leave as many, which slots are off is not observable: when the
//                    one other rotation blames one other slot instead, the report names both,
//                    `slot` and `or_slot`, as at a manhole of two mouths where the turn between
//                    them is 15 degrees off; with more alternatives, none is reported);
//   diameter-smaller a pipe seen smaller than mapped, at either end, beyond k_sigma and the floor;
//   unmapped-lateral a mouth seen in a manhole where the map has none, in lateral_share of
//   arrivals; missing-lateral  a mapped slot of a visited manhole never seen in any arrival;
//   unmapped-junction a manhole sighted inside a pipe (one per 5 m of pipe);
//   position-off     only with report_positions.
// Precondition: measurements of `map` (same fingerprint). Runtime: O(measurements × slots²).
std::vector<FoundDiscrepancy> discrepancies(const MapMeasurements& measurements,
                                            const SewerMap& map,
                                            const DiscrepancyThresholds& thresholds = {});

struct CorrectedMap {
  SewerMap map;
  // Each of measurements.discrepancies, and whether the corrected map carries it: lengths,
  // directions, smaller diameters and positions are applied; unmapped junctions and laterals,
  // and missing laterals, are not (a junction would split a pipe at an offset known only to the
  // odometry's metre and give a manhole with no position or slot geometry of its own; a lateral
  // leads to a pipe nobody has seen the other end of; removing a mapped slot removes its pipe's
  // end): they are listed for the operator.
  std::vector<std::pair<FoundDiscrepancy, bool>> applied;
};

// What a correction assumes of the map's pipe lengths: most are right (a municipal database's
// lengths come from surveyed manhole positions), to within right_sd_fraction of the length (one
// standard deviation); the others are off by up to off_max_fraction, any amount alike. The
// defaults: 90 % right to 1 %, the rest off by up to 20 %.
struct LengthPrior {
  double right_share = 0.9;
  double right_sd_fraction = 0.01;
  double off_max_fraction = 0.20;
};

// The corrected length of a pipe the map has `map_m` long and `measured` measured: the mean of its
// true length given both, under `prior` (a mixture: right, a Gaussian about map_m that the
// measurement's Gaussian updates; or off, where the measurement is all there is). A measurement
// that agrees with the map within its own noise mostly keeps the map's length (one odometry pass
// is off by 3 to 6 %, more than most maps are); one far off it is the pipe's length.
// `measured.variance` 0, or map_m 0: the measurement.
double corrected_length_m(double map_m, const PooledValue& measured, const LengthPrior& prior = {});

// A copy of `map` with every driven pipe's corrected length (corrected_length_m), and each
// discrepancy that can be applied soundly (above); inspection points and findings move with their
// pipe's length (offsets scaled). Built through MapBuilder, so the result is validated like any
// map; an error names what would not validate. kInvalidArgument if the measurements are of
// another map.
Result<CorrectedMap> corrected_map(const SewerMap& map, const MapMeasurements& measurements,
                                   const LengthPrior& prior = {});

}  // namespace sewerplan
