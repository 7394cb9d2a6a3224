// SPDX-License-Identifier: MIT
#include "sewerplan/core/map_discrepancy.h"

#include <cmath>
#include <sstream>

#include "sewerplan/core/enum_names.h"

namespace sewerplan {
namespace {

constexpr detail::EnumNames<Discrepancy::Kind, 7> kNames{{
    {Discrepancy::Kind::kLengthOff, "length-off"},
    {Discrepancy::Kind::kDirectionOff, "direction-off"},
    {Discrepancy::Kind::kPositionOff, "position-off"},
    {Discrepancy::Kind::kDiameterSmaller, "diameter-smaller"},
    {Discrepancy::Kind::kUnmappedJunction, "unmapped-junction"},
    {Discrepancy::Kind::kUnmappedLateral, "unmapped-lateral"},
    {Discrepancy::Kind::kMissingLateral, "missing-lateral"},
}};
static_assert(detail::distinct(kNames));

std::string fixed(double value, int digits) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(digits);
  os << value;
  return os.str();
}

}  // namespace

std::string_view to_string(Discrepancy::Kind kind) { return detail::name_of(kNames, kind); }

std::optional<Discrepancy::Kind> parse_discrepancy_kind(std::string_view name) {
  return detail::value_of(kNames, name);
}

std::string describe(const Discrepancy& d, const SewerMap& map) {
  const std::string pipe = d.pipe ? map.pipe(*d.pipe).name : std::string("?");
  const std::string manhole = d.manhole ? map.manhole(*d.manhole).name : std::string("?");
  const std::string slot = d.slot ? " slot " + std::to_string(to_paper_number(*d.slot)) : "";
  switch (d.kind) {
    case Discrepancy::Kind::kLengthOff:
      return pipe + ": length " + fixed(d.value, 2) + " m, the map says " + fixed(d.map_value, 2) +
             " m";
    case Discrepancy::Kind::kDirectionOff: {
      std::string text = manhole + slot + ": leaves at " + fixed(d.value, 0) + "°, the map says " +
                         fixed(d.map_value, 0) + "°";
      if (d.or_slot && d.manhole && d.or_slot->index() < map.manhole(*d.manhole).slot_count) {
        const double mapped = map.slot(*d.manhole, *d.or_slot).azimuth_deg;
        const double other = std::fmod(mapped - (d.value - d.map_value) + 720.0, 360.0);
        text += "; or slot " + std::to_string(to_paper_number(*d.or_slot)) + " leaves at " +
                fixed(other, 0) + "°, the map says " + fixed(mapped, 0) +
                "° (the angle between the two was measured, not which is off)";
      }
      return text;
    }
    case Discrepancy::Kind::kPositionOff:
      return manhole + ": " + fixed(d.value, 2) + " m from where the map puts it";
    case Discrepancy::Kind::kDiameterSmaller:
      return pipe + ": clear size " + fixed(d.value, 3) + " m, the map says " +
             fixed(d.map_value, 3) + " m";
    case Discrepancy::Kind::kUnmappedJunction:
      return pipe + ": a manhole the map lacks at " + fixed(d.offset_m, 2) + " m, with " +
             fixed(d.value, 0) + " slots";
    case Discrepancy::Kind::kUnmappedLateral:
      return manhole + ": a pipe mouth the map lacks, at " + fixed(d.value, 0) + "°";
    case Discrepancy::Kind::kMissingLateral:
      return manhole + slot + ": on the map, not in the sewer";
  }
  return "?";
}

bool same_difference(const Discrepancy& a, const Discrepancy& b, double offset_tolerance_m) {
  if (a.kind != b.kind) return false;
  switch (a.kind) {
    case Discrepancy::Kind::kLengthOff:
    case Discrepancy::Kind::kDiameterSmaller:
      return a.pipe == b.pipe;
    case Discrepancy::Kind::kUnmappedJunction:
      return a.pipe == b.pipe && std::abs(a.offset_m - b.offset_m) <= offset_tolerance_m;
    case Discrepancy::Kind::kPositionOff:
    case Discrepancy::Kind::kUnmappedLateral:
      return a.manhole == b.manhole;
    case Discrepancy::Kind::kDirectionOff: {
      if (a.manhole != b.manhole) return false;
      const auto has = [](const Discrepancy& d, const std::optional<SlotIndex>& s) {
        return s && (d.slot == s || d.or_slot == s);
      };
      return has(a, b.slot) || has(a, b.or_slot);
    }
    case Discrepancy::Kind::kMissingLateral:
      return a.manhole == b.manhole && a.slot == b.slot;
  }
  return false;
}

}  // namespace sewerplan
