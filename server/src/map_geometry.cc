// SPDX-License-Identifier: MIT
#include "map_geometry.h"

#include <algorithm>
#include <array>
#include <bit>
#include <limits>
#include <vector>

#include <nlohmann/json.hpp>

namespace sewerplan::server {

namespace {

// The map's bounds: [min_x, min_y, max_x, max_y] of its manholes, zeros for none.
std::array<double, 4> bounds_of(const SewerMap& map) {
  double min_x = std::numeric_limits<double>::infinity(), min_y = min_x;
  double max_x = -min_x, max_y = -min_x;
  for (const Manhole& m : map.manholes()) {
    min_x = std::min(min_x, m.position.x_m);
    min_y = std::min(min_y, m.position.y_m);
    max_x = std::max(max_x, m.position.x_m);
    max_y = std::max(max_y, m.position.y_m);
  }
  if (map.manhole_count() == 0) return {0, 0, 0, 0};
  return {min_x, min_y, max_x, max_y};
}

// Appends little-endian values whatever the host's byte order.
class LittleEndian {
 public:
  explicit LittleEndian(std::string& out) : out_(out) {}
  void u8(std::uint8_t v) { out_.push_back(static_cast<char>(v)); }
  void u16(std::uint16_t v) {
    for (int shift = 0; shift < 16; shift += 8) u8(static_cast<std::uint8_t>(v >> shift));
  }
  void u32(std::uint32_t v) {
    for (int shift = 0; shift < 32; shift += 8) u8(static_cast<std::uint8_t>(v >> shift));
  }
  void f64(double v) {
    const auto bits = std::bit_cast<std::uint64_t>(v);
    for (int shift = 0; shift < 64; shift += 8) u8(static_cast<std::uint8_t>(bits >> shift));
  }

 private:
  std::string& out_;
};

}  // namespace

Result<std::string> map_geometry_binary(const SewerMap& map) {
  constexpr std::uint64_t kMaxU32 = std::numeric_limits<std::uint32_t>::max();
  const auto too_large = [&](std::uint64_t count, std::uint64_t limit, const std::string& what) {
    return Error{ErrorCode::kInvalidArgument,
                 "map '" + map.name() + "': " + std::to_string(count) + " " + what +
                     ", the compact geometry holds at most " + std::to_string(limit)};
  };
  // A manhole's index is never kNoManhole, the open end's mark.
  if (map.manhole_count() >= kNoManhole) {
    return too_large(map.manhole_count(), kNoManhole - 1, "manholes");
  }
  if (map.pipe_count() > kMaxU32) return too_large(map.pipe_count(), kMaxU32, "pipes");
  std::uint64_t name_bytes = 0;
  for (const Manhole& m : map.manholes()) name_bytes += m.name.size();
  for (const Pipe& p : map.pipes()) name_bytes += p.name.size();
  if (name_bytes > kMaxU32) return too_large(name_bytes, kMaxU32, "bytes of names");
  std::string names;
  names.reserve(name_bytes);
  std::vector<std::uint32_t> offsets{0};
  offsets.reserve(map.manhole_count() + map.pipe_count() + 1);
  const auto add_name = [&](const std::string& name) {
    names += name;
    offsets.push_back(static_cast<std::uint32_t>(names.size()));
  };
  for (const Manhole& m : map.manholes()) add_name(m.name);
  for (const Pipe& p : map.pipes()) add_name(p.name);
  std::string out;
  out.reserve(56 + 16 * map.manhole_count() + 24 * map.pipe_count() + 4 * offsets.size() +
              3 * map.manhole_count() + names.size());
  LittleEndian w(out);
  out += "SPGM";
  w.u32(kGeometryFormatVersion);
  w.u32(static_cast<std::uint32_t>(map.manhole_count()));
  w.u32(static_cast<std::uint32_t>(map.pipe_count()));
  for (double b : bounds_of(map)) w.f64(b);
  w.u32(static_cast<std::uint32_t>(names.size()));
  w.u32(0);
  for (const Manhole& m : map.manholes()) {
    w.f64(m.position.x_m);
    w.f64(m.position.y_m);
  }
  for (const Pipe& p : map.pipes()) w.f64(p.length_m);
  for (const Pipe& p : map.pipes()) w.f64(p.diameter_m);
  for (std::size_t end = 0; end < 2; ++end) {
    for (const Pipe& p : map.pipes()) {
      const auto& m = p.ends[end].manhole;
      w.u32(m ? static_cast<std::uint32_t>(m->value()) : kNoManhole);
    }
  }
  for (std::uint32_t o : offsets) w.u32(o);
  for (const Manhole& m : map.manholes()) w.u16(m.slot_count);
  for (const Manhole& m : map.manholes()) w.u8(m.exit ? 1 : 0);
  out += names;
  return out;
}

std::string map_geometry_json(const SewerMap& map, const std::string& id) {
  using Json = nlohmann::ordered_json;
  Json names = Json::array(), xs = Json::array(), ys = Json::array(), slots = Json::array(),
       exits = Json::array();
  for (const Manhole& m : map.manholes()) {
    names.push_back(m.name);
    xs.push_back(m.position.x_m);
    ys.push_back(m.position.y_m);
    slots.push_back(m.slot_count);
    exits.push_back(m.exit ? 1 : 0);
  }
  const auto [min_x, min_y, max_x, max_y] = bounds_of(map);
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
