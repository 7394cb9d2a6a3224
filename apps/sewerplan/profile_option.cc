// SPDX-License-Identifier: MIT
#include "profile_option.h"

namespace sewerplan::cli {

Result<RobotProfile> load_profile_option(const std::string& name) {
  Result<RobotProfile> profile = load_profile(name);
  if (profile.has_value()) return profile;
  const Error& e = profile.error();
  return Error{e.code == ErrorCode::kIo ? ErrorCode::kIo : ErrorCode::kInvalidProfile, e.message};
}

}  // namespace sewerplan::cli
