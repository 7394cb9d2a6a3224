// SPDX-License-Identifier: MIT
#include "sewerplan/fusion/action_json.h"

#include <type_traits>

#include <nlohmann/json.hpp>

namespace sewerplan::fusion {
namespace {

using json = nlohmann::ordered_json;

// "M5", or null for a blind end.
json end_manhole(const SewerMap& map, PipeId pipe, std::uint8_t end) {
  const PipeEnd& e = map.pipe(pipe).ends[end];
  return e.manhole ? json(map.manhole(*e.manhole).name) : json();
}

void add_drive(json& j, const char* key, const PipeDrive& drive) {
  j[key] = {{"direction", to_string(drive.direction)},
            {"distance_m", drive.distance_m},
            {"speed_mps", drive.speed_mps}};
}

void add_parameters(json& j, const RobotAction& action, const SewerMap& map,
                    const Mission& mission) {
  std::visit(
      [&](const auto& a) {
        using T = std::decay_t<decltype(a)>;
        if constexpr (std::is_same_v<T, DriveToManhole>) {
          j["pipe"] = map.pipe(a.pipe).name;
          j["manhole"] = map.manhole(a.manhole).name;
          j["direction"] = to_string(a.direction);
          j["distance_m"] = a.distance_m;
          j["manhole_type"] = a.manhole_type;
          j["manhole_variant"] =
              a.manhole_variant ? json(std::string(1, *a.manhole_variant)) : json();
          j["pipe_diameter_m"] = a.pipe_diameter_m;
          j["speed_mps"] = a.speed_mps;
          j["from_offset_m"] = a.from_offset_m;
          j["to_offset_m"] = a.to_offset_m;
        } else if constexpr (std::is_same_v<T, PassManhole>) {
          j["manhole"] = map.manhole(a.manhole).name;
          j["from_slot"] = to_paper_number(a.from_slot);
          j["to_slot"] = to_paper_number(a.to_slot);
          j["from_pipe"] = map.pipe(a.from_pipe).name;
          j["to_pipe"] = map.pipe(a.to_pipe).name;
          j["turn_deg"] = a.turn_deg;
          j["step_m"] = a.step_m;
          j["manhole_diameter_m"] = a.manhole_diameter_m;
          if (!a.waypoints.empty()) {
            nlohmann::ordered_json points = nlohmann::ordered_json::array();
            for (const Waypoint& w : a.waypoints) {
              points.push_back({w.x_m, w.y_m, w.z_m, w.heading_deg});
            }
            j["waypoints"] = std::move(points);
          }
        } else if constexpr (std::is_same_v<T, EnterPipe>) {
          j["manhole"] = map.manhole(a.manhole).name;
          j["slot"] = to_paper_number(a.slot);
          j["pipe"] = map.pipe(a.pipe).name;
        } else if constexpr (std::is_same_v<T, TakeWaterSample>) {
          j["pipe"] = map.pipe(a.pipe).name;
          j["offset_m"] = a.offset_m;
          j["task"] = mission.task(a.task).name;
          add_drive(j, "drive", a.drive);
          j["sample_s"] = a.sample_s;
        } else if constexpr (std::is_same_v<T, InspectPipe>) {
          j["pipe"] = map.pipe(a.pipe).name;
          j["task"] = mission.task(a.task).name;
          j["length_m"] = a.length_m;
          j["speed_mps"] = a.speed_mps;
          j["start_manhole"] = end_manhole(map, a.pipe, a.start_end);
          j["finish_manhole"] = end_manhole(map, a.pipe, a.finish_end);
          j["scan_direction"] = to_string(a.scan_direction);
          add_drive(j, "approach", a.approach);
        } else if constexpr (std::is_same_v<T, GoToPoint>) {
          j["pipe"] = map.pipe(a.pipe).name;
          j["offset_m"] = a.offset_m;
          j["task"] = mission.task(a.task).name;
          add_drive(j, "drive", a.drive);
        } else {
          static_assert(std::is_same_v<T, GoToManhole>);
          j["manhole"] = map.manhole(a.manhole).name;
          j["task"] = mission.task(a.task).name;
        }
      },
      action);
}

}  // namespace

std::string write_action_json(const RobotAction& action, const SewerMap& map,
                              const Mission& mission) {
  json j;
  j["kind"] = action_kind(action);
  j["plan_step"] = plan_step(action) + 1;
  add_parameters(j, action, map, mission);
  j["duration_s"] = duration_s(action);
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace sewerplan::fusion
