// SPDX-License-Identifier: MIT
#include "sewerplan/core/robot_profile.h"

#include <cmath>
#include <sstream>

#include "sewerplan/core/limits.h"

namespace sewerplan {
namespace {

RobotProfile makro_1_1() {
  RobotProfile p;
  p.name = "makro-1.1";
  p.speed_mps = 0.30;
  p.inspection_speed_mps = 0.10;
  p.battery_wh = 240;  // about 2 h at 120 W (paper, section 1)
  return p;
}

RobotProfile makro_plus() {
  RobotProfile p = makro_1_1();
  p.name = "makro-plus";
  p.speed_mps = 0.60;  // "up to twice as fast (maximum of 60cm/sec)" (paper, section 7)
  p.inspection_speed_mps = 0.20;
  p.battery_wh = 480;  // "able to give power twice as long"
  return p;
}

}  // namespace

std::optional<RobotProfile> builtin_profile(std::string_view name) {
  if (name == "makro-1.1") return makro_1_1();
  if (name == "makro-plus") return makro_plus();
  return std::nullopt;
}

std::vector<std::string> builtin_profile_names() { return {"makro-1.1", "makro-plus"}; }

std::ostream& operator<<(std::ostream& os, const RobotProfile& p) {
  return os << p.name << " (" << p.speed_mps << " m/s, pipes " << p.min_pipe_diameter_m << "-"
            << p.max_pipe_diameter_m << " m, steps <= " << p.max_step_m
            << " m, turns <= " << p.max_turn_deg << " deg, battery " << p.battery_wh << " Wh)";
}

Result<void> validate_profile(const RobotProfile& p) {
  std::ostringstream problems;
  auto require = [&](bool ok, std::string_view field, double value, std::string_view rule) {
    if (!ok) problems << "\n  " << field << " = " << value << ": must be " << rule;
  };
  auto positive = [&](double v, std::string_view field) {
    require(std::isfinite(v) && v > 0, field, v, "a positive number");
  };
  auto non_negative = [&](double v, std::string_view field) {
    require(std::isfinite(v) && v >= 0, field, v, "zero or more");
  };
  positive(p.length_m, "length_m");
  require(p.segment_count >= 1, "segment_count", p.segment_count, "at least 1");
  positive(p.body_width_m, "body_width_m");
  positive(p.min_pipe_diameter_m, "min_pipe_diameter_m");
  positive(p.max_pipe_diameter_m, "max_pipe_diameter_m");
  require(p.min_pipe_diameter_m <= p.max_pipe_diameter_m, "max_pipe_diameter_m",
          p.max_pipe_diameter_m, "at least min_pipe_diameter_m");
  non_negative(p.max_step_m, "max_step_m");
  require(std::isfinite(p.max_turn_deg) && p.max_turn_deg >= 0 && p.max_turn_deg <= 180,
          "max_turn_deg", p.max_turn_deg, "between 0 and 180");
  require(
      std::isfinite(p.joint_yaw_max_deg) && p.joint_yaw_max_deg > 0 && p.joint_yaw_max_deg <= 90,
      "joint_yaw_max_deg", p.joint_yaw_max_deg, "above 0 and at most 90");
  require(std::isfinite(p.joint_pitch_max_deg) && p.joint_pitch_max_deg >= 0 &&
              p.joint_pitch_max_deg <= 90,
          "joint_pitch_max_deg", p.joint_pitch_max_deg, "between 0 and 90");
  // Speeds, times and the battery within core/limits.h, so that plan costs fit the planner's
  // integer milliseconds.
  auto speed = [&](double v, std::string_view field) {
    require(std::isfinite(v) && v >= kMinSpeed_mps && v <= kMaxSpeed_mps, field, v,
            "from 0.001 to 100 m/s");
  };
  auto duration = [&](double v, std::string_view field) {
    require(std::isfinite(v) && v >= 0 && v <= kMaxDuration_s, field, v, "from 0 to 1e6");
  };
  speed(p.speed_mps, "speed_mps");
  speed(p.inspection_speed_mps, "inspection_speed_mps");
  duration(p.manhole_pass_s, "manhole_pass_s");
  speed(p.manoeuvre_speed_mps, "manoeuvre_speed_mps");
  duration(p.turn_s_per_deg, "turn_s_per_deg");
  duration(p.step_s_per_m, "step_s_per_m");
  duration(p.sample_s, "sample_s");
  require(std::isfinite(p.battery_wh) && p.battery_wh > 0 && p.battery_wh <= kMaxBattery_wh,
          "battery_wh", p.battery_wh, "above 0 and at most 1e6");
  require(std::isfinite(p.power_w) && p.power_w >= kMinPower_w && p.power_w <= kMaxPower_w,
          "power_w", p.power_w, "from 0.001 to 1e6");
  const std::string text = problems.str();
  if (text.empty()) return {};
  return Error{ErrorCode::kInvalidProfile, "robot profile '" + p.name + "':" + text};
}

}  // namespace sewerplan
