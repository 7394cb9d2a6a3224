// SPDX-License-Identifier: MIT
#include "support/small_map.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace sewerplan::testing {
namespace {

ManholeRecord* find(std::vector<ManholeRecord>& manholes, const std::string& name) {
  for (ManholeRecord& m : manholes) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

}  // namespace

SmallMap& SmallMap::manhole(std::string name, double x_m, double y_m, bool exit) {
  manholes_.push_back(
      {.name = std::move(name), .position = {x_m, y_m, 0}, .diameter_m = 1.0, .exit = exit});
  return *this;
}

SmallMap& SmallMap::pipe(std::string name, std::string from, std::string to, double diameter_m,
                         std::optional<double> length_m) {
  ManholeRecord* a = find(manholes_, from);
  ManholeRecord* b = find(manholes_, to);
  double length = length_m.value_or(1.0);
  if (a != nullptr && b != nullptr && !length_m) {
    length = std::hypot(b->position.x_m - a->position.x_m, b->position.y_m - a->position.y_m);
  }
  auto azimuth = [](const ManholeRecord& here, const ManholeRecord* there) {
    if (there == nullptr) return 0.0;
    return std::atan2(there->position.y_m - here.position.y_m,
                      there->position.x_m - here.position.x_m) *
           180.0 / std::numbers::pi;
  };
  if (a != nullptr) a->slots.push_back({.pipe = name, .azimuth_deg = azimuth(*a, b)});
  if (b != nullptr) b->slots.push_back({.pipe = name, .azimuth_deg = azimuth(*b, a)});
  PipeRecord record{.name = std::move(name), .length_m = length, .diameter_m = diameter_m};
  if (!from.empty()) record.from = std::move(from);
  if (!to.empty()) record.to = std::move(to);
  pipes_.push_back(std::move(record));
  return *this;
}

SmallMap& SmallMap::invert(const std::string& manhole, const std::string& pipe, double z_m) {
  ManholeRecord* m = find(manholes_, manhole);
  EXPECT_NE(m, nullptr) << manhole;
  if (m == nullptr) return *this;
  for (SlotRecord& slot : m->slots) {
    if (slot.pipe == pipe) slot.invert_z_m = z_m;
  }
  return *this;
}

SmallMap& SmallMap::point(std::string name, std::string pipe, double offset_m) {
  points_.push_back({.name = std::move(name), .pipe = std::move(pipe), .offset_m = offset_m});
  return *this;
}

SewerMap SmallMap::build() const {
  MapBuilder builder("small");
  for (const ManholeRecord& m : manholes_) builder.add_manhole(m);
  for (const PipeRecord& p : pipes_) builder.add_pipe(p);
  for (const PointRecord& p : points_) builder.add_point(p);
  Diagnostics diagnostics;
  Result<SewerMap> map = std::move(builder).build(diagnostics);
  EXPECT_TRUE(map.has_value()) << map.error();
  return map.has_value() ? std::move(map).value() : SewerMap{};
}

Mission small_mission(const SewerMap& map, const std::string& start) {
  Mission mission;
  mission.name = "test";
  mission.profile = *builtin_profile("makro-1.1");
  mission.battery_reserve_fraction = 0;
  if (auto m = map.find_manhole(start)) {
    mission.start = *m;
  } else {
    auto p = map.find_pipe(start);
    EXPECT_TRUE(p.has_value()) << start;
    mission.start = PipeSpot{p.value_or(PipeId{0}), std::nullopt, std::nullopt};
  }
  for (ManholeId id : map.manhole_ids()) {
    if (map.manhole(id).exit) mission.exits.push_back(id);
  }
  return mission;
}

TaskId add_task(Mission& mission, const SewerMap& map, std::string name, TaskKind kind,
                const std::string& where, std::optional<double> offset_m, bool final) {
  Place place = ManholeId{0};
  if (auto m = map.find_manhole(where)) {
    place = *m;
  } else {
    auto p = map.find_pipe(where);
    EXPECT_TRUE(p.has_value()) << where;
    place = PipeSpot{p.value_or(PipeId{0}), offset_m, std::nullopt};
  }
  mission.tasks.push_back({std::move(name), kind, place, final});
  return TaskId{static_cast<std::uint32_t>(mission.tasks.size() - 1)};
}

}  // namespace sewerplan::testing
