// SPDX-License-Identifier: MIT
// A true world that is not the map: seeded error models that turn an operator's map into the sewer
// the simulated robot really drives, and the robot's sensing errors.
//
// Municipal sewer maps carry pipe lengths off by metres, slot directions off, manholes placed from
// old plans, junctions and laterals the map lacks or has but the sewer does not, pipes smaller than
// recorded; and a robot counting wheel turns in a wet pipe drifts. A WorldErrorProfile gives one
// rate and one magnitude per error model; make_true_world() draws, from a seed, the true world
// (a SewerMap, built and validated by MapBuilder like every map) and the list of what it did, as
// Discrepancy values in the map's terms (core/map_discrepancy.h), for a scorer to compare the
// robot's reports to. The sensing rates (odometry drift, missed and false manholes) travel in the
// same profile, for the simulated robot (hal/sim_robot.h, SensingModel). The models and their
// shapes are documented in docs/simulation.md, "A world that is not the map".
//
// IDs: every map object that exists in the world keeps its ID and slot index there, so that jobs
// and missions in the map's terms still address the world. What only the world has is appended
// after the map's objects: new manholes ("world-J1", ...), new slots at the end of a manhole's slot
// list, new pipes ("world-P1", ...). A pipe split by an unmapped junction keeps its ID for the part
// from its ends[0] to the junction; the rest is a new pipe. A lateral the world lacks is the map's
// pipe stopping blind short of the manhole (its slot there is gone: only a manhole's last slot is
// ever taken away, so that the others keep their indices).
//
//   Result<WorldErrorProfile> profile = parse_world_errors("realistic,drift=0.05");
//   Result<TrueWorld> truth = make_true_world(map, *profile, seed);
//   hal::SimRobot robot(truth->world, ...);   // the executor still plans on `map`
//   for (const Discrepancy& d : truth->seeded) std::cout << describe(d, map) << '\n';
//
// Thread safety: plain values and pure functions.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/map_discrepancy.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"

namespace sewerplan::hal {

// Every rate and magnitude of the error models. Shares are 0..1; a "max" is the largest error
// drawn (each drawn error is uniform between a quarter of it and all of it, of either sign, so
// that every seeded discrepancy is one a robot could measure).
struct WorldErrorProfile {
  // Map errors (the world differs from the map).
  double length_share = 0;           // of pipes, with a length off
  double length_max_rel = 0;         // ... by up to this share of the map's length
  double length_max_abs_m = 0;       // ... and up to this many metres besides
  double direction_share = 0;        // of slots, leaving the manhole at another azimuth
  double direction_max_deg = 0;      // ... by up to this
  double position_share = 0;         // of manholes, lying elsewhere
  double position_max_m = 0;         // ... by up to this
  double junction_share = 0;         // unmapped junctions: per map manhole, one in a mapped pipe
  double lateral_extra_share = 0;    // of manholes, with a lateral (slot and pipe) the map lacks
  double lateral_missing_share = 0;  // of manholes, lacking their last mapped slot's lateral
  double diameter_share = 0;         // of pipes, smaller than mapped
  double diameter_max_rel = 0;       // ... by up to this share of the mapped size
  // Sensing errors (the robot's, hal/sim_robot.h SensingModel).
  double drift = 0;         // odometry: standard deviation as a share of the distance driven
  double wet_share = 0;     // of pipes, wet (odometry slips twice as much)
  double missed_share = 0;  // of manhole arrivals, not detected
  double false_per_km = 0;  // false manhole detections per km driven
  friend bool operator==(const WorldErrorProfile&, const WorldErrorProfile&) = default;
};

// A named profile: "none" (today's exact world, exact sensing) and "realistic" (issue 29's).
struct NamedWorldErrors {
  std::string_view name;
  WorldErrorProfile profile;
  std::string_view meant_for;
};

inline constexpr std::array<NamedWorldErrors, 2> kWorldErrorProfiles{{
    {"none", WorldErrorProfile{}, "the world is the map, sensing is exact (the default)"},
    {"realistic",
     WorldErrorProfile{.length_share = 0.10,
                       .length_max_rel = 0.20,
                       .length_max_abs_m = 0.5,
                       .direction_share = 0.10,
                       .direction_max_deg = 20,
                       .position_share = 0.10,
                       .position_max_m = 2,
                       .junction_share = 0.03,
                       .lateral_extra_share = 0.03,
                       .lateral_missing_share = 0.03,
                       .diameter_share = 0.05,
                       .diameter_max_rel = 0.2,
                       .drift = 0.03,
                       .wet_share = 0.3,
                       .missed_share = 0.05,
                       .false_per_km = 0.5},
     "a municipal map and a robot in wet pipes (issue 29's acceptance)"},
}};

// Reads "NAME", "key=value,...", or "NAME,key=value,..." (the profile's rates, then the overrides;
// without a name the others are 0). Keys: docs/simulation.md ("lengths", "length_rel",
// "length_abs", "directions", "direction_deg", "positions", "position_m", "junctions",
// "laterals_extra", "laterals_missing", "diameters", "diameter_rel", "drift", "wet", "missed",
// "false_per_km"). Errors (kInvalidArgument) name the bad item: an unknown profile (with the known
// ones), an unknown key (with the known ones), a value that is not a number or out of range.
Result<WorldErrorProfile> parse_world_errors(std::string_view text);
// The canonical "key=value,..." of every rate (parse_world_errors reads it back to the same).
std::string format_world_errors(const WorldErrorProfile& profile);

// A map piece of a pipe that an unmapped junction split in the world: the map's pipe is `pipe`
// from its ends[0] to the junction (at_m, the world's length) and `rest` after it.
struct PipeSplit {
  PipeId pipe{0};
  PipeId rest{0};
  double at_m = 0;
  friend bool operator==(const PipeSplit&, const PipeSplit&) = default;
};

struct TrueWorld {
  SewerMap world;
  std::vector<Discrepancy> seeded;  // in the map's terms, in the order drawn
  std::vector<PipeSplit> splits;
  std::vector<bool> wet;  // per world pipe
  WorldErrorProfile profile;
  std::uint64_t seed = 0;
};

// The true world of `map` under `profile`, drawn from `seed` (the same inputs give the same world,
// bit for bit). With a profile of zero map errors the world equals the map. Errors: an invalid
// profile (kInvalidArgument); the world failing MapBuilder's validation (kInvalidMap: a bug).
Result<TrueWorld> make_true_world(const SewerMap& map, const WorldErrorProfile& profile,
                                  std::uint64_t seed);

// The simulated robot's sensing in `truth` (hal/sim_robot.h): the profile's drift, wet pipes,
// missed and false manholes; observations (with SignatureNoise's defaults) and turns measured to 1
// degree whenever the profile has any error at all, neither for "none" (the simulator as before,
// byte for byte). Its own seed, drawn from the world's.
SensingModel make_sensing(const TrueWorld& truth);

// A place on the map as it lies in the world: an offset along map pipe `pipe` (map metres from its
// ends[0]) is scaled to the world's length, and lands on the split's rest beyond a junction.
struct WorldSpot {
  PipeId pipe{0};
  double offset_m = 0;
};
WorldSpot world_spot(const SewerMap& map, const TrueWorld& truth, PipeId pipe, double offset_m);

// The true length of map pipe `pipe`: its world pipe's, plus the rest's where an unmapped junction
// split it (from the map pipe's ends[0] manhole to its ends[1] one, through the junction).
double world_length_m(const TrueWorld& truth, PipeId pipe);

// A start pose given on the map, in the world (world_spot for a pose in a pipe).
SimPose world_pose(const SewerMap& map, const TrueWorld& truth, const SimPose& pose);

// Faults drawn or read on the map, in the world (world_spot for each offset; a dangerous passage
// through a slot the world lacks is dropped).
FaultScenario world_faults(const SewerMap& map, const TrueWorld& truth, FaultScenario faults);

}  // namespace sewerplan::hal
