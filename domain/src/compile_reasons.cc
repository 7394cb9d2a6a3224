// SPDX-License-Identifier: MIT
#include "compile_reasons.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "sewerplan/core/message_text.h"
#include "sewerplan/domain/robot_state.h"

namespace sewerplan::domain::detail {
namespace {

std::string fixed(double v, int digits) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << v;
  return out.str();
}

}  // namespace

std::string CompileReasons::energy(Cost cost) const {
  return fixed(mission_.profile.energy_wh(to_seconds(cost)), 1) + " Wh";
}

std::string CompileReasons::limits() const {
  const RobotProfile& p = mission_.profile;
  return p.name + "'s limits (pipes " + fixed(p.min_pipe_diameter_m, 2) + "-" +
         fixed(p.max_pipe_diameter_m, 2) + " m, turns <= " + fixed(p.max_turn_deg, 0) +
         " deg, steps <= " + fixed(p.max_step_m, 2) + " m) and the mission's closures";
}

std::string CompileReasons::origin() const {
  const SewerMap& map = graph_.map();
  // Issue 30: after the robot has moved, "from the start" named the wrong place.
  const bool at_start = !(progress_.energy_used_wh > 0) &&
                        progress_.position == initial_progress(mission_, map).position;
  return (at_start ? "the start (" : "here (") + describe(progress_.position, map) + ")";
}

bool CompileReasons::at_task(const Task& task, Node n) const {
  if (const auto* m = std::get_if<ManholeId>(&task.place)) {
    return manhole_of(graph_.position(n)) == *m;
  }
  return graph_.pipe_of(n) == std::get<PipeSpot>(task.place).pipe;
}

std::string CompileReasons::unreachable(const Task& task) const {
  const SewerMap& map = graph_.map();
  if (const auto* spot = std::get_if<PipeSpot>(&task.place)) {
    const Pipe& pipe = map.pipe(spot->pipe);
    const RobotProfile& p = mission_.profile;
    if (std::find(mission_.closed_pipes.begin(), mission_.closed_pipes.end(), spot->pipe) !=
        mission_.closed_pipes.end()) {
      return "pipe " + pipe.name + " is closed";
    }
    for (const Blockage& b : mission_.blockages) {
      if (b.pipe == spot->pipe &&
          (task.kind == TaskKind::kInspectPipe || !graph_.pipe_drivable(spot->pipe))) {
        return "pipe " + pipe.name + " is blocked at " + fixed(b.offset_m, 2) + " m";
      }
    }
    if (!graph_.pipe_drivable(spot->pipe)) {
      const LimitText t = limit_text_fixed(pipe.diameter_m, pipe.diameter_m < p.min_pipe_diameter_m
                                                                ? p.min_pipe_diameter_m
                                                                : p.max_pipe_diameter_m);
      const bool narrow = pipe.diameter_m < p.min_pipe_diameter_m;
      return "pipe " + pipe.name + " is " + t.value + " m, outside " + p.name + "'s " +
             (narrow ? t.limit : fixed(p.min_pipe_diameter_m, 2)) + "-" +
             (narrow ? fixed(p.max_pipe_diameter_m, 2) : t.limit) + " m";
    }
  }
  return "no route from " + origin() + " reaches " + describe(task.place, map) + " within " +
         limits();
}

std::string CompileReasons::task_reason(const Task& task, const std::vector<Node>& keys,
                                        const std::vector<Cost>& dist,
                                        const std::vector<Cost>& exit_dist,
                                        bool ends_at_exit) const {
  Cost reach = kInfiniteCost;
  Cost via = kInfiniteCost;  // to the task and on to an exit
  for (std::size_t e = 0; e < keys.size(); ++e) {
    if (!at_task(task, keys[e])) continue;
    reach = std::min(reach, dist[e]);
    if (ends_at_exit && dist[e] != kInfiniteCost && exit_dist[e] != kInfiniteCost) {
      via = std::min(via, dist[e] + exit_dist[e]);
    }
  }
  const std::string place = describe(task.place, graph_.map());
  if (reach == kInfiniteCost) return unreachable(task);
  if (reach > bound_) {
    return "reaching " + place + " needs at least " + energy(reach) + ", but " + energy(bound_) +
           " are available";
  }
  if (ends_at_exit && via == kInfiniteCost) return "no exit can be reached from " + place;
  if (ends_at_exit && via > bound_) {
    return "going to " + place + " and on to an exit needs at least " + energy(via) + ", but " +
           energy(bound_) + " are available";
  }
  return {};
}

std::string CompileReasons::fatal(const std::vector<Cost>& exit_dist, bool ends_at_exit) const {
  if (bound_ < 0) {
    return "\n  - the battery is spent: " + fixed(progress_.energy_used_wh, 1) +
           " Wh used, and the reserve must stay";
  }
  if (const auto* in = std::get_if<InPipe>(&progress_.position);
      in && !graph_.pipe_fits(in->pipe)) {
    const Pipe& pipe = graph_.map().pipe(in->pipe);
    const RobotProfile& p = mission_.profile;
    return "\n  - the robot starts in pipe " + pipe.name + ", which " + p.name +
           " cannot drive: " + fixed(pipe.diameter_m, 2) + " m, outside its " +
           fixed(p.min_pipe_diameter_m, 2) + "-" + fixed(p.max_pipe_diameter_m, 2) + " m";
  }
  if (!ends_at_exit) return {};
  const SewerMap& map = graph_.map();
  std::string names;
  for (std::size_t i = 0; i < mission_.exits.size() && i < 8; ++i) {
    names += (i == 0 ? "" : ", ") + map.manhole(mission_.exits[i]).name;
  }
  if (mission_.exits.size() > 8) names += ", ...";
  if (exit_dist[0] == kInfiniteCost) {
    // The route searches stop at the battery, so "not found" covers both: name both.
    // On the reserve itself (the Replanner's last way out) there is no reserve to be above.
    const bool reserve = mission_.battery_reserve_fraction > 0;
    return "\n  - no exit (" + names + ") can be reached from " + origin() + " on the " +
           energy(bound_) + (reserve ? " left above the reserve" : " left") + ", within " +
           limits();
  }
  if (exit_dist[0] > bound_) {
    return "\n  - reaching the nearest exit needs at least " + energy(exit_dist[0]) + ", but " +
           energy(bound_) + " are available";
  }
  return {};
}

std::string CompileReasons::explain(const std::vector<Node>& keys,
                                    const std::vector<TaskId>& pending,
                                    const std::vector<Cost>& dist,
                                    const std::vector<Cost>& exit_dist, bool ends_at_exit) const {
  // The battery and the start make everything else moot; an unreachable exit is listed last.
  if (bound_ < 0 || std::holds_alternative<InPipe>(progress_.position)) {
    const std::string why = fatal(exit_dist, false);
    if (!why.empty()) return why;
  }
  std::string out;
  for (TaskId t : pending) {
    const Task& task = mission_.task(t);
    const std::string why = task_reason(task, keys, dist, exit_dist, ends_at_exit);
    if (!why.empty()) {
      out += "\n  - task '" + task.name + "' (" + std::string(to_string(task.kind)) + "): " + why;
    }
  }
  return out + fatal(exit_dist, ends_at_exit);
}

}  // namespace sewerplan::domain::detail
