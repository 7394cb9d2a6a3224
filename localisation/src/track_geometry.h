// SPDX-License-Identifier: MIT
// One hypothesis moved through the network: its explanations of an arrival or of a drive without
// one, and its turn at a manhole. The filter's updates (topological_filter.cc) apply these to each
// hypothesis; verification.cc reuses them to look ahead.
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "sewerplan/core/manhole_signature.h"
#include "sewerplan/localisation/topological_filter.h"

namespace sewerplan::localisation::detail {

using Track = TopologicalFilter::Track;

// Counter-clockwise angle from `from_deg` to `to_deg`, in [0, 360).
double ccw_deg(double from_deg, double to_deg);

// The mouth ahead of a hypothesis moving in a pipe: the end it moves towards.
struct MouthAhead {
  std::optional<ManholeId> manhole;  // none: a blind end
  SlotIndex slot{0};
  double at_m = 0;  // where the mouth is, in the hypothesis's travelled coordinate
};
MouthAhead mouth_ahead(const SewerMap& map, const Track& track);

// How many degrees the way from `arrival` on through `to` turns from straight on, by the map.
double turn_off_straight_deg(const SewerMap& map, ManholeId manhole, SlotIndex arrival,
                             SlotIndex to);
// The mouths of `manhole` a robot that drives through it unseen from `arrival` may go on into,
// with the log of how likely the map has that mouth where it is: within straight_through_deg of
// straight on, 0; beyond it by e < direction_off_max_deg, log(direction_off_share x (1 - e / max))
// (the map has one of the two mouths off by e or more; its slot directions are off up to that
// much at that share). (AIS, 200 realistic runs, seed 4, run 83: a pipe 14 degrees off straight on
// in the world, 45 on the map, another nearer straight on by the map; the filter knew neither,
// and took the robot's sighting of the next manhole for a false detection.)
std::vector<std::pair<SlotIndex, double>> chain_onward(const SewerMap& map,
                                                       const LocalisationOptions& o,
                                                       ManholeId manhole, SlotIndex arrival);

// The slot of `manhole` nearest `relative_deg` counter-clockwise from `arrival` (never `arrival`),
// if one lies within `tolerance_deg`. Runtime: O(slots).
std::optional<SlotIndex> slot_towards(const SewerMap& map, ManholeId manhole, SlotIndex arrival,
                                      double relative_deg, double tolerance_deg);

// Whether `track`, held at its mouth or junction (Track::held), can have read its held_m: within
// four standard deviations of the held odometry's wide tail (about 1.6 m by default).
bool held_in_reach(const LocalisationOptions& options, const Track& track);

// Appends to `out` every explanation of "the drive ended at a detected manhole" from `track` (in
// a pipe): at the mapped mouth ahead or, through up to max_misses manholes missed straight on, a
// later one; at an unmapped junction where it is; a false detection. Log-weights not normalised.
void explain_arrival(const TopologicalFilter& filter, const Track& track,
                     const std::optional<ManholeSignature>& observation, std::vector<Track>& out);

// Appends to `out` every explanation of "the last `distance_m` passed no detected manhole": still
// before the mouth ahead, or past it (missed) in the pipe straight on.
void explain_no_arrival(const TopologicalFilter& filter, const Track& track, double distance_m,
                        std::vector<Track>& out);

// `track` (at a manhole) after leaving through the mouth `relative_deg` from its arrival mouth, or
// through `passage` when it is at that passage's manhole and slot; nothing when it cannot. With
// `measured_deg` (the turn the joints measured) the mouth is the one nearest it (or the passage's)
// and the weight has the measured angle's likelihood given the map's angle between the mouths
// (straight on, within straight_through_deg, at a manhole the map lacks or at none).
std::optional<Track> turned(const TopologicalFilter& filter, const Track& track,
                            double relative_deg, const std::optional<Passage>& passage,
                            std::optional<double> measured_deg);

}  // namespace sewerplan::localisation::detail
