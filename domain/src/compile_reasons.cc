// SPDX-License-Identifier: MIT
#include "compile_reasons.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "sewerplan/core/message_text.h"
#include "sewerplan/domain/robot_state.h"

#include "reach_barriers.h"

namespace sewerplan::domain::detail {
namespace {

std::string fixed(double v, int digits) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << v;
  return out.str();
}

// What the diagnosis found in the way, after a "no route" (empty if only the battery is).
std::string in_the_way(const ReachDiagnosis& d) {
  if (d.reachable) return {};
  if (d.barriers.empty()) return ": the network does not connect them";
  return ": in the way: " + barrier_list(d);
}

}  // namespace

std::vector<Node> CompileReasons::exit_nodes() const {
  std::vector<Node> nodes;
  for (ManholeId e : mission_.exits) {
    nodes.push_back(graph_.in_manhole(e));
    for (std::uint16_t s = 0; s < graph_.map().manhole(e).slot_count; ++s) {
      nodes.push_back(graph_.at_slot(e, SlotIndex{s}));
    }
  }
  return nodes;
}

const ReachDiagnoser& CompileReasons::from_origin() const {
  if (from_origin_ == nullptr) {
    from_origin_ =
        std::make_unique<ReachDiagnoser>(graph_, mission_, reachable_from(graph_, {&origin_, 1}));
  }
  return *from_origin_;
}

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

std::string CompileReasons::unreachable(const Task& task, const std::vector<Node>& keys) const {
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
  // Issue 30: name what stands in the way, the limit and its object, not only the limits.
  std::vector<Node> targets;
  for (Node n : keys) {
    if (at_task(task, n)) targets.push_back(n);
  }
  const ReachDiagnosis d = from_origin().diagnose(targets);
  if (d.reachable) {
    return "reaching " + describe(task.place, map) + " from " + origin() + " needs more than the " +
           energy(bound_) + " available";
  }
  return "no route from " + origin() + " reaches " + describe(task.place, map) + " within " +
         limits() + in_the_way(d);
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
  if (reach == kInfiniteCost) return unreachable(task, keys);
  if (reach > bound_) {
    return "reaching " + place + " needs at least " + energy(reach) + ", but " + energy(bound_) +
           " are available";
  }
  if (ends_at_exit && via == kInfiniteCost) {
    std::vector<Node> from;
    for (std::size_t e = 0; e < keys.size(); ++e) {
      if (at_task(task, keys[e]) && dist[e] != kInfiniteCost) from.push_back(keys[e]);
    }
    const ReachDiagnosis d =
        ReachDiagnoser(graph_, mission_, reachable_from(graph_, from)).diagnose(exit_nodes());
    if (d.reachable) {
      return "going to " + place + " and on to an exit needs more than the " + energy(bound_) +
             " available";
    }
    return "no exit can be reached from " + place + in_the_way(d);
  }
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
    // The route searches stop at the battery, so "not found" may be either: tell which (issue
    // 30). On the reserve itself (the Replanner's last way out) there is no reserve to be above.
    const ReachDiagnosis d = from_origin().diagnose(exit_nodes());
    const std::string what = "\n  - no exit (" + names + ") can be reached from " + origin();
    if (!d.reachable) return what + " within " + limits() + in_the_way(d);
    const bool reserve = mission_.battery_reserve_fraction > 0;
    return what + " on the " + energy(bound_) + (reserve ? " left above the reserve" : " left") +
           ": every route to one needs more";
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
