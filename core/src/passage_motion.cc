// SPDX-License-Identifier: MIT
#include "sewerplan/core/passage_motion.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <sstream>
#include <tuple>

#include <nlohmann/json.hpp>

#include "sewerplan/core/check.h"
#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/map_fingerprint.h"
#include "sewerplan/core/map_queries.h"
#include "sewerplan/core/text_file.h"

namespace sewerplan {
namespace {

using Need = JsonFields::Need;

constexpr double kLimitTolerance = 1e-9;

bool key_less(const PassageMotion& a, const PassageMotion& b) {
  return std::tie(a.manhole, a.from, a.to) < std::tie(b.manhole, b.from, b.to);
}

// FNV-1a over text: stable across platforms and runs (std::hash is neither).
class Fingerprint {
 public:
  void add(std::string_view text) {
    for (char c : text) {
      hash_ ^= static_cast<unsigned char>(c);
      hash_ *= 1099511628211ULL;
    }
    hash_ ^= 0xff;  // separator
    hash_ *= 1099511628211ULL;
  }
  void add(double v) { add(format_double(v)); }
  std::string hex() const {
    std::ostringstream out;
    out << std::hex << std::setw(16) << std::setfill('0') << hash_;
    return out.str();
  }

 private:
  std::uint64_t hash_ = 14695981039346656037ULL;
};

std::optional<Waypoint> read_waypoint(JsonElement e, const std::string& where, Diagnostics& d) {
  JsonArray array;
  if (e.get_array().get(array) != simdjson::SUCCESS || array.size() != 4) {
    d.error(where, "expected a waypoint [x_m, y_m, z_m, heading_deg], got " + describe_json(e));
    return std::nullopt;
  }
  double v[4];
  std::size_t i = 0;
  for (JsonElement x : array) {
    if (x.get_double().get(v[i]) != simdjson::SUCCESS || !std::isfinite(v[i])) {
      d.error(where, "waypoint values must be finite numbers, got " + describe_json(x));
      return std::nullopt;
    }
    ++i;
  }
  return Waypoint{v[0], v[1], v[2], v[3]};
}

std::optional<SlotIndex> read_slot(JsonFields& f, std::string_view key, const Manhole& manhole) {
  auto n = f.number(key);
  if (!n) return std::nullopt;
  if (!(*n >= 1 && *n <= manhole.slot_count && std::floor(*n) == *n)) {
    f.diagnostics().error(f.where(key), "manhole " + manhole.name + " has slots 1 to " +
                                            std::to_string(manhole.slot_count) + ", got " +
                                            format_double(*n));
    return std::nullopt;
  }
  return SlotIndex{static_cast<std::uint16_t>(*n - 1)};
}

std::optional<PassageMotion> read_passage(JsonElement e, const std::string& path,
                                          const std::string& file, const SewerMap& map,
                                          Diagnostics& d) {
  JsonFields f(e, path, file, d);
  f.warn_unknown(
      {"manhole", "from_slot", "to_slot", "feasible", "duration_s", "waypoints", "reason"});
  const auto name = f.string("manhole");
  const auto feasible = f.boolean("feasible");
  if (!name || !feasible) return std::nullopt;
  const auto id = map.find_manhole(*name);
  if (!id) {
    d.error(f.where("manhole"), "unknown manhole '" + *name + "'");
    return std::nullopt;
  }
  const Manhole& manhole = map.manhole(*id);
  const auto from = read_slot(f, "from_slot", manhole);
  const auto to = read_slot(f, "to_slot", manhole);
  if (!from || !to) return std::nullopt;
  PassageMotion p{.manhole = *id, .from = *from, .to = *to, .feasible = *feasible};
  if (*from == *to) {
    d.error(f.where("to_slot"), "a passage leads from one slot to another, got slot " +
                                    std::to_string(to_paper_number(*to)) + " twice");
    return std::nullopt;
  }
  if (p.feasible) {
    const auto duration = f.number("duration_s");
    if (!duration) return std::nullopt;
    if (!(std::isfinite(*duration) && *duration >= 0)) {
      d.error(f.where("duration_s"),
              "must be a finite number >= 0, got " + format_double(*duration));
      return std::nullopt;
    }
    p.duration_s = *duration;
    if (auto points = f.array("waypoints", Need::kOptional)) {
      std::size_t i = 0;
      for (JsonElement w : *points) {
        auto point = read_waypoint(w, file + ":" + indexed(path + ".waypoints", i++), d);
        if (!point) return std::nullopt;
        p.waypoints.push_back(*point);
      }
    }
  } else {
    p.reason = f.string("reason", Need::kOptional).value_or("");
  }
  return p;
}

}  // namespace

PassageMotionTable::PassageMotionTable(std::string map_fingerprint, std::string profile_fingerprint,
                                       std::vector<PassageMotion> entries)
    : map_fingerprint_(std::move(map_fingerprint)),
      profile_fingerprint_(std::move(profile_fingerprint)),
      entries_(std::move(entries)) {
  // The precompute gives them in order: then one pass, not a sort (issue 14: the sort was part of
  // a stretch without a stop check at the precompute's end).
  if (!std::is_sorted(entries_.begin(), entries_.end(), key_less)) {
    std::sort(entries_.begin(), entries_.end(), key_less);
  }
  for (std::size_t i = 1; i < entries_.size(); ++i) {
    SEWER_CHECK(key_less(entries_[i - 1], entries_[i]), "passage motion table: duplicate passage");
  }
}

const PassageMotion* PassageMotionTable::find(ManholeId manhole, SlotIndex from,
                                              SlotIndex to) const {
  const PassageMotion key{.manhole = manhole, .from = from, .to = to};
  auto it = std::lower_bound(entries_.begin(), entries_.end(), key, key_less);
  if (it == entries_.end() || it->manhole != manhole || it->from != from || it->to != to) {
    return nullptr;
  }
  return &*it;
}

std::string map_geometry_fingerprint(const SewerMap& map) {
  return *map_geometry_fingerprint(map, StopCondition{});
}

std::optional<std::string> map_geometry_fingerprint(const SewerMap& map,
                                                    const StopCondition& stop) {
  constexpr std::size_t kCheckEvery = 64;
  Fingerprint f;
  f.add(std::to_string(map.manhole_count()));
  for (ManholeId m : map.manhole_ids()) {
    if (m.index() % kCheckEvery == 0 && stop.interrupted()) return std::nullopt;
    const Manhole& manhole = map.manhole(m);
    f.add(manhole.name);
    f.add(manhole.diameter_m);
    f.add(manhole.position.z_m);
    for (const Slot& s : map.slots(m)) {
      f.add(s.azimuth_deg);
      f.add(s.invert_z_m);
      f.add(map.pipe(s.pipe).diameter_m);
    }
  }
  return f.hex();
}

std::string profile_geometry_fingerprint(const RobotProfile& p) {
  Fingerprint f;
  for (double v :
       {p.length_m, static_cast<double>(p.segment_count), p.body_width_m, p.min_pipe_diameter_m,
        p.max_pipe_diameter_m, p.joint_yaw_max_deg, p.joint_pitch_max_deg, p.manoeuvre_speed_mps,
        p.turn_s_per_deg, p.step_s_per_m}) {
    f.add(v);
  }
  return f.hex();
}

Result<PassageMotionTable> read_passage_motion_json(std::string_view text,
                                                    const std::string& file_name,
                                                    const SewerMap& map, Diagnostics& diagnostics) {
  const Diagnostics::Mark before = diagnostics.mark();
  auto doc = JsonDocument::parse(text, file_name, diagnostics);
  if (!doc) return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  JsonFields root(doc->root(), "$", file_name, diagnostics);
  root.warn_unknown({"format", "version", "map", "map_fingerprint", "profile",
                     "profile_fingerprint", "passages"});
  if (auto format = root.string("format"); format && *format != kPassageMotionJsonFormat) {
    diagnostics.error(root.where("format"), "expected \"" + std::string(kPassageMotionJsonFormat) +
                                                "\", got \"" + *format + "\"");
  }
  if (auto version = root.number("version"); version && *version != kPassageMotionJsonVersion) {
    diagnostics.error(root.where("version"), "unsupported version " + format_double(*version));
  }
  const auto map_fp = root.string("map_fingerprint");
  const auto profile_fp = root.string("profile_fingerprint");
  std::vector<PassageMotion> entries;
  if (auto passages = root.array("passages")) {
    std::size_t i = 0;
    for (JsonElement e : *passages) {
      const std::string path = indexed("$.passages", i++);
      auto p = read_passage(e, path, file_name, map, diagnostics);
      if (p) entries.push_back(std::move(*p));
    }
  }
  if (diagnostics.has_errors_since(before))
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  std::vector<PassageMotion> sorted = entries;
  std::sort(sorted.begin(), sorted.end(), key_less);
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    if (!key_less(sorted[i - 1], sorted[i])) {
      diagnostics.error(file_name + ":$.passages",
                        "passage " + map.manhole(sorted[i].manhole).name + " slot " +
                            std::to_string(to_paper_number(sorted[i].from)) + " -> " +
                            std::to_string(to_paper_number(sorted[i].to)) +
                            " is listed more than once");
      return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
    }
  }
  return PassageMotionTable(*map_fp, *profile_fp, std::move(entries));
}

void write_passage_motion_json(const PassageMotionTable& table, const SewerMap& map,
                               std::ostream& out) {
  // One passage a line: tables of city networks hold hundreds of thousands of waypoints.
  out << "{\"format\": " << nlohmann::json(kPassageMotionJsonFormat).dump()
      << ", \"version\": " << kPassageMotionJsonVersion << ",\n \"map\": "
      << nlohmann::json(map.name()).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)
      << ",\n \"map_fingerprint\": " << nlohmann::json(table.map_fingerprint()).dump()
      << ",\n \"profile_fingerprint\": " << nlohmann::json(table.profile_fingerprint()).dump()
      << ",\n \"passages\": [";
  bool first = true;
  for (const PassageMotion& p : table.entries()) {
    nlohmann::ordered_json e;
    e["manhole"] = map.manhole(p.manhole).name;
    e["from_slot"] = to_paper_number(p.from);
    e["to_slot"] = to_paper_number(p.to);
    e["feasible"] = p.feasible;
    if (p.feasible) {
      e["duration_s"] = p.duration_s;
      nlohmann::ordered_json points = nlohmann::ordered_json::array();
      for (const Waypoint& w : p.waypoints) {
        points.push_back({w.x_m, w.y_m, w.z_m, w.heading_deg});
      }
      e["waypoints"] = std::move(points);
    } else {
      e["reason"] = p.reason;
    }
    out << (first ? "\n  " : ",\n  ")
        << e.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    first = false;
  }
  out << "]}\n";
}

Result<PassageMotionTable> load_passage_motion(const std::filesystem::path& path,
                                               const SewerMap& map, const RobotProfile& profile) {
  Result<std::string> text = read_text_file(path);
  if (!text.has_value()) return text.error();
  Diagnostics diagnostics;
  Result<PassageMotionTable> table =
      read_passage_motion_json(*text, path.string(), map, diagnostics);
  if (!table.has_value()) return table;
  const std::string remake = "; remake it with 'sewerplan motion precompute'";
  if (table->map_fingerprint() != map_geometry_fingerprint(map)) {
    return Error{ErrorCode::kInvalidArgument,
                 path.string() + ": stale motion table: it was made for another map geometry " +
                     "than map '" + map.name() + "' (fingerprint " + table->map_fingerprint() +
                     ", the map's is " + map_geometry_fingerprint(map) + ")" + remake};
  }
  if (table->profile_fingerprint() != profile_geometry_fingerprint(profile)) {
    return Error{ErrorCode::kInvalidArgument,
                 path.string() + ": stale motion table: it was made for another robot geometry " +
                     "than profile '" + profile.name + "' (fingerprint " +
                     table->profile_fingerprint() + ", the profile's is " +
                     profile_geometry_fingerprint(profile) + ")" + remake + " --profile " +
                     profile.name};
  }
  return table;
}

std::filesystem::path default_motion_path(const std::filesystem::path& map_path) {
  std::filesystem::path p = map_path;
  p.replace_extension(".motion.json");
  return p;
}

PassageVerdict judge_passage(const SewerMap& map, const RobotProfile& profile,
                             const PassageMotionTable* motion, ManholeId manhole, SlotIndex from,
                             SlotIndex to) {
  PassageVerdict v;
  v.turn_deg = passage_turn_deg(map, manhole, from, to);
  v.step_m = passage_step_m(map, manhole, from, to);
  if (motion != nullptr) {
    if (const PassageMotion* m = motion->find(manhole, from, to)) {
      v.by_motion = true;
      v.motion = m;
      v.allowed = m->feasible;
      v.duration_s = m->duration_s;
      return v;
    }
  }
  v.allowed = v.turn_deg <= profile.max_turn_deg + kLimitTolerance &&
              std::abs(v.step_m) <= profile.max_step_m + kLimitTolerance;
  v.duration_s = profile.manhole_pass_s + v.turn_deg * profile.turn_s_per_deg +
                 std::abs(v.step_m) * profile.step_s_per_m;
  return v;
}

}  // namespace sewerplan
