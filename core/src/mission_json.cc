// SPDX-License-Identifier: MIT
#include <algorithm>
#include <map>
#include <set>

#include "sewerplan/core/enum_names.h"
#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/message_text.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/text_file.h"

#include "profile_json.h"

namespace sewerplan {
namespace {

// A task's "type": a TaskKind's name (written by mission_text.cc through to_string), or
// "inspect_area", which a file may hold and which reads as one kInspectPipe task per pipe.
constexpr detail::EnumNames<TaskKind, 3> kTaskKinds{{
    {TaskKind::kGoTo, "go_to"},
    {TaskKind::kInspectPipe, "inspect_pipe"},
    {TaskKind::kTakeWaterSample, "take_water_sample"},
}};
static_assert(detail::distinct(kTaskKinds));
constexpr std::string_view kInspectArea = "inspect_area";
static_assert(!detail::value_of(kTaskKinds, kInspectArea));

using Need = JsonFields::Need;

// Resolves names against the map; each failure is reported at the field that named it.
class MissionReader {
 public:
  // `root`: the mission's JSON path ("$" in a mission file).
  MissionReader(const SewerMap& map, std::string root, std::string_view file, Diagnostics& d)
      : map_(map), root_(std::move(root)), file_(file), d_(d) {}

  std::optional<ManholeId> manhole_named(const std::string& name, const std::string& where) {
    auto id = map_.find_manhole(name);
    if (!id) d_.error(where, "unknown manhole " + input_quoted(name));
    return id;
  }

  std::optional<PipeId> pipe_named(const std::string& name, const std::string& where) {
    auto id = map_.find_pipe(name);
    if (!id) d_.error(where, "unknown pipe " + input_quoted(name));
    return id;
  }

  std::optional<ManholeId> manhole(JsonFields& f, std::string_view key) {
    auto name = f.string(key);
    return name ? manhole_named(*name, f.where(key)) : std::nullopt;
  }

  std::optional<PipeId> pipe(JsonFields& f, std::string_view key) {
    auto name = f.string(key);
    return name ? pipe_named(*name, f.where(key)) : std::nullopt;
  }

  // Every element of `array` (at `path`) names a pipe.
  std::vector<PipeId> pipes(JsonArray array, const std::string& path) {
    std::vector<PipeId> ids;
    std::size_t i = 0;
    for (JsonElement e : array) {
      const std::string where = file_ + ":" + indexed(path, i++);
      auto name = string_element(e, where, d_);
      if (!name) continue;
      if (auto id = pipe_named(*name, where)) ids.push_back(*id);
    }
    return ids;
  }

  std::optional<Place> place(JsonElement j, const std::string& path) {
    JsonFields f(j, path, file_, d_);
    f.reject_unknown({"manhole", "pipe", "point", "offset_m"});
    const int given = int{f.has("manhole")} + int{f.has("pipe")} + int{f.has("point")};
    if (given != 1) {
      d_.error(f.where(), "a place names exactly one of \"manhole\", \"pipe\" or \"point\"");
      return std::nullopt;
    }
    if (f.has("manhole")) return manhole(f, "manhole");
    if (f.has("point")) return point(f);
    auto id = pipe(f, "pipe");
    if (!id) return std::nullopt;
    PipeSpot spot{*id, f.number("offset_m", Need::kOptional), std::nullopt};
    const double length = map_.pipe(*id).length_m;
    if (spot.offset_m && !(*spot.offset_m >= 0 && *spot.offset_m <= length)) {
      d_.error(f.where("offset_m"), "offset " + format_double(*spot.offset_m) +
                                        " m is outside pipe " + map_.pipe(*id).name + " (0 to " +
                                        format_double(length) + " m)");
    }
    return spot;
  }

  void tasks(JsonArray array, std::vector<Task>& out) {
    std::size_t i = 0;
    for (JsonElement t : array) {
      task(t, indexed(root_ + ".tasks", i), i, out);
      ++i;
    }
  }

  void closed(JsonElement j, Mission& m) {
    JsonFields f(j, root_ + ".closed", file_, d_);
    f.reject_unknown({"pipes", "passages", "blockages"});
    if (auto pipes_array = f.array("pipes", Need::kOptional)) {
      m.closed_pipes = pipes(*pipes_array, root_ + ".closed.pipes");
    }
    if (auto passages = f.array("passages", Need::kOptional)) {
      std::size_t i = 0;
      for (JsonElement p : *passages) passage(p, indexed(root_ + ".closed.passages", i++), m);
    }
    if (auto blockages = f.array("blockages", Need::kOptional)) {
      std::size_t i = 0;
      for (JsonElement b : *blockages) blockage(b, indexed(root_ + ".closed.blockages", i++), m);
    }
  }

  void blockage(JsonElement j, const std::string& path, Mission& m) {
    JsonFields f(j, path, file_, d_);
    f.reject_unknown({"pipe", "offset_m"});
    auto name = f.string("pipe");
    auto offset = f.number("offset_m");
    if (!name || !offset) return;
    const auto id = map_.find_pipe(*name);
    if (!id) {
      d_.error(f.where("pipe"), "unknown pipe " + input_quoted(*name));
      return;
    }
    const double length = map_.pipe(*id).length_m;
    if (!(*offset >= 0 && *offset <= length)) {
      d_.error(f.where("offset_m"), "pipe " + *name + " is " + format_double(length) +
                                        " m long, got an offset of " + format_double(*offset) +
                                        " m");
      return;
    }
    m.blockages.push_back({*id, *offset});
  }

  // "exits": an array of manhole names, "map" (the manholes marked exit in the map; also the
  // default) or "all" (every manhole with a pipe: imported networks rarely say which are usable).
  void exit_choice(std::optional<JsonElement> exits, Mission& m) {
    std::string_view choice = "map";
    if (exits && exits->is_array()) return this->exits(exits->get_array().value_unsafe(), m);
    if (exits && (!exits->is_string() || (exits->get_string().value_unsafe() != "map" &&
                                          exits->get_string().value_unsafe() != "all"))) {
      d_.error(
          file_ + ":" + root_ + ".exits",
          "expected an array of manhole names, \"map\" or \"all\", got " + describe_json(*exits));
      return;
    }
    if (exits) choice = exits->get_string().value_unsafe();
    for (ManholeId id : map_.manhole_ids()) {
      const Manhole& manhole = map_.manhole(id);
      if (choice == "all" ? manhole.slot_count > 0 : manhole.exit) m.exits.push_back(id);
    }
  }

  void exits(JsonArray array, Mission& m) {
    std::size_t i = 0;
    for (JsonElement e : array) {
      const std::string where = file_ + ":" + indexed(root_ + ".exits", i++);
      auto name = string_element(e, where, d_);
      if (!name) continue;
      if (auto id = manhole_named(*name, where)) m.exits.push_back(*id);
    }
  }

 private:
  std::optional<Place> point(JsonFields& f) {
    auto name = f.string("point");
    if (!name) return std::nullopt;
    auto id = map_.find_point(*name);
    if (!id) {
      d_.error(f.where("point"), "unknown inspection point " + input_quoted(*name));
      return std::nullopt;
    }
    const InspectionPoint& p = map_.point(*id);
    return PipeSpot{p.pipe, p.offset_m, id};
  }

  void task(JsonElement j, const std::string& path, std::size_t index, std::vector<Task>& out) {
    JsonFields f(j, path, file_, d_);
    f.reject_unknown({"name", "type", "at", "pipe", "pipes", "final"});
    const std::string name =
        f.string("name", Need::kOptional).value_or("task-" + std::to_string(index + 1));
    const bool final = f.boolean("final", Need::kOptional).value_or(false);
    auto type = f.string("type");
    if (!type) return;
    const std::optional<TaskKind> kind = detail::value_of(kTaskKinds, *type);
    if (kind == TaskKind::kGoTo || kind == TaskKind::kTakeWaterSample) {
      auto at = f.member("at");
      if (!at) return;
      auto where = place(*at, path + ".at");
      if (!where) return;
      if (kind == TaskKind::kTakeWaterSample && std::holds_alternative<ManholeId>(*where)) {
        d_.error(f.where("at"),
                 "task " + name + ": a water sample is taken in a pipe, not in a manhole");
        return;
      }
      out.push_back({name, *kind, *where, final});
    } else if (kind == TaskKind::kInspectPipe) {
      if (auto id = pipe(f, "pipe")) {
        out.push_back({name, TaskKind::kInspectPipe, PipeSpot{*id, {}, {}}, final});
      }
    } else if (*type == kInspectArea) {
      if (final) d_.error(f.where("final"), "task " + name + ": an area cannot be the final task");
      auto array = f.array("pipes");
      if (!array) return;
      for (PipeId id : pipes(*array, path + ".pipes")) {
        out.push_back(
            {name + "/" + map_.pipe(id).name, TaskKind::kInspectPipe, PipeSpot{id, {}, {}}, false});
      }
    } else {
      d_.error(f.where("type"), "unknown task type " + input_quoted(*type) + " (" +
                                    detail::names_joined(kTaskKinds) + ", " +
                                    std::string(kInspectArea) + ")");
    }
  }

  void passage(JsonElement j, const std::string& path, Mission& m) {
    JsonFields f(j, path, file_, d_);
    f.reject_unknown({"manhole", "from_slot", "to_slot"});
    auto id = manhole(f, "manhole");
    auto from = f.number("from_slot");
    auto to = f.number("to_slot");
    if (!id || !from || !to) return;
    const auto slots = static_cast<double>(map_.manhole(*id).slot_count);
    for (auto [key, v] : {std::pair{"from_slot", *from}, std::pair{"to_slot", *to}}) {
      if (!(v >= 1 && v <= slots && v == static_cast<double>(static_cast<int>(v)))) {
        d_.error(f.where(key), "manhole " + map_.manhole(*id).name + " has slots 1 to " +
                                   format_double(slots) + ", got " + format_double(v));
        return;
      }
    }
    m.closed_passages.push_back({*id, SlotIndex{static_cast<std::uint16_t>(*from - 1)},
                                 SlotIndex{static_cast<std::uint16_t>(*to - 1)}});
  }

  const SewerMap& map_;
  std::string root_;
  std::string file_;
  Diagnostics& d_;
};

// `where`: "file:" and the mission's JSON path.
void check_tasks(const Mission& m, const std::string& where, bool exits_unreadable,
                 Diagnostics& d) {
  std::set<std::string> names;
  std::size_t finals = 0;
  for (std::size_t i = 0; i < m.tasks.size(); ++i) {
    if (!names.insert(m.tasks[i].name).second) {
      d.error(where + ".tasks", "duplicate task name " + input_quoted(m.tasks[i].name));
    }
    finals += m.tasks[i].final ? 1U : 0U;
  }
  if (finals > 1) d.error(where + ".tasks", "more than one task is marked final");
  // One inspection of a pipe covers it; two would be indistinguishable in a plan.
  std::map<PipeId, std::string> inspected;
  for (const Task& t : m.tasks) {
    if (t.kind != TaskKind::kInspectPipe) continue;
    const PipeId pipe = std::get<PipeSpot>(t.place).pipe;
    auto [it, added] = inspected.emplace(pipe, t.name);
    if (!added) {
      d.error(where + ".tasks",
              "tasks '" + it->second + "' and '" + t.name + "' both inspect the same pipe");
    }
  }
  if (m.exits.empty() && finals == 0 && !exits_unreadable) {
    d.error(
        where + ".exits",
        "the mission has no exit: name \"exits\", mark exit manholes in the map, or mark a task "
        "final");
  }
}

}  // namespace

const Task* Mission::final_task() const {
  auto it = std::find_if(tasks.begin(), tasks.end(), [](const Task& t) { return t.final; });
  return it == tasks.end() ? nullptr : &*it;
}

std::optional<TaskId> Mission::final_task_id() const {
  for (TaskId id : task_ids()) {
    if (tasks[id.index()].final) return id;
  }
  return std::nullopt;
}

const Task& Mission::task(TaskId id) const {
  SEWER_CHECK(id.index() < tasks.size(), "task id does not belong to this mission");
  return tasks[id.index()];
}

std::string_view to_string(TaskKind kind) { return detail::name_of(kTaskKinds, kind); }

Result<Mission> read_mission_json(std::string_view text, const std::string& file_name,
                                  const SewerMap& map, Diagnostics& diagnostics) {
  const Diagnostics::Mark before = diagnostics.mark();
  auto doc = JsonDocument::parse(text, file_name, diagnostics);
  if (!doc) return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  return read_mission_value(doc->root(), "$", file_name, map, diagnostics);
}

Result<Mission> read_mission_value(const JsonElement& value, const std::string& path,
                                   const std::string& file_name, const SewerMap& map,
                                   Diagnostics& diagnostics) {
  const Diagnostics::Mark before = diagnostics.mark();
  JsonFields root(value, path, file_name, diagnostics);
  root.reject_unknown({"format", "version", "name", "profile", "start", "tasks", "exits",
                       "battery_reserve", "closed"});
  if (auto format = root.string("format"); format && *format != kMissionJsonFormat) {
    diagnostics.error(root.where("format"), "expected \"" + std::string(kMissionJsonFormat) +
                                                "\", got " + input_quoted(*format));
  }
  if (auto version = root.number("version"); version && *version != kMissionJsonVersion) {
    diagnostics.error(root.where("version"), "unsupported version " + format_double(*version));
  }
  MissionReader reader(map, path, file_name, diagnostics);
  Mission m;
  m.name = root.string("name", Need::kOptional).value_or("mission");
  if (auto profile = root.member("profile", Need::kOptional)) {
    auto p = detail::read_profile_value(*profile, path + ".profile", file_name, diagnostics);
    if (p) m.profile = *p;
  } else {
    m.profile = *builtin_profile("makro-1.1");
  }
  if (auto start = root.member("start")) {
    if (auto p = reader.place(*start, path + ".start")) m.start = *p;
  }
  if (auto tasks = root.array("tasks")) reader.tasks(*tasks, m.tasks);
  const std::size_t errors_before_exits = diagnostics.error_count();
  reader.exit_choice(root.member("exits", Need::kOptional), m);
  const bool exits_unreadable = diagnostics.error_count() > errors_before_exits;
  m.battery_reserve_fraction = root.number("battery_reserve", Need::kOptional).value_or(0.2);
  if (!(m.battery_reserve_fraction >= 0 && m.battery_reserve_fraction < 1)) {
    diagnostics.error(root.where("battery_reserve"), "must be a fraction from 0 to below 1, got " +
                                                         format_double(m.battery_reserve_fraction));
  }
  if (auto closed = root.member("closed", Need::kOptional)) reader.closed(*closed, m);
  check_tasks(m, file_name + ":" + path, exits_unreadable, diagnostics);
  if (diagnostics.has_errors_since(before)) {
    return Error{ErrorCode::kInvalidMission, diagnostics.error_summary(before)};
  }
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
