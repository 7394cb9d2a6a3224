// SPDX-License-Identifier: MIT
#include "object_names.h"

#include <charconv>
#include <cstdio>

namespace sewerplan::domain::detail {

bool in_map(const SewerMap& map, ManholeId id) { return id.index() < map.manhole_count(); }
bool in_map(const SewerMap& map, PipeId id) { return id.index() < map.pipe_count(); }
bool in_mission(const Mission& mission, TaskId id) { return id.index() < mission.tasks.size(); }

std::string name_of(const SewerMap& map, ManholeId id) {
  return in_map(map, id) ? map.manhole(id).name : "#" + std::to_string(id.value());
}

std::string name_of(const SewerMap& map, PipeId id) {
  return in_map(map, id) ? map.pipe(id).name : "#" + std::to_string(id.value());
}

std::string name_of(const Mission& mission, TaskId id) {
  return in_mission(mission, id) ? mission.task(id).name : "#" + std::to_string(id.value());
}

std::string describe_task(const Mission& mission, TaskId id) {
  if (!in_mission(mission, id)) return "task #" + std::to_string(id.value());
  const Task& task = mission.task(id);
  return "task '" + task.name + "' (" + std::string(to_string(task.kind)) + ")";
}

std::optional<PipeId> task_pipe(const Task& task) {
  if (const auto* spot = std::get_if<PipeSpot>(&task.place)) return spot->pipe;
  return std::nullopt;
}

std::optional<ManholeId> task_manhole(const Task& task) {
  if (const auto* m = std::get_if<ManholeId>(&task.place)) return *m;
  return std::nullopt;
}

std::optional<double> task_offset_m(const Task& task, const SewerMap& map) {
  const auto* spot = std::get_if<PipeSpot>(&task.place);
  if (spot == nullptr || task.kind == TaskKind::kInspectPipe) return std::nullopt;
  if (spot->offset_m) return spot->offset_m;
  if (spot->point && spot->point->index() < map.point_count()) {
    return map.point(*spot->point).offset_m;
  }
  return std::nullopt;
}

std::vector<TaskId> tasks_in_pipe(const Mission& mission, TaskKind kind, PipeId pipe) {
  std::vector<TaskId> found;
  for (TaskId id : mission.task_ids()) {
    const Task& task = mission.task(id);
    if (task.kind == kind && task_pipe(task) == pipe) found.push_back(id);
  }
  return found;
}

std::vector<TaskId> go_to_tasks_at(const Mission& mission, ManholeId m) {
  std::vector<TaskId> found;
  for (TaskId id : mission.task_ids()) {
    const Task& task = mission.task(id);
    if (task.kind == TaskKind::kGoTo && task_manhole(task) == m) found.push_back(id);
  }
  return found;
}

std::string fixed(double v, int decimals) {
  char buffer[64];
  const int n = std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  if (n < 0 || static_cast<std::size_t>(n) >= sizeof buffer) return shortest(v);
  return std::string(buffer, static_cast<std::size_t>(n));
}

std::string shortest(double v) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
  if (ec != std::errc{}) return "?";
  return std::string(buffer, end);
}

std::string paper_type(const Manhole& m) {
  std::string text = "TYPE_" + std::to_string(m.slot_count);
  if (m.variant) text += std::string("_TYPE_") + *m.variant;
  return text;
}

char ascii_upper(char c) { return c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c; }

std::string ascii_upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = ascii_upper(c);
  return out;
}

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (ascii_upper(a[i]) != ascii_upper(b[i])) return false;
  }
  return true;
}

}  // namespace sewerplan::domain::detail
