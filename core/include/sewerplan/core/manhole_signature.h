// SPDX-License-Identifier: MIT
// ManholeSignature: what a robot sees of a manhole when it arrives in it, and what the map says it
// should see.
//
// A robot in a sewer has no compass and no GPS. What it can tell of a manhole it drives into is
// relative to the pipe it came out of: how many pipe mouths (slots) the shaft has, the direction
// of each relative to the one it came from, the height of each mouth's invert relative to the one
// it came from (the step it would climb), each pipe's clear size, and the shaft's size. That is a
// manhole's signature; the paper's robot "has to find and identify manholes and junctions" by it.
// Slots are listed counter-clockwise (seen from above) from the arrival slot, which is slots[0]
// with a relative direction of 0: the robot's own numbering, not the map's.
//
// expected_signature() is the signature the map predicts for an arrival through a given slot;
// compare() scores an observation against it (a log-likelihood under a noise model, for the
// localisation filter) and says whether it matches and, if not, why (for manhole verification).
//
//   ManholeSignature seen = report.observation->signature;
//   ManholeSignature want = expected_signature(map, m, arrival_slot);
//   SignatureMatch match = compare(want, seen, SignatureNoise{});
//   if (!match.matches) ... match.reason: "3 slots seen, 4 expected: no slot seen at 90°"
//
// Thread safety: plain value types and pure functions.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

// One pipe mouth as the robot sees it from the arrival slot.
struct SlotSighting {
  double relative_deg = 0;  // direction relative to the arrival slot's, counter-clockwise, [0, 360)
  double step_m = 0;        // this mouth's invert minus the arrival mouth's (negative: lower)
  double diameter_m = 0;    // the pipe's clear size
  friend bool operator==(const SlotSighting&, const SlotSighting&) = default;
};

struct ManholeSignature {
  std::vector<SlotSighting> slots;  // counter-clockwise from the arrival slot (slots[0])
  double shaft_diameter_m = 0;      // the shaft's smaller floor dimension
  friend bool operator==(const ManholeSignature&, const ManholeSignature&) = default;
};

// The signature of `manhole` for a robot arriving through `arrival` (one of its slots), from the
// map. Runtime: O(slots log slots).
ManholeSignature expected_signature(const SewerMap& map, ManholeId manhole, SlotIndex arrival);

// The map's slot of `manhole` that each of the expected signature's slots stands for (the same
// order as expected_signature(map, manhole, arrival).slots).
std::vector<SlotIndex> signature_slot_order(const SewerMap& map, ManholeId manhole,
                                            SlotIndex arrival);

// Whether a signature is one a robot could have seen: at least one slot, slots[0] at 0 degrees,
// every number finite, directions in [0, 360) and increasing, sizes > 0. The error names the
// first problem ("slot 3: direction 400 is not in [0, 360)").
Result<void> check_signature(const ManholeSignature& signature);

// The standard deviations of the robot's measurements (the sensing model's, docs/simulation.md).
struct SignatureNoise {
  double direction_deg = 8;
  double step_m = 0.03;
  double diameter_m = 0.03;
  double shaft_m = 0.1;
  // The largest differences still taken as the same manhole: beyond any of them, compare() says
  // it does not match.
  double max_direction_deg = 30;
  double max_step_m = 0.15;
  double max_diameter_m = 0.12;
  double max_shaft_m = 0.5;
  // The share of the map's mouths unlike the sewer's beyond the noise (a direction, a step or a
  // pipe size wrong on the map: issue 29's error profile has a tenth of the slots 20 degrees off
  // and a twentieth of the pipes narrower than mapped). A mouth never scores below this share of
  // one nothing predicts (unknown_mouth_log_likelihood()), so one wrong mouth does not make a
  // manhole a stranger; one that fits scores as without it. In [0, 1); 0 (the default): every
  // difference is noise. It changes compare()'s log_likelihood only, never whether it matches.
  double mouth_off_share = 0;
  // The share of the map's manholes with a mouth the map lacks (a lateral added since the map was
  // drawn; issue 29's error profile has 3 %). When > 0, a mouth seen that the pairing leaves
  // unpaired scores log(unmapped_mouth_share) plus a mouth nothing predicts
  // (unknown_mouth_log_likelihood(): its direction, step and size unknown), the scale on which
  // the localisation scores a manhole the map lacks; 0 (the default): kSlotCountLogPenalty. In
  // [0, 1); like mouth_off_share, it changes compare()'s log_likelihood (and which pairing is the
  // most likely) only, never whether it matches.
  double unmapped_mouth_share = 0;
};

// The ranges of a measurement nothing predicts, on compare()'s scale: a direction anywhere in 360
// degrees, a step within a metre, a pipe of 0.1-1.1 m (docs/localisation.md).
inline constexpr double kUnknownDirectionRangeDeg = 360.0;
inline constexpr double kUnknownStepRangeM = 1.0;
inline constexpr double kUnknownDiameterRangeM = 1.0;
// log(sqrt(2 pi)): compare()'s Gaussian terms leave it out (-z^2/2 - log sigma), so a uniform
// density over a range adds it back to be comparable.
inline constexpr double kLogSqrtTwoPi = 0.91893853320467274178;
// The log-likelihood of a measurement uniform over `range`, on compare()'s scale.
inline double unknown_log_likelihood(double range) { return kLogSqrtTwoPi - std::log(range); }
// ... and of a whole mouth: direction, step and size unknown.
inline double unknown_mouth_log_likelihood() {
  return unknown_log_likelihood(kUnknownDirectionRangeDeg) +
         unknown_log_likelihood(kUnknownStepRangeM) +
         unknown_log_likelihood(kUnknownDiameterRangeM);
}

struct SignatureMatch {
  bool matches = false;
  // The log-likelihood of `observed` given `expected` under the noise (Gaussian per measurement;
  // a mouth seen and left unpaired costs unexpected_mouth_log_likelihood(), one expected and not
  // seen kSlotCountLogPenalty). Comparable across manholes.
  double log_likelihood = 0;
  // The expected mouths (indices into expected.slots) the pairing left without a sighting: with
  // a differing slot count, mouths the world may lack.
  std::vector<std::size_t> unseen;
  // The observed mouths (indices into observed.slots) the pairing left without an expected one:
  // laterals the map may lack.
  std::vector<std::size_t> unexpected;
  std::string
      reason;  // why not, when !matches: "3 slots seen, 4 expected"; "slot 2 at 75°, 20° expected"
};

inline constexpr double kSlotCountLogPenalty = -12.0;
// What compare() charges for a mouth seen that the map lacks: kSlotCountLogPenalty, or by
// SignatureNoise::unmapped_mouth_share. A mouth of the map's not seen costs kSlotCountLogPenalty.
double unexpected_mouth_log_likelihood(const SignatureNoise& noise);

// The log-likelihood of `seen` as the mouth the map lists as `want` (direction, step and size,
// each Gaussian, or the mouth off the map's by SignatureNoise::mouth_off_share), on compare()'s
// scale.
double mouth_log_likelihood(const SlotSighting& want, const SlotSighting& seen,
                            const SignatureNoise& noise);

// How well `observed` fits `expected`. Slots are paired in order; with a differing slot count
// (never a match) the pairing that keeps both orders and is most likely, each mouth left unpaired
// (a lateral the map lacks: unexpected_mouth_log_likelihood(); one the world lacks:
// kSlotCountLogPenalty), and the reason names it ("4 slots seen, 3 expected: slot 2 at 27° is not
// on the map"). Runtime: O(slots) with equal counts, O(expected x observed) otherwise.
SignatureMatch compare(const ManholeSignature& expected, const ManholeSignature& observed,
                       const SignatureNoise& noise = {});

}  // namespace sewerplan
