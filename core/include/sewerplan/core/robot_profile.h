// SPDX-License-Identifier: MIT
// RobotProfile: what a robot can do and what its actions cost, as the planner needs to know it.
//
// MAKRO (Adria, Streich and Hertzberg 2004, sections 1 and 2) is a 2 m, six-segment worm that
// drives in pipes of 0.30 to 0.60 m, climbs steps of up to 0.30 m and turns up to 90 degrees inside
// a manhole. It is symmetric: it drives both ways but cannot turn around inside a pipe. Two
// profiles are built in: "makro-1.1" (the prototype: 0.30 m/s, about 2 h of battery) and
// "makro-plus" (0.60 m/s, about 4 h). A mission names one, or gives its own (mission.h), in the
// JSON form documented in docs/formats/mission-json.md.
//
// The limits prune actions in the planner; the times give action costs in seconds. Energy is the
// mission's time at the profile's average power: energy_wh = time_s x power_w / 3600. One average
// power (rather than one for driving and one for standing) keeps energy proportional to time, so
// the battery becomes an exact bound on a plan's cost.
//
//   RobotProfile p = *builtin_profile("makro-plus");
//   double hours = p.battery_wh / p.power_w;  // endurance
//
// Thread safety: Plain values: const access from several threads is safe.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"

namespace sewerplan {

struct RobotProfile {
  std::string name;
  // Body.
  double length_m = 2.0;
  int segment_count = 6;
  double body_width_m = 0.22;  // the largest cross-section dimension of a segment
  bool symmetric = true;       // drives both ways (cannot turn around inside a pipe either way)
  // Limits.
  double min_pipe_diameter_m = 0.30;
  double max_pipe_diameter_m = 0.60;
  double max_step_m = 0.30;  // up or down, between two pipe inverts in a manhole
  double max_turn_deg = 90;  // deviation from straight through a manhole
  // Joints, for motion planning in manholes (docs/motion.md): the largest bend of one joint
  // sideways (yaw) and up or down (pitch). The paper gives no figures; 45 degrees of yaw lets the
  // 0.33 m segments follow a 0.43 m radius, and 70 degrees of pitch lets the two lifted segments
  // reach 0.33 m x sin 70 = 0.31 m, the paper's 0.30 m step.
  double joint_yaw_max_deg = 45;
  double joint_pitch_max_deg = 70;
  // Motion and task times.
  double speed_mps = 0.30;             // driving in a pipe
  double inspection_speed_mps = 0.10;  // driving while scanning a pipe
  double manhole_pass_s = 20;          // passing a manhole straight through
  // The head's speed along a planned manoeuvre in a manhole (docs/motion.md): 3 m (a 1 m manhole
  // and the 2 m body) at 0.15 m/s take the 20 s of manhole_pass_s.
  double manoeuvre_speed_mps = 0.15;
  double turn_s_per_deg = 0.3;  // added per degree of turn in a manhole
  double step_s_per_m = 100;    // added per metre of step, up or down
  double sample_s = 180;        // taking and analysing a water sample
  // Energy.
  double battery_wh = 240;
  double power_w = 120;  // average power while working

  // The energy of `seconds` of work, and the seconds a given energy lasts.
  double energy_wh(double seconds) const { return seconds * power_w / 3600.0; }
  double seconds_for(double energy) const { return energy * 3600.0 / power_w; }

  friend bool operator==(const RobotProfile&, const RobotProfile&) = default;
};

std::ostream& operator<<(std::ostream& os, const RobotProfile& profile);

// The built-in profiles: "makro-1.1" and "makro-plus".
std::optional<RobotProfile> builtin_profile(std::string_view name);
std::vector<std::string> builtin_profile_names();

// Every number finite and in its range (positive speeds and times, min <= max diameter, ...).
// The error names the profile and each field that is wrong.
Result<void> validate_profile(const RobotProfile& profile);

}  // namespace sewerplan

namespace sewerplan {

// Reads a profile from JSON: {"base": "makro-plus", "speed_mps": 0.5, ...}. Every field of
// RobotProfile may be given under its own name; the others come from `base` (default
// "makro-1.1"). Then validate_profile.
Result<RobotProfile> read_profile_json(std::string_view text, const std::string& file_name,
                                       Diagnostics& diagnostics);

// A built-in profile's name, or the path of a JSON profile file.
Result<RobotProfile> load_profile(const std::string& name_or_path);

}  // namespace sewerplan
