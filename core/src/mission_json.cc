// SPDX-License-Identifier: MIT
#include <algorithm>
#include <set>

#include <nlohmann/json.hpp>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/text_file.h"

#include "json_fields.h"
#include "profile_json.h"

namespace sewerplan {
namespace {

using detail::JsonFields;
using Need = JsonFields::Need;
using nlohmann::json;

// Resolves names against the map; each failure is reported at the field that named it.
class MissionReader {
 public:
  MissionReader(const SewerMap& map, std::string_view file, Diagnostics& d)
      : map_(map), file_(file), d_(d) {}

  std::optional<ManholeId> manhole(JsonFields& f, std::string_view key, Need need) {
    auto name = f.string(key, need);
    if (!name) return std::nullopt;
    auto id = map_.find_manhole(*name);
    if (!id) d_.error(f.where(key), "unknown manhole '" + *name + "'");
    return id;
  }

  std::optional<PipeId> pipe(JsonFields& f, std::string_view key, Need need) {
    auto name = f.string(key, need);
    if (!name) return std::nullopt;
    auto id = map_.find_pipe(*name);
    if (!id) d_.error(f.where(key), "unknown pipe '" + *name + "'");
    return id;
  }

  std::optional<Place> place(const json& j, const std::string& path) {
    JsonFields f(j, path, file_, d_);
    f.warn_unknown({"manhole", "pipe", "point", "offset_m"});
    const int given = int{f.has("manhole")} + int{f.has("pipe")} + int{f.has("point")};
    if (given != 1) {
      d_.error(f.where(), "a place names exactly one of \"manhole\", \"pipe\" or \"point\"");
      return std::nullopt;
    }
    if (f.has("manhole")) return manhole(f, "manhole", Need::kRequired);
    if (f.has("point")) {
      auto name = f.string("point");
      if (!name) return std::nullopt;
      auto id = map_.find_point(*name);
      if (!id) {
        d_.error(f.where("point"), "unknown inspection point '" + *name + "'");
        return std::nullopt;
      }
      const InspectionPoint& p = map_.point(*id);
      return PipeSpot{p.pipe, p.offset_m, id};
    }
    auto id = pipe(f, "pipe", Need::kRequired);
    if (!id) return std::nullopt;
    PipeSpot spot{*id, f.number("offset_m", Need::kOptional), std::nullopt};
    const double length = map_.pipe(*id).length_m;
    if (spot.offset_m && !(*spot.offset_m >= 0 && *spot.offset_m <= length)) {
      d_.error(f.where("offset_m"), "offset " + detail::format_double(*spot.offset_m) +
                                        " m is outside pipe " + map_.pipe(*id).name + " (0 to " +
                                        detail::format_double(length) + " m)");
    }
    return spot;
  }

  void tasks(const json& array, std::vector<Task>& out) {
    for (std::size_t i = 0; i < array.size(); ++i) {
      task(array[i], "$.tasks[" + std::to_string(i) + "]", i, out);
    }
  }

  void closed(const json& j, Mission& m) {
    JsonFields f(j, "$.closed", file_, d_);
    f.warn_unknown({"pipes", "passages"});
    if (const json* pipes = f.array("pipes", Need::kOptional)) {
      for (std::size_t i = 0; i < pipes->size(); ++i) {
        json wrapper = {{"pipe", (*pipes)[i]}};
        JsonFields pf(wrapper, "$.closed.pipes[" + std::to_string(i) + "]", file_, d_);
        if (auto id = pipe(pf, "pipe", Need::kRequired)) m.closed_pipes.push_back(*id);
      }
    }
    if (const json* passages = f.array("passages", Need::kOptional)) {
      for (std::size_t i = 0; i < passages->size(); ++i) {
        passage((*passages)[i], "$.closed.passages[" + std::to_string(i) + "]", m);
      }
    }
  }

 private:
  void task(const json& j, const std::string& path, std::size_t index, std::vector<Task>& out) {
    JsonFields f(j, path, file_, d_);
    f.warn_unknown({"name", "type", "at", "pipe", "pipes", "final"});
    const std::string name =
        f.string("name", Need::kOptional).value_or("task-" + std::to_string(index + 1));
    const bool final = f.boolean("final", Need::kOptional).value_or(false);
    auto type = f.string("type");
    if (!type) return;
    if (*type == "go_to" || *type == "take_water_sample") {
      const TaskKind kind = *type == "go_to" ? TaskKind::kGoTo : TaskKind::kTakeWaterSample;
      const json* at = f.member("at");
      if (at == nullptr) return;
      auto where = place(*at, path + ".at");
      if (!where) return;
      if (kind == TaskKind::kTakeWaterSample && std::holds_alternative<ManholeId>(*where)) {
        d_.error(f.where("at"),
                 "task " + name + ": a water sample is taken in a pipe, not in a manhole");
        return;
      }
      out.push_back({name, kind, *where, final});
    } else if (*type == "inspect_pipe") {
      if (auto id = pipe(f, "pipe", Need::kRequired)) {
        out.push_back({name, TaskKind::kInspectPipe, PipeSpot{*id, {}, {}}, final});
      }
    } else if (*type == "inspect_area") {
      if (final) d_.error(f.where("final"), "task " + name + ": an area cannot be the final task");
      const json* pipes = f.array("pipes");
      for (std::size_t k = 0; pipes && k < pipes->size(); ++k) {
        json wrapper = {{"pipe", (*pipes)[k]}};
        JsonFields pf(wrapper, path + ".pipes[" + std::to_string(k) + "]", file_, d_);
        if (auto id = pipe(pf, "pipe", Need::kRequired)) {
          out.push_back({name + "/" + map_.pipe(*id).name, TaskKind::kInspectPipe,
                         PipeSpot{*id, {}, {}}, false});
        }
      }
    } else {
      d_.error(f.where("type"), "unknown task type \"" + *type +
                                    "\" (go_to, inspect_pipe, inspect_area, take_water_sample)");
    }
  }

  void passage(const json& j, const std::string& path, Mission& m) {
    JsonFields f(j, path, file_, d_);
    f.warn_unknown({"manhole", "from_slot", "to_slot"});
    auto id = manhole(f, "manhole", Need::kRequired);
    auto from = f.number("from_slot");
    auto to = f.number("to_slot");
    if (!id || !from || !to) return;
    const auto slots = static_cast<double>(map_.manhole(*id).slot_count);
    for (auto [key, v] : {std::pair{"from_slot", *from}, std::pair{"to_slot", *to}}) {
      if (!(v >= 1 && v <= slots && v == static_cast<double>(static_cast<int>(v)))) {
        d_.error(f.where(key), "manhole " + map_.manhole(*id).name + " has slots 1 to " +
                                   detail::format_double(slots) + ", got " +
                                   detail::format_double(v));
        return;
      }
    }
    m.closed_passages.push_back({*id, SlotIndex{static_cast<std::uint16_t>(*from - 1)},
                                 SlotIndex{static_cast<std::uint16_t>(*to - 1)}});
  }

  const SewerMap& map_;
  std::string_view file_;
  Diagnostics& d_;
};

void check_tasks(const Mission& m, const std::string& file, Diagnostics& d) {
  std::set<std::string> names;
  std::size_t finals = 0;
  for (std::size_t i = 0; i < m.tasks.size(); ++i) {
    if (!names.insert(m.tasks[i].name).second) {
      d.error(file + ":$.tasks", "duplicate task name '" + m.tasks[i].name + "'");
    }
    finals += m.tasks[i].final ? 1U : 0U;
  }
  if (finals > 1) d.error(file + ":$.tasks", "more than one task is marked final");
  if (m.exits.empty() && finals == 0) {
    d.error(
        file + ":$.exits",
        "the mission has no exit: name \"exits\", mark exit manholes in the map, or mark a task "
        "final");
  }
}

}  // namespace

const Task* Mission::final_task() const {
  auto it = std::find_if(tasks.begin(), tasks.end(), [](const Task& t) { return t.final; });
  return it == tasks.end() ? nullptr : &*it;
}

std::string_view to_string(TaskKind kind) {
  switch (kind) {
    case TaskKind::kGoTo:
      return "go_to";
    case TaskKind::kInspectPipe:
      return "inspect_pipe";
    case TaskKind::kTakeWaterSample:
      return "take_water_sample";
  }
  return "go_to";
}

Result<Mission> read_mission_json(std::string_view text, const std::string& file_name,
                                  const SewerMap& map, Diagnostics& diagnostics) {
  auto doc = detail::parse_json(text, file_name, diagnostics);
  if (!doc) return Error{ErrorCode::kParse, diagnostics.error_summary()};
  JsonFields root(*doc, "$", file_name, diagnostics);
  root.warn_unknown({"format", "version", "name", "profile", "start", "tasks", "exits",
                     "battery_reserve", "closed"});
  if (auto format = root.string("format"); format && *format != kMissionJsonFormat) {
    diagnostics.error(root.where("format"), "expected \"" + std::string(kMissionJsonFormat) +
                                                "\", got \"" + *format + "\"");
  }
  if (auto version = root.number("version"); version && *version != kMissionJsonVersion) {
    diagnostics.error(root.where("version"),
                      "unsupported version " + detail::format_double(*version));
  }
  MissionReader reader(map, file_name, diagnostics);
  Mission m;
  m.name = root.string("name", Need::kOptional).value_or("mission");
  const json default_profile = "makro-1.1";
  const json* profile = root.member("profile", Need::kOptional);
  if (auto p = detail::read_profile_value(profile ? *profile : default_profile, "$.profile",
                                          file_name, diagnostics)) {
    m.profile = *p;
  }
  if (const json* start = root.member("start")) {
    if (auto p = reader.place(*start, "$.start")) m.start = *p;
  }
  if (const json* tasks = root.array("tasks")) reader.tasks(*tasks, m.tasks);
  if (const json* exits = root.array("exits", Need::kOptional)) {
    for (std::size_t i = 0; i < exits->size(); ++i) {
      json wrapper = {{"manhole", (*exits)[i]}};
      JsonFields f(wrapper, "$.exits[" + std::to_string(i) + "]", file_name, diagnostics);
      if (auto id = reader.manhole(f, "manhole", Need::kRequired)) m.exits.push_back(*id);
    }
  } else {
    for (ManholeId id : map.manhole_ids()) {
      if (map.manhole(id).exit) m.exits.push_back(id);
    }
  }
  m.battery_reserve_fraction = root.number("battery_reserve", Need::kOptional).value_or(0.2);
  if (!(m.battery_reserve_fraction >= 0 && m.battery_reserve_fraction < 1)) {
    diagnostics.error(root.where("battery_reserve"),
                      "must be a fraction from 0 to below 1, got " +
                          detail::format_double(m.battery_reserve_fraction));
  }
  if (const json* closed = root.member("closed", Need::kOptional)) reader.closed(*closed, m);
  check_tasks(m, file_name, diagnostics);
  if (diagnostics.has_errors())
    return Error{ErrorCode::kInvalidMission, diagnostics.error_summary()};
  return m;
}

}  // namespace sewerplan

namespace sewerplan {

Result<Mission> read_mission(const std::filesystem::path& path, const SewerMap& map,
                             Diagnostics& diagnostics) {
  Result<std::string> text = read_text_file(path);
  if (!text.has_value()) return text.error();
  return read_mission_json(*text, path.string(), map, diagnostics);
}

}  // namespace sewerplan
