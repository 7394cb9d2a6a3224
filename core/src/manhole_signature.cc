// SPDX-License-Identifier: MIT
#include "sewerplan/core/manhole_signature.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "sewerplan/core/map_queries.h"

namespace sewerplan {
namespace {

// Counter-clockwise angle from `from_deg` to `to_deg`, in [0, 360).
double ccw_deg(double from_deg, double to_deg) {
  double a = std::fmod(to_deg - from_deg, 360.0);
  if (a < 0) a += 360.0;
  if (a >= 360.0) a -= 360.0;
  return a;
}

double gaussian_log(double difference, double sigma) {
  const double z = difference / sigma;
  return -0.5 * z * z - std::log(sigma);
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

SignatureMatch compare(const ManholeSignature& expected, const ManholeSignature& observed,
                       const SignatureNoise& noise) {
  SignatureMatch match;
  match.matches = true;
  auto fail = [&](std::string why) {
    if (match.matches) match.reason = std::move(why);
    match.matches = false;
  };
  const std::size_t n = std::min(expected.slots.size(), observed.slots.size());
  if (expected.slots.size() != observed.slots.size()) {
    const double missing = std::abs(static_cast<double>(expected.slots.size()) -
                                    static_cast<double>(observed.slots.size()));
    match.log_likelihood += kSlotCountLogPenalty * missing;
    fail(std::to_string(observed.slots.size()) + " slots seen, " +
         std::to_string(expected.slots.size()) + " expected");
  }
  for (std::size_t i = 1; i < n; ++i) {
    const SlotSighting& want = expected.slots[i];
    const SlotSighting& seen = observed.slots[i];
    const double direction = normalize_deg(seen.relative_deg - want.relative_deg);
    const double step = seen.step_m - want.step_m;
    const double size = seen.diameter_m - want.diameter_m;
    match.log_likelihood += gaussian_log(direction, noise.direction_deg) +
                            gaussian_log(step, noise.step_m) + gaussian_log(size, noise.diameter_m);
    const std::string slot = "slot " + std::to_string(i + 1);
    if (std::abs(direction) > noise.max_direction_deg) {
      fail(slot + " at " + number(seen.relative_deg, 0) + "°, " + number(want.relative_deg, 0) +
           "° expected");
    } else if (std::abs(step) > noise.max_step_m) {
      fail(slot + " with a step of " + number(seen.step_m, 2) + " m, " + number(want.step_m, 2) +
           " m expected");
    } else if (std::abs(size) > noise.max_diameter_m) {
      fail(slot + " of " + number(seen.diameter_m, 2) + " m, " + number(want.diameter_m, 2) +
           " m expected");
    }
  }
  if (n > 0) {
    const double size = observed.slots[0].diameter_m - expected.slots[0].diameter_m;
    match.log_likelihood += gaussian_log(size, noise.diameter_m);
  }
  const double shaft = observed.shaft_diameter_m - expected.shaft_diameter_m;
  match.log_likelihood += gaussian_log(shaft, noise.shaft_m);
  if (std::abs(shaft) > noise.max_shaft_m) {
    fail("a shaft of " + number(observed.shaft_diameter_m, 2) + " m, " +
         number(expected.shaft_diameter_m, 2) + " m expected");
  }
  return match;
}

}  // namespace sewerplan
