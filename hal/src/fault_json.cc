// SPDX-License-Identifier: MIT
// The fault file format (docs/simulation.md): read through core's JSON reader (json_fields.h), as
// every file of sewerplan is; written with nlohmann::json, whose number text the messages share.
#include <algorithm>
#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/hal/fault_scenario.h"

namespace sewerplan::hal {
namespace {

using json = nlohmann::ordered_json;

std::string number_text(double value) { return json(value).dump(); }

// A whole number from `min` in the field `key`.
std::optional<std::uint32_t> count(JsonFields& f, std::string_view key, std::uint32_t min) {
  std::optional<double> value = f.number(key);
  if (!value) return std::nullopt;
  if (!(*value >= min && *value <= 65535.0 * 65536.0 && std::floor(*value) == *value)) {
    f.error(key,
            "expected a whole number from " + std::to_string(min) + ", got " + number_text(*value));
    return std::nullopt;
  }
  return static_cast<std::uint32_t>(*value);
}

class FaultReader {
 public:
  FaultReader(const SewerMap& map, const std::string& file, Diagnostics& diagnostics)
      : map_(map), file_(file), diagnostics_(diagnostics) {}

  // Each list's items, with their path, to `read`.
  template <class F>
  void each(JsonFields& root, std::string_view key, F read) {
    const std::optional<JsonArray> items = root.array(key, JsonFields::Need::kOptional);
    if (!items) return;
    std::size_t i = 0;
    for (JsonElement item : *items) {
      JsonFields f(item, indexed(root.path() + "." + std::string(key), i++), file_, diagnostics_);
      read(f);
    }
  }

  // A pipe by name and an offset inside it.
  std::optional<std::pair<PipeId, double>> pipe_spot(JsonFields& f) {
    std::optional<std::string> name = f.string("pipe");
    std::optional<double> offset_m = f.number("offset_m");
    if (!name) return std::nullopt;
    std::optional<PipeId> pipe = map_.find_pipe(*name);
    if (!pipe) {
      f.error("pipe", "unknown pipe \"" + *name + "\" in map " + map_.name());
      return std::nullopt;
    }
    if (!offset_m) return std::nullopt;
    const double length_m = map_.pipe(*pipe).length_m;
    if (!(*offset_m >= 0 && *offset_m <= length_m)) {
      f.error("offset_m", "pipe " + *name + ": offset " + number_text(*offset_m) +
                              " m is outside the pipe (0 to " + number_text(length_m) + " m)");
      return std::nullopt;
    }
    return std::pair{*pipe, *offset_m};
  }

  void obstacle(JsonFields& f, FaultScenario& out) {
    f.warn_unknown({"pipe", "offset_m", "kind"});
    auto spot = pipe_spot(f);
    std::optional<ObstacleKind> kind;
    if (auto name = f.string("kind")) {
      kind = obstacle_kind_from_string(*name);
      if (!kind) {
        f.error("kind", "unknown obstacle kind \"" + *name + "\" (" + obstacle_kind_names() + ")");
      }
    }
    if (spot && kind) out.obstacles.push_back({spot->first, spot->second, *kind});
  }

  void danger(JsonFields& f, FaultScenario& out) {
    if (f.has("pipe") || !f.has("manhole")) {
      f.warn_unknown({"pipe", "offset_m"});
      if (auto spot = pipe_spot(f)) out.danger_spots.push_back({spot->first, spot->second});
      return;
    }
    f.warn_unknown({"manhole", "from_slot", "to_slot"});
    std::optional<std::string> name = f.string("manhole");
    std::optional<std::uint32_t> from = count(f, "from_slot", 1);
    std::optional<std::uint32_t> to = count(f, "to_slot", 1);
    if (!name) return;
    std::optional<ManholeId> manhole = map_.find_manhole(*name);
    if (!manhole) {
      f.error("manhole", "unknown manhole \"" + *name + "\" in map " + map_.name());
      return;
    }
    const std::uint16_t slots = map_.manhole(*manhole).slot_count;
    bool ok = from && to;
    for (auto [key, slot] : {std::pair{"from_slot", from}, std::pair{"to_slot", to}}) {
      if (slot && *slot > slots) {
        f.error(key, "manhole " + *name + " has " + std::to_string(slots) + " slots, not " +
                         std::to_string(*slot));
        ok = false;
      }
    }
    if (ok && *from == *to) {
      f.error("to_slot", "manhole " + *name + ": a passage joins two different slots");
      ok = false;
    }
    if (!ok) return;
    out.dangerous_passages.push_back({*manhole, SlotIndex{static_cast<std::uint16_t>(*from - 1)},
                                      SlotIndex{static_cast<std::uint16_t>(*to - 1)}});
  }

  void malfunction(JsonFields& f, FaultScenario& out) {
    f.warn_unknown({"at_job", "at_time_s", "kind"});
    std::optional<MalfunctionKind> kind;
    if (auto name = f.string("kind")) {
      kind = malfunction_kind_from_string(*name);
      if (!kind)
        f.error("kind",
                "unknown malfunction kind \"" + *name + "\" (" + malfunction_kind_names() + ")");
    }
    std::optional<std::variant<AtJob, AtTime>> when;
    if (f.has("at_job") == f.has("at_time_s")) {
      f.error("", "give exactly one of at_job and at_time_s");
    } else if (f.has("at_job")) {
      if (auto index = count(f, "at_job", 0)) when = AtJob{*index};
    } else if (auto time_s = f.number("at_time_s")) {
      if (std::isfinite(*time_s) && *time_s >= 0) {
        when = AtTime{*time_s};
      } else {
        f.error("at_time_s", "expected a time >= 0 s, got " + number_text(*time_s));
      }
    }
    if (kind && when) out.malfunctions.push_back({*when, *kind});
  }

 private:
  const SewerMap& map_;
  const std::string& file_;
  Diagnostics& diagnostics_;
};

}  // namespace

Result<FaultScenario> read_faults_json(std::string_view text, const std::string& file_name,
                                       const SewerMap& map, Diagnostics& diagnostics) {
  const Diagnostics::Mark before = diagnostics.mark();
  const std::optional<JsonDocument> doc = JsonDocument::parse(text, file_name, diagnostics);
  if (!doc) return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  return read_faults_value(doc->root(), "$", file_name, map, diagnostics);
}

Result<FaultScenario> read_faults_value(const JsonElement& value, const std::string& path,
                                        const std::string& file_name, const SewerMap& map,
                                        Diagnostics& diagnostics) {
  const Diagnostics::Mark before = diagnostics.mark();
  JsonFields root(value, path, file_name, diagnostics);
  if (auto format = root.string("format"); format && *format != kFaultsJsonFormat) {
    root.error("format",
               "expected \"" + std::string(kFaultsJsonFormat) + "\", got \"" + *format + "\"");
  }
  if (auto version = root.number("version"); version && *version != kFaultsJsonVersion) {
    root.error("version", "unsupported version " + number_text(*version));
  }
  if (diagnostics.has_errors_since(before)) {
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  }
  root.warn_unknown({"format", "version", "obstacles", "danger", "malfunctions", "battery_wh"});
  FaultReader reader(map, file_name, diagnostics);
  FaultScenario scenario;
  reader.each(root, "obstacles", [&](JsonFields& f) { reader.obstacle(f, scenario); });
  reader.each(root, "danger", [&](JsonFields& f) { reader.danger(f, scenario); });
  reader.each(root, "malfunctions", [&](JsonFields& f) { reader.malfunction(f, scenario); });
  if (auto battery_wh = root.number("battery_wh", JsonFields::Need::kOptional)) {
    if (std::isfinite(*battery_wh) && *battery_wh >= 0) {
      scenario.battery_wh = *battery_wh;
    } else {
      root.error("battery_wh", "expected an energy >= 0 Wh, got " + number_text(*battery_wh));
    }
  }
  if (diagnostics.has_errors_since(before)) {
    return Error{ErrorCode::kInvalidArgument, diagnostics.error_summary(before)};
  }
  return scenario;
}

Result<FaultScenario> read_faults(const std::filesystem::path& path, const SewerMap& map,
                                  Diagnostics& diagnostics) {
  Result<std::string> text = read_text_file(path);
  if (!text.has_value()) return text.error();
  return read_faults_json(*text, path.string(), map, diagnostics);
}

void write_faults_json(const FaultScenario& scenario, const SewerMap& map, std::ostream& out) {
  json j;
  j["format"] = std::string(kFaultsJsonFormat);
  j["version"] = kFaultsJsonVersion;
  j["obstacles"] = json::array();
  for (const Obstacle& o : scenario.obstacles) {
    j["obstacles"].push_back({{"pipe", map.pipe(o.pipe).name},
                              {"offset_m", o.offset_m},
                              {"kind", std::string(to_string(o.kind))}});
  }
  j["danger"] = json::array();
  for (const DangerSpot& d : scenario.danger_spots) {
    j["danger"].push_back({{"pipe", map.pipe(d.pipe).name}, {"offset_m", d.offset_m}});
  }
  for (const DangerousPassage& p : scenario.dangerous_passages) {
    j["danger"].push_back({{"manhole", map.manhole(p.manhole).name},
                           {"from_slot", to_paper_number(p.from_slot)},
                           {"to_slot", to_paper_number(p.to_slot)}});
  }
  j["malfunctions"] = json::array();
  for (const Malfunction& m : scenario.malfunctions) {
    json item;
    if (const auto* at_job = std::get_if<AtJob>(&m.when)) {
      item["at_job"] = at_job->index;
    } else {
      item["at_time_s"] = std::get<AtTime>(m.when).time_s;
    }
    item["kind"] = std::string(to_string(m.kind));
    j["malfunctions"].push_back(std::move(item));
  }
  if (scenario.battery_wh) j["battery_wh"] = *scenario.battery_wh;
  out << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
}

std::string faults_json(const FaultScenario& scenario, const SewerMap& map) {
  std::ostringstream out;
  write_faults_json(scenario, map, out);
  return out.str();
}

}  // namespace sewerplan::hal
