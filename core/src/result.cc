// SPDX-License-Identifier: MIT
#include "sewerplan/core/result.h"

namespace sewerplan {

std::string_view to_string(ErrorCode code) {
  switch (code) {
    case ErrorCode::kIo:
      return "io";
    case ErrorCode::kParse:
      return "parse";
    case ErrorCode::kInvalidMap:
      return "invalid-map";
    case ErrorCode::kInvalidMission:
      return "invalid-mission";
    case ErrorCode::kInvalidProfile:
      return "invalid-profile";
    case ErrorCode::kInvalidArgument:
      return "invalid-argument";
    case ErrorCode::kUnsupportedFormat:
      return "unsupported-format";
    case ErrorCode::kNoPlan:
      return "no-plan";
    case ErrorCode::kSearchLimit:
      return "search-limit";
    case ErrorCode::kCancelled:
      return "cancelled";
    case ErrorCode::kCanTimeout:
      return "can-timeout";
    case ErrorCode::kBusError:
      return "bus-error";
  }
  return "unknown";
}

std::ostream& operator<<(std::ostream& os, const Error& error) {
  return os << to_string(error.code) << ": " << error.message;
}

}  // namespace sewerplan
