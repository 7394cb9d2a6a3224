// SPDX-License-Identifier: MIT
#include "sewerplan/core/manhole_signature.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "sewerplan/core/map_queries.h"

namespace sewerplan {
namespace {

double gaussian_log(double difference, double sigma) {
  const double z = difference / sigma;
  return -0.5 * z * z - std::log(sigma);
}

// log(exp(fits) + share exp(unknown)): a measurement that fits the map's within the noise, or one
// the map has wrong (SignatureNoise::mouth_off_share). A floor under the Gaussian rather than a
// mixture, so that a mouth that fits scores as it always did (a mixture's 1 - share took a tenth
// off every mapped manhole's likelihood against the alternatives, a junction and a detection of
// nothing, which have no map to be wrong).
double or_map_wrong(double fits, double unknown, double share) {
  if (share <= 0) return fits;
  const double b = std::log(share) + unknown;
  const double hi = std::max(fits, b);
  return hi + std::log1p(std::exp(std::min(fits, b) - hi));
}

std::string number(double value, int digits) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(digits);
  os << value;
  return os.str();
}

// A measured value for a message: "0.25", "nan", "inf".
std::string shown(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  std::ostringstream os;
  os.precision(4);
  os << value;
  return os.str();
}

}  // namespace

std::vector<SlotIndex> signature_slot_order(const SewerMap& map, ManholeId manhole,
                                            SlotIndex arrival) {
  const Manhole& m = map.manhole(manhole);
  const double base = map.slot(manhole, arrival).azimuth_deg;
  std::vector<SlotIndex> order;
  order.reserve(m.slot_count);
  for (std::uint16_t s = 0; s < m.slot_count; ++s) order.push_back(SlotIndex{s});
  // The arrival slot first, then counter-clockwise; equal directions keep the map's order.
  std::stable_sort(order.begin(), order.end(), [&](SlotIndex a, SlotIndex b) {
    const double da = a == arrival ? -1.0 : ccw_deg(base, map.slot(manhole, a).azimuth_deg);
    const double db = b == arrival ? -1.0 : ccw_deg(base, map.slot(manhole, b).azimuth_deg);
    return da < db;
  });
  return order;
}

ManholeSignature expected_signature(const SewerMap& map, ManholeId manhole, SlotIndex arrival) {
  const Manhole& m = map.manhole(manhole);
  const Slot& in = map.slot(manhole, arrival);
  ManholeSignature signature;
  signature.shaft_diameter_m = m.diameter_m;
  for (SlotIndex s : signature_slot_order(map, manhole, arrival)) {
    const Slot& slot = map.slot(manhole, s);
    signature.slots.push_back(
        {.relative_deg = s == arrival ? 0.0 : ccw_deg(in.azimuth_deg, slot.azimuth_deg),
         .step_m = slot.invert_z_m - in.invert_z_m,
         .diameter_m = map.pipe(slot.pipe).diameter_m});
  }
  return signature;
}

Result<void> check_signature(const ManholeSignature& signature) {
  if (signature.slots.empty())
    return Error{ErrorCode::kInvalidArgument, "a manhole signature needs at least one slot, has 0"};
  if (!std::isfinite(signature.shaft_diameter_m) || signature.shaft_diameter_m <= 0) {
    return Error{ErrorCode::kInvalidArgument,
                 "shaft diameter " + shown(signature.shaft_diameter_m) + " is not > 0"};
  }
  double previous = -1;
  for (std::size_t i = 0; i < signature.slots.size(); ++i) {
    const SlotSighting& s = signature.slots[i];
    const std::string at = "slot " + std::to_string(i + 1) + ": ";
    if (!std::isfinite(s.relative_deg) || s.relative_deg < 0 || s.relative_deg >= 360) {
      return Error{ErrorCode::kInvalidArgument,
                   at + "direction " + shown(s.relative_deg) + " is not in [0, 360)"};
    }
    if (i == 0 && s.relative_deg != 0) {
      return Error{ErrorCode::kInvalidArgument,
                   at + "the arrival slot's direction must be 0, is " + shown(s.relative_deg)};
    }
    if (i > 0 && s.relative_deg < previous) {
      return Error{ErrorCode::kInvalidArgument,
                   at + "directions must be counter-clockwise (increasing), " +
                       shown(s.relative_deg) + " follows " + shown(previous)};
    }
    previous = s.relative_deg;
    if (!std::isfinite(s.step_m))
      return Error{ErrorCode::kInvalidArgument, at + "the step is not a number"};
    if (!std::isfinite(s.diameter_m) || s.diameter_m <= 0) {
      return Error{ErrorCode::kInvalidArgument,
                   at + "diameter " + shown(s.diameter_m) + " is not > 0"};
    }
  }
  return {};
}

namespace {

// Why `seen` is not the mouth `want`, or empty when it is within the noise's limits.
std::string pair_problem(std::size_t seen_index, const SlotSighting& want, const SlotSighting& seen,
                         const SignatureNoise& noise) {
  const std::string slot = "slot " + std::to_string(seen_index + 1);
  if (std::abs(normalize_deg(seen.relative_deg - want.relative_deg)) > noise.max_direction_deg) {
    return slot + " at " + number(seen.relative_deg, 0) + "°, " + number(want.relative_deg, 0) +
           "° expected";
  }
  if (std::abs(seen.step_m - want.step_m) > noise.max_step_m) {
    return slot + " with a step of " + number(seen.step_m, 2) + " m, " + number(want.step_m, 2) +
           " m expected";
  }
  if (std::abs(seen.diameter_m - want.diameter_m) > noise.max_diameter_m) {
    return slot + " of " + number(seen.diameter_m, 2) + " m, " + number(want.diameter_m, 2) +
           " m expected";
  }
  return {};
}

// Two mouths a few degrees apart (two pipes entering side by side; the official ISYBAU sample has
// them 6 degrees apart) are seen in either order counter-clockwise, depending on the noise and on
// how far the map's directions are off: pairing them in the map's order scored the right manhole
// as two missing mouths and two the map lacks, and the robot read its arrival as a false
// detection. So a pairing may swap neighbours: `want_a` with `seen_b` and `want_b` with `seen_a`.
double swapped_log(const SlotSighting& want_a, const SlotSighting& want_b,
                   const SlotSighting& seen_a, const SlotSighting& seen_b,
                   const SignatureNoise& noise) {
  return mouth_log_likelihood(want_a, seen_b, noise) + mouth_log_likelihood(want_b, seen_a, noise);
}

// Pairs the mouths of two signatures with different slot counts: both lists run
// counter-clockwise from the arrival mouth (paired with each other), so the pairing keeps their
// order but for swapped neighbours (swapped_log), and each mouth left unpaired (one the map lacks,
// or one the world lacks) costs unexpected_mouth_log_likelihood() or kSlotCountLogPenalty. The
// pairing of most likelihood (an alignment, O(expected x observed)). Adds its log-likelihood to
// `match` and names the first difference.
void compare_unequal(const ManholeSignature& expected, const ManholeSignature& observed,
                     const SignatureNoise& noise, SignatureMatch& match) {
  const std::size_t e = expected.slots.size();
  const std::size_t o = observed.slots.size();
  // best[i][j]: the pairing of expected mouths 1..i with observed mouths 1..j.
  const std::size_t width = o;
  std::vector<double> best(e * o, 0.0);
  enum Step : unsigned char { kPair, kSwap, kExpectedAlone, kObservedAlone };
  std::vector<Step> how(e * o, kPair);
  const double unseen = kSlotCountLogPenalty;
  const double unexpected = unexpected_mouth_log_likelihood(noise);
  for (std::size_t i = 0; i < e; ++i) {
    for (std::size_t j = 0; j < o; ++j) {
      if (i == 0 && j == 0) continue;
      double value = -std::numeric_limits<double>::infinity();
      Step step = kPair;
      if (i > 0 && j > 0) {
        value = best[(i - 1) * width + j - 1] +
                mouth_log_likelihood(expected.slots[i], observed.slots[j], noise);
      }
      if (i > 1 && j > 1) {
        const double swap = best[(i - 2) * width + j - 2] +
                            swapped_log(expected.slots[i - 1], expected.slots[i],
                                        observed.slots[j - 1], observed.slots[j], noise);
        if (swap > value) {
          value = swap;
          step = kSwap;
        }
      }
      if (i > 0 && best[(i - 1) * width + j] + unseen > value) {
        value = best[(i - 1) * width + j] + unseen;
        step = kExpectedAlone;
      }
      if (j > 0 && best[i * width + j - 1] + unexpected > value) {
        value = best[i * width + j - 1] + unexpected;
        step = kObservedAlone;
      }
      best[i * width + j] = value;
      how[i * width + j] = step;
    }
  }
  match.log_likelihood += best[e * o - 1];
  // Back from the end; the reason is the first difference counter-clockwise.
  std::string reason;
  for (std::size_t i = e - 1, j = o - 1; i > 0 || j > 0;) {
    switch (how[i * width + j]) {
      case kPair: {
        std::string problem = pair_problem(j, expected.slots[i], observed.slots[j], noise);
        if (!problem.empty()) reason = std::move(problem);
        --i;
        --j;
        break;
      }
      case kSwap: {
        std::string problem = pair_problem(j, expected.slots[i - 1], observed.slots[j], noise);
        if (problem.empty())
          problem = pair_problem(j - 1, expected.slots[i], observed.slots[j - 1], noise);
        if (!problem.empty()) reason = std::move(problem);
        i -= 2;
        j -= 2;
        break;
      }
      case kExpectedAlone:
        reason = "no slot seen at " + number(expected.slots[i].relative_deg, 0) + "°";
        match.unseen.insert(match.unseen.begin(), i);
        --i;
        break;
      case kObservedAlone:
        reason = "slot " + std::to_string(j + 1) + " at " +
                 number(observed.slots[j].relative_deg, 0) + "° is not on the map";
        match.unexpected.insert(match.unexpected.begin(), j);
        --j;
        break;
    }
  }
  match.matches = false;
  match.reason = std::to_string(o) + " slots seen, " + std::to_string(e) + " expected" +
                 (reason.empty() ? "" : ": " + reason);
}

}  // namespace

double mouth_log_likelihood(const SlotSighting& want, const SlotSighting& seen,
                            const SignatureNoise& noise) {
  return or_map_wrong(
      gaussian_log(normalize_deg(seen.relative_deg - want.relative_deg), noise.direction_deg) +
          gaussian_log(seen.step_m - want.step_m, noise.step_m) +
          gaussian_log(seen.diameter_m - want.diameter_m, noise.diameter_m),
      unknown_mouth_log_likelihood(), noise.mouth_off_share);
}

double unexpected_mouth_log_likelihood(const SignatureNoise& noise) {
  if (noise.unmapped_mouth_share <= 0) return kSlotCountLogPenalty;
  return std::log(noise.unmapped_mouth_share) + unknown_mouth_log_likelihood();
}

SignatureMatch compare(const ManholeSignature& expected, const ManholeSignature& observed,
                       const SignatureNoise& noise) {
  SignatureMatch match;
  match.matches = true;
  if (expected.slots.empty() || observed.slots.empty()) {
    match.matches = false;
    match.log_likelihood = -std::numeric_limits<double>::infinity();
    match.reason = std::to_string(observed.slots.size()) + " slots seen, " +
                   std::to_string(expected.slots.size()) + " expected";
    return match;
  }
  if (expected.slots.size() != observed.slots.size()) {
    compare_unequal(expected, observed, noise, match);
  } else {
    // In order, but for neighbours seen swapped (swapped_log).
    const std::size_t n = expected.slots.size();
    std::vector<std::size_t> seen_as(n);
    for (std::size_t i = 0; i < n; ++i) seen_as[i] = i;
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const SlotSighting& a = expected.slots[i];
      const SlotSighting& b = expected.slots[i + 1];
      if (swapped_log(a, b, observed.slots[i], observed.slots[i + 1], noise) >
          mouth_log_likelihood(a, observed.slots[i], noise) +
              mouth_log_likelihood(b, observed.slots[i + 1], noise)) {
        std::swap(seen_as[i], seen_as[i + 1]);
        ++i;
      }
    }
    for (std::size_t i = 1; i < n; ++i) {
      const SlotSighting& seen = observed.slots[seen_as[i]];
      match.log_likelihood += mouth_log_likelihood(expected.slots[i], seen, noise);
      std::string problem = pair_problem(seen_as[i], expected.slots[i], seen, noise);
      if (match.matches && !problem.empty()) {
        match.matches = false;
        match.reason = std::move(problem);
      }
    }
  }
  match.log_likelihood += or_map_wrong(
      gaussian_log(observed.slots[0].diameter_m - expected.slots[0].diameter_m, noise.diameter_m),
      unknown_log_likelihood(kUnknownDiameterRangeM), noise.mouth_off_share);
  const double shaft = observed.shaft_diameter_m - expected.shaft_diameter_m;
  match.log_likelihood += gaussian_log(shaft, noise.shaft_m);
  if (std::abs(shaft) > noise.max_shaft_m && match.matches) {
    match.matches = false;
    match.reason = "a shaft of " + number(observed.shaft_diameter_m, 2) + " m, " +
                   number(expected.shaft_diameter_m, 2) + " m expected";
  }
  return match;
}

}  // namespace sewerplan
