// SPDX-License-Identifier: MIT
#include "profile_json.h"

#include <array>

#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/text_file.h"

namespace sewerplan::detail {
namespace {

struct NumberField {
  std::string_view key;
  double RobotProfile::*member;
};

constexpr std::array kNumberFields{
    NumberField{"length_m", &RobotProfile::length_m},
    NumberField{"body_width_m", &RobotProfile::body_width_m},
    NumberField{"min_pipe_diameter_m", &RobotProfile::min_pipe_diameter_m},
    NumberField{"max_pipe_diameter_m", &RobotProfile::max_pipe_diameter_m},
    NumberField{"max_step_m", &RobotProfile::max_step_m},
    NumberField{"max_turn_deg", &RobotProfile::max_turn_deg},
    NumberField{"joint_yaw_max_deg", &RobotProfile::joint_yaw_max_deg},
    NumberField{"joint_pitch_max_deg", &RobotProfile::joint_pitch_max_deg},
    NumberField{"speed_mps", &RobotProfile::speed_mps},
    NumberField{"inspection_speed_mps", &RobotProfile::inspection_speed_mps},
    NumberField{"manhole_pass_s", &RobotProfile::manhole_pass_s},
    NumberField{"manoeuvre_speed_mps", &RobotProfile::manoeuvre_speed_mps},
    NumberField{"turn_s_per_deg", &RobotProfile::turn_s_per_deg},
    NumberField{"step_s_per_m", &RobotProfile::step_s_per_m},
    NumberField{"sample_s", &RobotProfile::sample_s},
    NumberField{"battery_wh", &RobotProfile::battery_wh},
    NumberField{"power_w", &RobotProfile::power_w},
};

bool is_known_key(std::string_view key) {
  if (key == "base" || key == "name" || key == "segment_count" || key == "symmetric") return true;
  for (const NumberField& f : kNumberFields) {
    if (f.key == key) return true;
  }
  return false;
}

std::optional<RobotProfile> named_profile(const std::string& name, const std::string& where,
                                          Diagnostics& diagnostics) {
  if (auto p = builtin_profile(name)) return p;
  std::string known;
  for (const std::string& n : builtin_profile_names()) known += (known.empty() ? "" : ", ") + n;
  diagnostics.error(where, "unknown robot profile '" + name + "' (built in: " + known + ")");
  return std::nullopt;
}

}  // namespace

std::optional<RobotProfile> read_profile_value(JsonElement value, const std::string& path,
                                               std::string_view file, Diagnostics& diagnostics) {
  const std::string where = std::string(file) + ":" + path;
  std::string_view name;
  if (value.get_string().get(name) == simdjson::SUCCESS) {
    return named_profile(std::string(name), where, diagnostics);
  }
  JsonFields f(value, path, file, diagnostics);
  if (!value.is_object()) return std::nullopt;
  const std::size_t errors_before = diagnostics.error_count();
  auto base = named_profile(f.string("base", JsonFields::Need::kOptional).value_or("makro-1.1"),
                            f.where("base"), diagnostics);
  if (!base) return std::nullopt;
  RobotProfile p = *base;
  p.name = f.string("name", JsonFields::Need::kOptional).value_or(p.name + "-custom");
  for (const NumberField& field : kNumberFields) {
    if (auto v = f.number(field.key, JsonFields::Need::kOptional)) p.*field.member = *v;
  }
  if (auto v = f.number("segment_count", JsonFields::Need::kOptional)) {
    p.segment_count = static_cast<int>(*v);
  }
  p.symmetric = f.boolean("symmetric", JsonFields::Need::kOptional).value_or(p.symmetric);
  f.warn_unknown(is_known_key);
  if (diagnostics.error_count() > errors_before) return std::nullopt;
  if (Result<void> valid = validate_profile(p); !valid.has_value()) {
    diagnostics.error(where, valid.error().message);
    return std::nullopt;
  }
  return p;
}

nlohmann::json profile_to_json(const RobotProfile& p) {
  nlohmann::json j;
  j["name"] = p.name;
  for (const NumberField& field : kNumberFields) j[std::string(field.key)] = p.*field.member;
  j["segment_count"] = p.segment_count;
  j["symmetric"] = p.symmetric;
  return j;
}

}  // namespace sewerplan::detail

namespace sewerplan {

Result<RobotProfile> read_profile_json(std::string_view text, const std::string& file_name,
                                       Diagnostics& diagnostics) {
  const Diagnostics::Mark before = diagnostics.mark();
  auto doc = JsonDocument::parse(text, file_name, diagnostics);
  if (!doc) return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  auto profile = detail::read_profile_value(doc->root(), "$", file_name, diagnostics);
  if (!profile) return Error{ErrorCode::kInvalidProfile, diagnostics.error_summary(before)};
  return *profile;
}

Result<RobotProfile> load_profile(const std::string& name_or_path) {
  if (auto p = builtin_profile(name_or_path)) return *p;
  Result<std::string> text = read_text_file(name_or_path);
  if (!text.has_value()) {
    std::string known;
    for (const std::string& n : builtin_profile_names()) known += (known.empty() ? "" : ", ") + n;
    return Error{ErrorCode::kInvalidProfile,
                 "'" + name_or_path + "' is neither a built-in profile (" + known +
                     ") nor a readable profile file: " + text.error().message};
  }
  Diagnostics diagnostics;
  return read_profile_json(*text, name_or_path, diagnostics);
}

}  // namespace sewerplan
