// SPDX-License-Identifier: MIT
#include "sewerplan/hal/robot.h"

#include "sewerplan/core/enum_names.h"

namespace sewerplan::hal {
namespace {

// The names events, logs and the CAN tools print (robot.h); the bus carries codes, not these
// (can/wire_codes.h).
constexpr detail::EnumNames<RobotErrorKind, 3> kErrorKinds{{
    {RobotErrorKind::kBlockage, "blockage"},
    {RobotErrorKind::kDanger, "danger"},
    {RobotErrorKind::kMalfunction, "malfunction"},
}};

constexpr detail::EnumNames<RobotErrorCause, kRobotErrorCauses> kErrorCauses{{
    {RobotErrorCause::kObstacle, "obstacle"},
    {RobotErrorCause::kBlindEnd, "blind-end"},
    {RobotErrorCause::kNoManholeSeen, "no-manhole-seen"},
    {RobotErrorCause::kNoMouth, "no-mouth"},
    {RobotErrorCause::kOtherBlockage, "blockage"},
    {RobotErrorCause::kDangerSpot, "danger-spot"},
    {RobotErrorCause::kDangerousPassage, "dangerous-passage"},
    {RobotErrorCause::kOtherDanger, "danger"},
    {RobotErrorCause::kFault, "fault"},
    {RobotErrorCause::kBatteryEmpty, "battery-empty"},
    {RobotErrorCause::kInvalidJob, "invalid-job"},
    {RobotErrorCause::kNotAtStart, "not-at-start"},
    {RobotErrorCause::kEmergencyStop, "emergency-stop"},
    {RobotErrorCause::kLink, "link"},
    {RobotErrorCause::kOtherMalfunction, "malfunction"},
}};

constexpr detail::EnumNames<BeaconState, 4> kBeaconStates{{
    {BeaconState::kNone, "none"},
    {BeaconState::kConfirmed, "confirmed"},
    {BeaconState::kUnconfirmed, "unconfirmed"},
    {BeaconState::kNotSent, "not-sent"},
}};

// kRobotErrorCauses distinct rows: every cause has its name.
static_assert(detail::distinct(kErrorKinds) && detail::distinct(kErrorCauses) &&
              detail::distinct(kBeaconStates));

// A kOther* cause is named as its kind: an error typed no further reads as the kind alone.
constexpr bool other_causes_named_as_their_kinds() {
  for (const auto& [kind, name] : kErrorKinds) {
    if (detail::name_of(kErrorCauses, other_cause(kind)) != name) return false;
  }
  return true;
}
static_assert(other_causes_named_as_their_kinds());

}  // namespace

std::string_view to_string(RobotErrorKind kind) { return detail::name_of(kErrorKinds, kind); }

std::optional<RobotErrorKind> parse_robot_error_kind(std::string_view name) {
  return detail::value_of(kErrorKinds, name);
}

std::string_view to_string(RobotErrorCause cause) { return detail::name_of(kErrorCauses, cause); }

std::optional<RobotErrorCause> parse_robot_error_cause(std::string_view name) {
  return detail::value_of(kErrorCauses, name);
}

std::string_view to_string(BeaconState state) { return detail::name_of(kBeaconStates, state); }

std::optional<BeaconState> parse_beacon_state(std::string_view name) {
  return detail::value_of(kBeaconStates, name);
}

std::ostream& operator<<(std::ostream& os, const RobotError& error) {
  return os << to_string(error.kind) << ": " << error.reason;
}

}  // namespace sewerplan::hal
