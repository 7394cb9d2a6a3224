// SPDX-License-Identifier: MIT
// The sewer compiler's contingency reserves: the battery to back out of a hazard and reach an
// exit another way, at two levels, and the ways out the stranding risk weighs
// (sewer_task_compiler.h; CompileOptions::contingency).
#include <algorithm>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "sewer_task_compiler.h"

namespace sewerplan::domain {

Cost SewerTaskCompiler::exit_need(Node from, PipeId first, std::optional<PipeId> second) {
  const auto key = std::make_tuple(from, first.value(), second ? second->value() + 1 : 0U);
  if (auto it = exit_need_.find(key); it != exit_need_.end()) return it->second;
  PositionGraph& graph = *result_.graph_;
  const bool first_was = graph.excluded(first);
  const bool second_was = second && graph.excluded(*second);
  graph.exclude_pipe(first, true);
  if (second) graph.exclude_pipe(*second, true);
  const std::optional<Node> exit = contingency_search_->run_to_nearest(from, exit_node(), bound_);
  Cost need = exit ? contingency_search_->distance(*exit) : kInfiniteCost;
  std::vector<Node> route;
  if (exit && !second) contingency_search_->path(*exit, route);
  if (second) graph.exclude_pipe(*second, second_was);
  if (!route.empty()) need = std::max(need, route_need(route, first));
  graph.exclude_pipe(first, first_was);
  exit_need_.emplace(key, need);
  return need;
}

SewerTaskCompiler::WayOut SewerTaskCompiler::way_out(Node from, PipeId first) {
  const auto key = std::make_pair(from, first.value());
  if (auto it = way_out_.find(key); it != way_out_.end()) return it->second;
  PositionGraph& graph = *result_.graph_;
  const bool first_was = graph.excluded(first);
  graph.exclude_pipe(first, true);
  const std::optional<Node> exit = contingency_search_->run_to_nearest(from, exit_node(), bound_);
  WayOut way;
  std::vector<Node> route;
  if (exit) {
    way.plain = contingency_search_->distance(*exit);
    contingency_search_->path(*exit, route);
  }
  graph.exclude_pipe(first, first_was);
  way.full = way.plain;
  double none = 1;
  std::vector<std::pair<std::uint32_t, double>> passed;
  for_each_step(graph, route, [&](Node u, Node v, Cost prefix) {
    const std::optional<PipeId> p = graph.pipe_of(u);
    const RobotPosition at = graph.position(v);
    const auto* slot = std::get_if<AtSlot>(&at);
    if (p && !graph.pipe_of(v) && slot != nullptr) {  // DRIVE_PIPE_TO_MANHOLE
      passed.clear();
      const double from_m = graph.offset_of(u);
      graph.hazards_between(
          *p, from_m, end_offset_m(map_.pipe(*p), map_.slot(slot->manhole, slot->slot).pipe_end),
          passed);
      double farthest = -1;
      for (const auto& [h, d] : passed) {
        none *= 1 - result_.hazard_probability_[h];
        farthest = std::max(farthest, d);
      }
      const std::size_t e = u == graph.pipe_end(*p, 0) ? 0 : u == graph.pipe_end(*p, 1) ? 1 : 2;
      if (farthest >= 0 && e != 2 && map_.pipe(*p).ends[e].manhole) {
        const PipeEnd& end = map_.pipe(*p).ends[e];
        const Cost out = exit_need(graph.at_slot(*end.manhole, end.slot), first, *p);
        if (out < kInfiniteCost) {
          way.full = std::max(way.full, prefix + to_cost(farthest / mission_.profile.speed_mps) +
                                            graph.drive_cost(farthest) + out);
        }
      }
    }
  });
  way.risk = 1 - none;
  way_out_.emplace(key, way);
  return way;
}

Cost SewerTaskCompiler::in_pipe_need(PipeId p, Node entry, double from, double to, Cost prefix,
                                     double speed_mps, std::optional<PipeId> blocked) {
  const PositionGraph& graph = *result_.graph_;
  const bool top = !blocked;
  const std::size_t noted = noted_.size();
  if (top) {
    graph.hazards_between(p, from, to, noted_);
    covered_.resize(noted_.size(), false);
    noted_need_.resize(noted_.size());
  }
  if (!contingency_) return 0;
  const std::optional<double> hazard = graph.farthest_hazard(p, from, to, &options_.insured);
  // At the first level every hazard noted gets its own need, insured or not (the battery to
  // back out from it: SewerTask::strand_risk weighs it against what the plan has left there);
  // at the second level only the insured ones ask for anything.
  if (!hazard && (!top || noted == noted_.size())) return 0;
  const std::size_t e = entry == graph.pipe_end(p, 0) ? 0 : entry == graph.pipe_end(p, 1) ? 1 : 2;
  if (e == 2 || !map_.pipe(p).ends[e].manhole) return 0;
  const PipeEnd& end = map_.pipe(p).ends[e];
  const Node back = graph.at_slot(*end.manhole, end.slot);
  const Cost out = blocked ? exit_need(back, *blocked, p) : exit_need(back, p, std::nullopt);
  if (out >= kInfiniteCost) return 0;
  const auto back_out = [&](double d) {
    return prefix + to_cost(d / speed_mps) + graph.drive_cost(d) + out;
  };
  if (top && noted < noted_.size()) {
    const WayOut way = way_out(back, p);
    for (std::size_t i = noted; way.plain < kInfiniteCost && i < noted_.size(); ++i) {
      const double d = noted_[i].second;
      const Cost there = prefix + to_cost(d / speed_mps) + graph.drive_cost(d);
      noted_need_[i] = {there + way.plain, there + way.full, way.risk};
    }
  }
  if (!hazard) return 0;
  const double d = std::abs(*hazard - from);
  // Backing out from the farthest insured hazard covers every nearer one too.
  for (std::size_t i = noted; top && i < noted_.size(); ++i) {
    covered_[i] = noted_[i].second <= d;
  }
  return back_out(d);
}

Cost SewerTaskCompiler::route_need(std::span<const Node> route, std::optional<PipeId> blocked) {
  const PositionGraph& graph = *result_.graph_;
  if (!contingency_) {
    // No reserve; the hazards the route passes are still noted, none covered.
    if (!blocked && graph.has_hazards()) note_route(route);
    return 0;
  }
  Cost need = 0;
  for_each_step(graph, route, [&](Node u, Node v, Cost prefix) {
    const std::optional<PipeId> p = graph.pipe_of(u);
    if (p && !graph.pipe_of(v)) {  // DRIVE_PIPE_TO_MANHOLE
      const RobotPosition to = graph.position(v);
      if (const auto* at = std::get_if<AtSlot>(&to)) {
        const Slot& slot = map_.slot(at->manhole, at->slot);
        need = std::max(need, in_pipe_need(*p, u, graph.offset_of(u),
                                           end_offset_m(map_.pipe(*p), slot.pipe_end), prefix,
                                           mission_.profile.speed_mps, blocked));
      }
    }
  });
  return need;
}

void SewerTaskCompiler::note_route(std::span<const Node> route) {
  const PositionGraph& graph = *result_.graph_;
  for (std::size_t i = 0; i + 1 < route.size(); ++i) {
    const std::optional<PipeId> p = graph.pipe_of(route[i]);
    if (!p || graph.pipe_of(route[i + 1])) continue;  // only DRIVE_PIPE_TO_MANHOLE
    const RobotPosition to = graph.position(route[i + 1]);
    const auto* at = std::get_if<AtSlot>(&to);
    if (at == nullptr) continue;
    const Slot& slot = map_.slot(at->manhole, at->slot);
    graph.hazards_between(*p, graph.offset_of(route[i]), end_offset_m(map_.pipe(*p), slot.pipe_end),
                          noted_);
  }
  covered_.resize(noted_.size(), false);
  noted_need_.resize(noted_.size());
}

}  // namespace sewerplan::domain
