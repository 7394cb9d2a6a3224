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

std::ostream& operator<<(std::ostream& os, const RobotError& error) {
  return os << to_string(error.kind) << ": " << error.reason;
}

}  // namespace sewerplan::hal
