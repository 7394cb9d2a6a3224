// SPDX-License-Identifier: MIT
// Writing plans in the paper's text form. Reading them is plan_parse.cc.
#include "sewerplan/domain/plan_text.h"

#include <type_traits>

#include "object_names.h"

namespace sewerplan::domain {
namespace {

using detail::name_of;

// " NAME" when the mission has more than one task like this one at its place, else nothing.
std::string task_token(const Mission& mission, TaskId task, std::size_t alike) {
  if (alike <= 1 || !detail::in_mission(mission, task)) return {};
  return " " + mission.task(task).name;
}

std::size_t alike_in_pipe(const Mission& mission, TaskKind kind, PipeId pipe) {
  return detail::tasks_in_pipe(mission, kind, pipe).size();
}

std::string drive_manhole_text(const DriveManhole& s, const SewerMap& map) {
  std::string text = "DRIVE_MANHOLE_TYPE_";
  if (!detail::in_map(map, s.manhole)) {
    return text + "?_FROM_" + std::to_string(to_paper_number(s.from)) + "_TO_" +
           std::to_string(to_paper_number(s.to)) + " " + name_of(map, s.manhole);
  }
  const Manhole& m = map.manhole(s.manhole);
  text = "DRIVE_MANHOLE_" + detail::paper_type(m) + "_FROM_" +
         std::to_string(to_paper_number(s.from)) + "_TO_" + std::to_string(to_paper_number(s.to)) +
         " " + m.name;
  for (const Slot& slot : map.slots(s.manhole)) text += " " + map.pipe(slot.pipe).name;
  return text;
}

std::string inspect_text(const InspectPipe& s, const SewerMap& map, const Mission& mission) {
  std::string text = "INSPECT_PIPE " + name_of(map, s.pipe);
  if (s.finish_end) {
    if (!detail::in_map(map, s.pipe) || *s.finish_end > 1) {
      text += " ?";
    } else {
      const PipeEnd& end = map.pipe(s.pipe).ends[*s.finish_end];
      text += " " + (end.manhole ? map.manhole(*end.manhole).name : std::string("-"));
    }
  }
  return text + task_token(mission, s.task, alike_in_pipe(mission, TaskKind::kInspectPipe, s.pipe));
}

}  // namespace

std::string format_step(const PlanStep& step, const SewerMap& map, const Mission& mission) {
  return std::visit(
      [&](const auto& s) -> std::string {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, DrivePipeToManhole>) {
          return "DRIVE_PIPE_TO_MANHOLE " + name_of(map, s.pipe) + " " + name_of(map, s.manhole);
        } else if constexpr (std::is_same_v<T, DriveManhole>) {
          return drive_manhole_text(s, map);
        } else if constexpr (std::is_same_v<T, EnterPipe>) {
          return "ENTER_PIPE " + name_of(map, s.manhole) + " " + name_of(map, s.pipe);
        } else if constexpr (std::is_same_v<T, TakeWaterSample>) {
          return "TAKE_WATER_SAMPLE " + name_of(map, s.pipe) +
                 task_token(mission, s.task,
                            alike_in_pipe(mission, TaskKind::kTakeWaterSample, s.pipe));
        } else if constexpr (std::is_same_v<T, InspectPipe>) {
          return inspect_text(s, map, mission);
        } else if constexpr (std::is_same_v<T, GoToPoint>) {
          return "GO_TO_POINT " + name_of(map, s.pipe) +
                 task_token(mission, s.task, alike_in_pipe(mission, TaskKind::kGoTo, s.pipe));
        } else {
          static_assert(std::is_same_v<T, GoToManhole>);
          return "GO_TO_MANHOLE " + name_of(map, s.manhole) +
                 task_token(mission, s.task, detail::go_to_tasks_at(mission, s.manhole).size());
        }
      },
      step);
}

std::string format_plan(const Plan& plan, const SewerMap& map, const Mission& mission) {
  std::string text;
  for (const PlanStep& step : plan.steps) text += format_step(step, map, mission) + '\n';
  return text;
}

std::string_view step_kind(const PlanStep& step) {
  return std::visit(
      [](const auto& s) -> std::string_view {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, DrivePipeToManhole>) {
          return "drive_pipe_to_manhole";
        } else if constexpr (std::is_same_v<T, DriveManhole>) {
          return "drive_manhole";
        } else if constexpr (std::is_same_v<T, EnterPipe>) {
          return "enter_pipe";
        } else if constexpr (std::is_same_v<T, TakeWaterSample>) {
          return "take_water_sample";
        } else if constexpr (std::is_same_v<T, InspectPipe>) {
          return "inspect_pipe";
        } else if constexpr (std::is_same_v<T, GoToPoint>) {
          return "go_to_point";
        } else {
          static_assert(std::is_same_v<T, GoToManhole>);
          return "go_to_manhole";
        }
      },
      step);
}

}  // namespace sewerplan::domain
