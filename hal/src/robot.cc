// SPDX-License-Identifier: MIT
#include "sewerplan/hal/robot.h"

namespace sewerplan::hal {

std::string_view to_string(RobotErrorKind kind) {
  switch (kind) {
    case RobotErrorKind::kBlockage:
      return "blockage";
    case RobotErrorKind::kDanger:
      return "danger";
    case RobotErrorKind::kMalfunction:
      return "malfunction";
  }
  return "malfunction";
}

std::string_view to_string(RobotErrorCause cause) {
  switch (cause) {
    case RobotErrorCause::kObstacle:
      return "obstacle";
    case RobotErrorCause::kBlindEnd:
      return "blind-end";
    case RobotErrorCause::kNoManholeSeen:
      return "no-manhole-seen";
    case RobotErrorCause::kOtherBlockage:
      return "blockage";
    case RobotErrorCause::kDangerSpot:
      return "danger-spot";
    case RobotErrorCause::kDangerousPassage:
      return "dangerous-passage";
    case RobotErrorCause::kOtherDanger:
      return "danger";
    case RobotErrorCause::kFault:
      return "fault";
    case RobotErrorCause::kBatteryEmpty:
      return "battery-empty";
    case RobotErrorCause::kInvalidJob:
      return "invalid-job";
    case RobotErrorCause::kEmergencyStop:
      return "emergency-stop";
    case RobotErrorCause::kLink:
      return "link";
    case RobotErrorCause::kOtherMalfunction:
      return "malfunction";
  }
  return "malfunction";
}

std::string_view to_string(BeaconState state) {
  switch (state) {
    case BeaconState::kNone:
      return "none";
    case BeaconState::kConfirmed:
      return "confirmed";
    case BeaconState::kUnconfirmed:
      return "unconfirmed";
    case BeaconState::kNotSent:
      return "not-sent";
  }
  return "none";
}

std::optional<BeaconState> parse_beacon_state(std::string_view name) {
  for (BeaconState s : {BeaconState::kNone, BeaconState::kConfirmed, BeaconState::kUnconfirmed,
                        BeaconState::kNotSent}) {
    if (to_string(s) == name) return s;
  }
  return std::nullopt;
}

std::ostream& operator<<(std::ostream& os, const RobotError& error) {
  return os << to_string(error.kind) << ": " << error.reason;
}

}  // namespace sewerplan::hal
