// SPDX-License-Identifier: MIT
// --profile NAME|FILE: the robot a command builds for (core/robot_profile.h: makro-1.1,
// makro-plus, or a profile's JSON file), for the commands that read one without a mission
// (`motion precompute`, `index build`).
#pragma once

#include <string>

#include "sewerplan/core/result.h"
#include "sewerplan/core/robot_profile.h"

namespace sewerplan::cli {

// load_profile(name), its error kInvalidProfile (exit 1: invalid input, whatever the reason)
// unless the file could not be read (kIo).
Result<RobotProfile> load_profile_option(const std::string& name);

}  // namespace sewerplan::cli
