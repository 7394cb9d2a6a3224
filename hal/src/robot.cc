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
