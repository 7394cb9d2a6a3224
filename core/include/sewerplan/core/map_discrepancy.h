// SPDX-License-Identifier: MIT
// Discrepancy: one way in which the sewer differs from its map.
//
// Real sewer maps carry pipe lengths off by metres, slot directions off, manholes placed from old
// plans, junctions and laterals the map lacks or has but the world does not, pipes smaller than
// recorded. A Discrepancy names one such difference, on the map's objects (a map pipe, a map
// manhole and slot) or at a place on a map pipe (a junction the map lacks). Two producers use the
// same type: the simulated world (hal/world_errors.h), which seeds them and so knows the truth, and
// the robot's measurements (core/map_measurements.h), which report what it found; a campaign
// scores the second against the first (docs/campaign.md).
//
//   Discrepancy d{.kind = Discrepancy::Kind::kLengthOff, .pipe = p5,
//                 .map_value = 41.2, .value = 44.9};
//   std::cout << describe(d, map);  // "P5: length 44.90 m, the map says 41.20 m"
//
// Thread safety: plain value types and pure functions.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

struct Discrepancy {
  enum class Kind {
    kLengthOff,         // pipe `pipe` is `value` m long, the map says `map_value`
    kDirectionOff,      // slot `slot` of `manhole` leaves at `value`°, the map says `map_value`;
                        // with `or_slot`: that, or `or_slot` is off by as much the other way
    kPositionOff,       // `manhole` lies `value` m from where the map puts it
    kDiameterSmaller,   // pipe `pipe`'s clear size is `value` m, the map says `map_value`
    kUnmappedJunction,  // a manhole in pipe `pipe` at `offset_m` from its ends[0] that the map
                        // lacks (`value`: its slot count)
    kUnmappedLateral,   // `manhole` has a pipe mouth the map lacks, at `value`° (azimuth)
    kMissingLateral,    // slot `slot` of `manhole` is on the map but not in the sewer
  };
  Kind kind = Kind::kLengthOff;
  std::optional<PipeId> pipe;
  std::optional<ManholeId> manhole;
  std::optional<SlotIndex> slot;
  // A direction-off the robot could not pin on one slot: it measured the angle between `slot` and
  // `or_slot` (a turn from one into the other), not which of them is off, as at every manhole of
  // two mouths (a robot without a compass sees only angles between a manhole's mouths). Then
  // `value` - `map_value` is `slot`'s deviation if `slot` is the one off; otherwise `or_slot` is
  // off by its negative. A corrected map does not apply it (which slot to turn is not known).
  std::optional<SlotIndex> or_slot;
  double offset_m = 0;
  double map_value = 0;
  double value = 0;
  double sigma = 0;  // the standard deviation of `value` (0: known exactly, e.g. a seeded one)
  friend bool operator==(const Discrepancy&, const Discrepancy&) = default;
};
// The number of kinds (kMissingLateral is the last).
inline constexpr std::size_t kDiscrepancyKinds =
    static_cast<std::size_t>(Discrepancy::Kind::kMissingLateral) + 1;

// "length-off", "direction-off", "position-off", "diameter-smaller", "unmapped-junction",
// "unmapped-lateral", "missing-lateral"; and back (empty for any other text).
std::string_view to_string(Discrepancy::Kind kind);
std::optional<Discrepancy::Kind> parse_discrepancy_kind(std::string_view name);

// One line with the map's names: "P5: length 44.90 m, the map says 41.20 m".
std::string describe(const Discrepancy& discrepancy, const SewerMap& map);

// Whether two discrepancies report the same difference: the same kind on the same object (for an
// unmapped junction: the same pipe, offsets within `offset_tolerance_m`; for a direction-off,
// the same manhole and a slot in common, `or_slot` counted as one of its slots). Values are not
// compared.
bool same_difference(const Discrepancy& a, const Discrepancy& b, double offset_tolerance_m = 5.0);

}  // namespace sewerplan
