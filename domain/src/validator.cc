// SPDX-License-Identifier: MIT
// The start check, the goal of docs/domain.md, and whole-plan validation.
#include "sewerplan/domain/validator.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

#include "sewerplan/domain/plan_text.h"

#include "object_names.h"

namespace sewerplan::domain {
namespace {

std::optional<std::string> position_problem(const SewerMap& map, const RobotPosition& position) {
  if (const auto* m = std::get_if<InManhole>(&position)) {
    if (!detail::in_map(map, m->manhole))
      return "manhole #" + std::to_string(m->manhole.value()) + " is not in the map";
  } else if (const auto* s = std::get_if<AtSlot>(&position)) {
    if (!detail::in_map(map, s->manhole))
      return "manhole #" + std::to_string(s->manhole.value()) + " is not in the map";
    const Manhole& manhole = map.manhole(s->manhole);
    if (s->slot.value() >= manhole.slot_count) {
      return manhole.name + " has slots 1 to " + std::to_string(manhole.slot_count) + ", not " +
             std::to_string(to_paper_number(s->slot));
    }
  } else {
    const auto& p = std::get<InPipe>(position);
    if (!detail::in_map(map, p.pipe))
      return "pipe #" + std::to_string(p.pipe.value()) + " is not in the map";
    const Pipe& pipe = map.pipe(p.pipe);
    if (!(p.offset_m >= 0 && p.offset_m <= pipe.length_m)) {
      return "offset " + detail::shortest(p.offset_m) + " m is outside pipe " + pipe.name +
             " (0 to " + detail::shortest(pipe.length_m) + " m)";
    }
  }
  return std::nullopt;
}

// The final task's goal when it is about where the robot ends: a go-to of a whole pipe or a
// manhole. Empty for any other final task, which must be done by an action.
std::optional<std::string> final_place_problem(const Task& task, const RobotPosition& position,
                                               const SewerMap& map) {
  if (auto m = detail::task_manhole(task)) {
    if (manhole_of(position) == *m) return std::nullopt;
    return "the robot is not at manhole " + map.manhole(*m).name + " for the final task '" +
           task.name + "'";
  }
  const auto& spot = std::get<PipeSpot>(task.place);
  const auto* in = std::get_if<InPipe>(&position);
  if (in != nullptr && in->pipe == spot.pipe) return std::nullopt;
  return "the robot is not in pipe " + map.pipe(spot.pipe).name + " for the final task '" +
         task.name + "'";
}

bool is_place_goal(const Task& task) {
  if (task.kind != TaskKind::kGoTo) return false;
  const auto* spot = std::get_if<PipeSpot>(&task.place);
  return spot == nullptr || (!spot->offset_m && !spot->point);
}

}  // namespace

std::optional<std::string> start_problem(const SewerMap& map, const Mission& mission,
                                         const MissionProgress& start) {
  if (start.done.size() != mission.tasks.size()) {
    return "the start has " + std::to_string(start.done.size()) + " task flags for " +
           std::to_string(mission.tasks.size()) + " tasks";
  }
  if (!(std::isfinite(start.energy_used_wh) && start.energy_used_wh >= 0)) {
    return "energy used " + detail::shortest(start.energy_used_wh) + " Wh is not a number >= 0";
  }
  for (const Task& task : mission.tasks) {
    const bool in_map = std::visit(
        [&map](const auto& place) {
          using T = std::decay_t<decltype(place)>;
          if constexpr (std::is_same_v<T, ManholeId>) {
            return detail::in_map(map, place);
          } else {
            return detail::in_map(map, place.pipe);
          }
        },
        task.place);
    if (!in_map) return "task '" + task.name + "' is at a place that is not in the map";
  }
  return position_problem(map, start.position);
}

std::optional<std::string> PlanReplay::unmet_goal() const {
  const std::optional<TaskId> final = mission_->final_task_id();
  for (TaskId id : mission_->task_ids()) {
    if (id != final && !progress_.done[id.index()]) {
      return detail::describe_task(*mission_, id) + " is not done";
    }
  }
  if (final) {
    const Task& task = mission_->task(*final);
    if (is_place_goal(task)) return final_place_problem(task, progress_.position, *map_);
    if (progress_.done[final->index()]) return std::nullopt;
    return "the final " + detail::describe_task(*mission_, *final) + " is not done";
  }
  const std::optional<ManholeId> at = manhole_of(progress_.position);
  const auto& exits = mission_->exits;
  if (at && std::find(exits.begin(), exits.end(), *at) != exits.end()) return std::nullopt;
  std::string names;
  for (ManholeId e : exits) names += (names.empty() ? "" : ", ") + detail::name_of(*map_, e);
  return "the robot is not at an exit (" +
         (names.empty() ? "the mission has none" : "exits: " + names) + ")";
}

std::ostream& operator<<(std::ostream& os, const ValidationReport& report) {
  if (!report.valid) return os << "invalid: " << report.error;
  return os << "valid: " << report.step_costs_s.size()
            << (report.step_costs_s.size() == 1 ? " step, " : " steps, ")
            << detail::fixed(report.total_cost_s, 1) << " s, " << detail::fixed(report.energy_wh, 1)
            << " Wh";
}

ValidationReport validate_plan(const Plan& plan, const SewerMap& map, const Mission& mission,
                               const MissionProgress& start) {
  ValidationReport report;
  report.end = start;
  if (auto problem = start_problem(map, mission, start)) {
    report.error = "invalid start: " + *problem;
    return report;
  }
  PlanReplay replay(map, mission, start);
  for (std::size_t i = 0; i < plan.steps.size(); ++i) {
    Result<double> cost = replay.apply(plan.steps[i]);
    if (!cost.has_value()) {
      report.failed_step = i;
      report.error = "step " + std::to_string(i + 1) + " (" +
                     format_step(plan.steps[i], map, mission) + "): " + cost.error().message;
      break;
    }
    report.step_costs_s.push_back(*cost);
    report.total_cost_s += *cost;
  }
  report.energy_wh = replay.energy_wh();
  report.end = replay.progress();
  if (report.failed_step) return report;
  if (auto unmet = replay.unmet_goal()) {
    report.error = "goal not reached: " + *unmet;
    return report;
  }
  report.valid = true;
  return report;
}

ValidationReport validate_plan(const Plan& plan, const SewerMap& map, const Mission& mission) {
  return validate_plan(plan, map, mission, initial_progress(mission, map));
}

}  // namespace sewerplan::domain
