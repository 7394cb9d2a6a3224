// SPDX-License-Identifier: MIT
// Writing missions (JSON) and describing places for people.
#include <algorithm>

#include <nlohmann/json.hpp>

#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/mission.h"

#include "profile_json.h"

namespace sewerplan {
namespace {

using nlohmann::json;

json place_to_json(const Place& place, const SewerMap& map) {
  if (const auto* m = std::get_if<ManholeId>(&place)) return {{"manhole", map.manhole(*m).name}};
  const auto& spot = std::get<PipeSpot>(place);
  if (spot.point) return {{"point", map.point(*spot.point).name}};
  json j = {{"pipe", map.pipe(spot.pipe).name}};
  if (spot.offset_m) j["offset_m"] = *spot.offset_m;
  return j;
}

}  // namespace

void write_mission_json(const Mission& m, const SewerMap& map, std::ostream& out) {
  json j;
  j["format"] = kMissionJsonFormat;
  j["version"] = kMissionJsonVersion;
  j["name"] = m.name;
  if (builtin_profile(m.profile.name) == m.profile) {
    j["profile"] = m.profile.name;
  } else {
    j["profile"] = detail::profile_to_json(m.profile);
  }
  j["start"] = place_to_json(m.start, map);
  j["tasks"] = json::array();
  for (const Task& t : m.tasks) {
    json task = {{"name", t.name}, {"type", to_string(t.kind)}};
    if (t.kind == TaskKind::kInspectPipe) {
      task["pipe"] = map.pipe(std::get<PipeSpot>(t.place).pipe).name;
    } else {
      task["at"] = place_to_json(t.place, map);
    }
    if (t.final) task["final"] = true;
    j["tasks"].push_back(task);
  }
  j["exits"] = json::array();
  for (ManholeId e : m.exits) j["exits"].push_back(map.manhole(e).name);
  j["battery_reserve"] = m.battery_reserve_fraction;
  if (!m.closed_pipes.empty() || !m.closed_passages.empty() || !m.blockages.empty()) {
    json closed = {{"pipes", json::array()}, {"passages", json::array()}};
    if (!m.blockages.empty()) closed["blockages"] = json::array();
    for (const Blockage& b : m.blockages) {
      closed["blockages"].push_back({{"pipe", map.pipe(b.pipe).name}, {"offset_m", b.offset_m}});
    }
    for (PipeId p : m.closed_pipes) closed["pipes"].push_back(map.pipe(p).name);
    for (const ClosedPassage& c : m.closed_passages) {
      closed["passages"].push_back({{"manhole", map.manhole(c.manhole).name},
                                    {"from_slot", to_paper_number(c.from)},
                                    {"to_slot", to_paper_number(c.to)}});
    }
    j["closed"] = closed;
  }
  out << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
}

std::string describe(const Place& place, const SewerMap& map) {
  if (const auto* m = std::get_if<ManholeId>(&place)) return "manhole " + map.manhole(*m).name;
  const auto& spot = std::get<PipeSpot>(place);
  const std::string pipe = "pipe " + map.pipe(spot.pipe).name;
  if (spot.point) return "point " + map.point(*spot.point).name + " (" + pipe + ")";
  if (spot.offset_m) return pipe + " at " + format_double(*spot.offset_m) + " m";
  return pipe;
}

std::optional<Blockage> blockage_between(const Mission& mission, PipeId pipe, double a, double b) {
  const double lo = std::min(a, b);
  const double hi = std::max(a, b);
  for (const Blockage& blockage : mission.blockages) {
    if (blockage.pipe == pipe && blockage.offset_m > lo && blockage.offset_m < hi) return blockage;
  }
  return std::nullopt;
}

}  // namespace sewerplan
