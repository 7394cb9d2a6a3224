// SPDX-License-Identifier: MIT
// Reading a RobotProfile from a JSON value, shared by profile files and missions. Private to core.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/robot_profile.h"

namespace sewerplan::detail {

// `value` is a built-in profile's name or an object with optional "base" and field overrides.
std::optional<RobotProfile> read_profile_value(JsonElement value, const std::string& path,
                                               std::string_view file, Diagnostics& diagnostics);

// The profile as a JSON object with every field.
nlohmann::json profile_to_json(const RobotProfile& profile);

}  // namespace sewerplan::detail
