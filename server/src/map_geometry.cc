// SPDX-License-Identifier: MIT
#include "map_geometry.h"

#include <algorithm>
#include <limits>

#include <nlohmann/json.hpp>

namespace sewerplan::server {

std::string map_geometry_json(const SewerMap& map, const std::string& id) {
  using Json = nlohmann::ordered_json;
  Json names = Json::array(), xs = Json::array(), ys = Json::array(), slots = Json::array(),
       exits = Json::array();
  double min_x = std::numeric_limits<double>::infinity(), min_y = min_x;
  double max_x = -min_x, max_y = -min_x;
  for (const Manhole& m : map.manholes()) {
    names.push_back(m.name);
    xs.push_back(m.position.x_m);
    ys.push_back(m.position.y_m);
    slots.push_back(m.slot_count);
    exits.push_back(m.exit ? 1 : 0);
    min_x = std::min(min_x, m.position.x_m);
    min_y = std::min(min_y, m.position.y_m);
    max_x = std::max(max_x, m.position.x_m);
    max_y = std::max(max_y, m.position.y_m);
  }
  if (map.manhole_count() == 0) min_x = min_y = max_x = max_y = 0;
  Json pipe_names = Json::array(), from = Json::array(), to = Json::array(),
       lengths = Json::array(), diameters = Json::array();
  for (const Pipe& p : map.pipes()) {
    pipe_names.push_back(p.name);
    from.push_back(p.ends[0].manhole ? static_cast<long long>(p.ends[0].manhole->value()) : -1);
    to.push_back(p.ends[1].manhole ? static_cast<long long>(p.ends[1].manhole->value()) : -1);
    lengths.push_back(p.length_m);
    diameters.push_back(p.diameter_m);
  }
  Json points = Json::array();
  for (const InspectionPoint& p : map.points()) {
    points.push_back({{"name", p.name}, {"pipe", map.pipe(p.pipe).name}, {"offset_m", p.offset_m}});
  }
  const Json j = {
      {"id", id},
      {"name", map.name()},
      {"bounds", {min_x, min_y, max_x, max_y}},
      {"manholes", {{"name", names}, {"x", xs}, {"y", ys}, {"slots", slots}, {"exit", exits}}},
      {"pipes",
       {{"name", pipe_names},
        {"from", from},
        {"to", to},
        {"length_m", lengths},
        {"diameter_m", diameters}}},
      {"points", points}};
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace sewerplan::server
