// SPDX-License-Identifier: MIT
// The sewer compiler's keys and the route searches between them, with the rows the route memo
// keeps between compiles (sewer_task_compiler.h, route_memo.h).
#include <algorithm>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "sewer_task_compiler.h"

namespace sewerplan::domain {

void SewerTaskCompiler::collect_keys(PositionGraph& graph) {
  add_key(graph.node(progress_.position));
  for (TaskId t : pending_) {
    const Task& task = mission_.task(t);
    if (const auto* m = std::get_if<ManholeId>(&task.place)) {
      for (std::uint16_t s = 0; s < map_.manhole(*m).slot_count; ++s) {
        add_key(graph.at_slot(*m, SlotIndex{s}));
      }
      continue;
    }
    const auto& spot = std::get<PipeSpot>(task.place);
    const Pipe& pipe = map_.pipe(spot.pipe);
    // Every key in a task's pipe is a place a task action may leave the robot at.
    for (std::size_t e = 0; e < 2; ++e) {
      if (pipe.ends[e].manhole || task.kind == TaskKind::kInspectPipe) {
        mark_landing(add_key(graph.pipe_end(spot.pipe, e)));
      }
    }
    if (spot.offset_m && task.kind != TaskKind::kInspectPipe) {
      mark_landing(add_key(graph.spot(spot.pipe, *spot.offset_m)));
    }
  }
}

std::vector<Node> SewerTaskCompiler::route_targets() const {
  std::vector<Node> targets;
  for (Node n : keys_) {
    if (can_be_entered(n)) targets.push_back(n);
  }
  return targets;
}

bool SewerTaskCompiler::can_be_entered(Node n) const {
  const PositionGraph& graph = *result_.graph_;
  if (graph.is_extra_spot(n)) return false;
  const Node start = keys_[0];
  auto reachable_source = [&](Node from) {
    if (from == start) return true;
    const RobotPosition p = graph.position(from);
    if (std::holds_alternative<InManhole>(p)) return false;
    if (const auto* s = std::get_if<AtSlot>(&p)) {
      const PipeId pipe = map_.slot(s->manhole, s->slot).pipe;
      return graph.pipe_drivable(pipe) || graph.pipe_of(start) == pipe;
    }
    const PipeId pipe = std::get<InPipe>(p).pipe;
    return graph.pipe_drivable(pipe) || graph.pipe_of(start) == pipe;
  };
  bool entered = false;
  graph.for_each_predecessor(n,
                             [&](Node from, Cost) { entered = entered || reachable_source(from); });
  return entered;
}

void SewerTaskCompiler::route(GraphSearch& search) {
  dist_.assign(k() * k(), kInfiniteCost);
  routes_.assign(k() * k(), {});
  route_store_.clear();
  exit_dist_.assign(k(), kInfiniteCost);
  exit_routes_.assign(k(), {});
  const std::vector<Node> targets = route_targets();
  const std::vector<bool>* exits = nullptr;
  if (ends_at_exit_) {
    mark_exits();
    // Risk-aware, the way to the exit weighs risks more: its own searches (route_to_exits).
    if (!options_.risk.active()) exits = &exit_node();
  }
  result_.graph_->set_risk_weight(options_.risk.blockage_s);
  // From the start first: only the keys it reaches within the bound take part after. From the
  // routing index when one is kept: the keys that are not targets are never entered by a move
  // (can_be_entered), so the search leaves them unreached too.
  detail::ChQuery* index = routing_index(false, 0);
  index_table_targets_ = targets;
  std::sort(index_table_targets_.begin(), index_table_targets_.end());
  std::optional<Node> found;
  if (index != nullptr) {
    index_row(*index, search, 0, targets, bound_, exits != nullptr, &found);
  } else {
    found = search.run(std::span<const Node>(keys_.data(), 1), targets, bound_,
                       GraphSearch::Direction::kForward, exits);
    store_routes(search, 0, found);
    ++result_.statistics_.route_searches;
  }
  if (needs_unbounded_diagnosis()) {
    // Some task is out of reach within the battery: find out whether it is out of reach at all,
    // so that the reason given is the right one.
    search.run(std::span<const Node>(keys_.data(), 1), targets, kInfiniteCost,
               GraphSearch::Direction::kForward);
    store_routes(search, 0, std::nullopt);
  }
  // Issue 35: when the searches from the other keys, each about as large as the start's, will
  // settle more nodes than the graph has, reading the moves from the core's adjacency repays
  // building it (one pass over the map): on 100,000 manholes numbered without spatial order a
  // search settles a node in about a third of the time (docs/benchmarks.md). A stop condition
  // that fires meanwhile leaves the core without it, and the next search stops at its check.
  const std::size_t settled_estimate = (search.settled_total() + 1) * (k() - 1);
  if (!result_.graph_->has_adjacency() && settled_estimate > result_.graph_->size()) {
    (void)result_.graph_->build_adjacency(&options_.stop);
  }
  if (index == nullptr) index = routing_index(!search.interrupted(), settled_estimate);
  // Issue 14: sized once from the start's routes (route_store.h).
  route_store_.reserve_rows(k());
  std::vector<Node> reachable;
  std::vector<bool> reachable_key(k(), false);
  for (Node n : targets) {
    const std::uint32_t b = key_of_.at(n);
    if (dist_[b] <= bound_) {
      reachable.push_back(n);
      reachable_key[b] = true;
    }
  }
  open_memo(reachable, exits != nullptr);
  const RowTargets rows{targets, reachable, reachable_key, exits};
  for (std::size_t a = 1; a < k() && !search.interrupted(); ++a) route_row(search, index, a, rows);
  result_.graph_->set_risk_weight(options_.risk.return_s);
  if (ends_at_exit_ && !search.interrupted()) route_to_exits(search, targets, index);
  result_.graph_->set_risk_weight(0);
  // Kept for the next compile on this core, once every search has run to its end.
  if (options_.cache != nullptr && !search.interrupted()) {
    result_.graph_->core().route_memo = memo_;
  }
}

void SewerTaskCompiler::route_row(GraphSearch& search, detail::ChQuery* index, std::size_t a,
                                  const RowTargets& rows) {
  // A task's spot is reached by the task's action, not by a route: always route from it. So is a
  // pipe end a task leaves the robot at: when no route from the start reaches it within the bound
  // (a go-to at the far end of a pipe entered from its other end), route from it within the whole
  // bound (issue 14: it was a dead end, and a feasible go-to "no plan").
  const bool spot = landing(a) && (result_.graph_->is_extra_spot(keys_[a]) || dist_[a] > bound_);
  if (!spot && dist_[a] > bound_) return;
  const Cost row_bound = spot ? bound_ : bound_ - dist_[a];
  const bool exit_goal = rows.exits != nullptr;
  // A row from a key the start reaches has the routes to the keys the start reaches within the
  // key's bound: those are its targets, and every other key lies beyond that bound. Only its
  // targets are kept, so that the row depends on them alone (RouteMemo).
  if (spot ? reuse_spot_row(a, rows.reachable, rows.reachable_key, exit_goal)
           : reuse_row(a, row_bound, rows.reachable_key)) {
    ++result_.statistics_.reused_searches;
    return;
  }
  std::optional<Node> found;
  // From the index where it gives the search's row. A spot's search keeps every key it settled:
  // the index gives the same only when every key a move enters is a target and the spot's pipe
  // is one the robot may enter (out of a closed pipe, its search settles the slots at the pipe's
  // ends, which no target list has).
  if (index != nullptr &&
      (!spot || (rows.reachable.size() == rows.all.size() &&
                 result_.graph_->pipe_drivable(*result_.graph_->pipe_of(keys_[a]))))) {
    index_row(*index, search, a, rows.reachable, row_bound, exit_goal, &found);
  } else {
    found = search.run(std::span<const Node>(&keys_[a], 1), rows.reachable, row_bound,
                       GraphSearch::Direction::kForward, rows.exits);
    ++result_.statistics_.route_searches;
    store_routes(search, a, found, spot ? nullptr : &rows.reachable_key);
  }
  if (!spot) {
    remember_row(a, row_bound, found, rows.reachable_key);
  } else if (!rows.reachable.empty() || exit_goal) {
    remember_spot_row(a, found);
  }
}

void SewerTaskCompiler::open_memo(const std::vector<Node>& reachable, bool exit_goal) {
  if (options_.cache == nullptr) return;
  const PositionGraph& graph = *result_.graph_;
  memo_->context = detail::RouteMemo::context_of(mission_, options_.risk.blockage_s,
                                                 options_.risk.return_s, exit_goal);
  memo_->targets = reachable;
  std::sort(memo_->targets.begin(), memo_->targets.end());
  old_memo_ = graph.core().route_memo;
  if (old_memo_ != nullptr) change_ = old_memo_->change_to(memo_->context, graph);
}

bool SewerTaskCompiler::reuse_row(std::size_t a, Cost bound,
                                  const std::vector<bool>& reachable_key) {
  if (!change_) return false;
  const auto it = old_memo_->rows.find(keys_[a]);
  if (it == old_memo_->rows.end() || bound > it->second.bound) return false;
  const detail::RouteMemo::Row& row = it->second;
  const PositionGraph& graph = *result_.graph_;
  const auto& old_targets = old_memo_->targets;
  // Per key: what the row found there, if it did.
  std::vector<const detail::RouteMemo::Found*> found(k(), nullptr);
  for (const detail::RouteMemo::Found& f : row.found) {
    if (const auto b = key_of_.find(f.to); b != key_of_.end()) found[b->second] = &f;
  }
  for (std::size_t b = 0; b < k(); ++b) {
    if (b != a && !reachable_key[b]) continue;
    const detail::RouteMemo::Found* f = found[b];
    if (f == nullptr) {
      // Not reached: beyond the row's bound if it was a target, else unknown.
      if (b == a || !std::binary_search(old_targets.begin(), old_targets.end(), keys_[b]))
        return false;
      continue;
    }
    if (f->cost <= bound && change_->touches(graph, old_memo_->store.route(f->route))) return false;
  }
  if (row.exit && row.exit->cost <= bound &&
      change_->touches(graph, old_memo_->store.route(row.exit->route))) {
    return false;
  }
  for (std::size_t b = 0; b < k(); ++b) {
    const detail::RouteMemo::Found* f = found[b];
    if (f == nullptr || f->cost > bound || (b != a && !reachable_key[b])) continue;
    dist_[a * k() + b] = f->cost;
    if (a != b) routes_[a * k() + b] = route_store_.keep(old_memo_->store.route(f->route));
  }
  std::optional<Node> exit;
  if (row.exit && row.exit->cost <= bound) {
    exit = row.exit->to;
    exit_dist_[a] = row.exit->cost;
    exit_routes_[a] = route_store_.keep(old_memo_->store.route(row.exit->route));
  }
  remember_row(a, bound, exit, reachable_key);
  return true;
}

void SewerTaskCompiler::remember_row(std::size_t a, Cost bound, std::optional<Node> exit,
                                     const std::vector<bool>& reachable_key) {
  if (options_.cache == nullptr) return;
  detail::RouteMemo::Row row{.bound = bound};
  for (std::size_t b = 0; b < k(); ++b) {
    if ((b == a || reachable_key[b]) && dist_[a * k() + b] != kInfiniteCost) {
      row.found.push_back({keys_[b], dist_[a * k() + b], routes_[a * k() + b]});
    }
  }
  if (exit && exit_dist_[a] != kInfiniteCost) {
    row.exit = detail::RouteMemo::Found{*exit, exit_dist_[a], exit_routes_[a]};
  }
  memo_->rows.insert_or_assign(keys_[a], std::move(row));
}

bool SewerTaskCompiler::reuse_spot_row(std::size_t a, const std::vector<Node>& reachable,
                                       const std::vector<bool>& reachable_key, bool exit_goal) {
  using Found = detail::RouteMemo::Found;
  if (!change_ || (reachable.empty() && !exit_goal)) return false;
  const auto it = old_memo_->spot_rows.find(spot_key(a));
  if (it == old_memo_->spot_rows.end() || bound_ > it->second.row.bound) return false;
  const PositionGraph& graph = *result_.graph_;
  const Node source = it->second.source;
  const detail::RouteMemo::Row& row = it->second.row;
  const bool extra = graph.is_extra_spot(keys_[a]);
  // An extra spot's moves are its pipe's drives: a change there changes them.
  if (extra && !change_->pipe.empty() && change_->pipe[graph.pipe_of(keys_[a])->index()]) {
    return false;
  }
  if (reachable_key[a]) return false;  // a target itself: not a spot row's shape
  // The route as this compile numbers it after its first node (an extra spot's number was the
  // last compile's), and whether a change touches it.
  const auto rest = [&](const Found& f) {
    const std::span<const Node> r = old_memo_->store.route(f.route);
    return extra && !r.empty() ? r.subspan(1) : r;
  };
  const auto touched = [&](const Found& f) { return change_->touches(graph, rest(f)); };
  const std::vector<Node>& old_targets = old_memo_->targets;
  std::vector<const Found*> found(k(), nullptr);
  std::size_t old_targets_found = 0;
  for (const Found& f : row.found) {
    const bool is_source = f.to == source;
    if (!extra || !is_source) {
      old_targets_found += std::binary_search(old_targets.begin(), old_targets.end(), f.to);
    }
    if (is_source) continue;
    if (const auto b = key_of_.find(f.to); b != key_of_.end()) found[b->second] = &f;
  }
  // The old search stopped once it had its targets and exit; else it ran out within its bound.
  const bool stopped_early = old_targets_found == old_targets.size() && (!exit_goal || row.exit);
  // Where the new search stops: at the last of its targets and its exit, if all are within the
  // bound (`all`); else it runs out within the bound.
  bool all = true;
  Cost stop = 0;
  for (Node t : reachable) {
    const Found* f = found[key_of_.at(t)];
    if (f == nullptr) {
      if (stopped_early) return false;  // beyond the old stop: settled after it
      all = false;
    } else if (f->cost > bound_) {
      all = false;
    } else {
      stop = std::max(stop, f->cost);
    }
  }
  const bool exit = row.exit && row.exit->cost <= bound_;
  if (exit_goal) {
    if (exit) {
      stop = std::max(stop, row.exit->cost);
    } else {
      all = false;
    }
  }
  const Cost limit = all ? stop : bound_;
  for (std::size_t b = 0; b < k(); ++b) {
    const Found* f = found[b];
    if (b == a || f == nullptr || f->cost > limit) continue;
    if (all && f->cost == limit && !reachable_key[b]) return false;  // either side of the stop
    if (touched(*f)) return false;
  }
  if (exit && touched(*row.exit)) return false;
  dist_[a * k() + a] = 0;
  const auto keep = [&](const Found& f) {
    return extra ? route_store_.keep(keys_[a], rest(f))
                 : route_store_.keep(old_memo_->store.route(f.route));
  };
  for (std::size_t b = 0; b < k(); ++b) {
    const Found* f = found[b];
    if (b == a || f == nullptr || f->cost > limit) continue;
    dist_[a * k() + b] = f->cost;
    routes_[a * k() + b] = keep(*f);
  }
  std::optional<Node> exit_node;
  if (exit) {
    exit_node = row.exit->to;
    exit_dist_[a] = row.exit->cost;
    exit_routes_[a] = keep(*row.exit);
  }
  remember_spot_row(a, exit_node);
  return true;
}

void SewerTaskCompiler::remember_spot_row(std::size_t a, std::optional<Node> exit) {
  if (options_.cache == nullptr) return;
  detail::RouteMemo::SpotRow spot{.source = keys_[a], .row = {.bound = bound_}};
  for (std::size_t b = 0; b < k(); ++b) {
    if (dist_[a * k() + b] != kInfiniteCost) {
      spot.row.found.push_back({keys_[b], dist_[a * k() + b], routes_[a * k() + b]});
    }
  }
  if (exit && exit_dist_[a] != kInfiniteCost) {
    spot.row.exit = detail::RouteMemo::Found{*exit, exit_dist_[a], exit_routes_[a]};
  }
  memo_->spot_rows.insert_or_assign(spot_key(a), std::move(spot));
}

void SewerTaskCompiler::mark_exits() {
  const PositionGraph& graph = *result_.graph_;
  detail::GraphCore& core = graph.core();
  if (core.exits_marked == mission_.exits && core.exit_marks.size() >= graph.size()) return;
  core.exits_marked = mission_.exits;
  for (Node n : core.marked_exits) core.exit_marks[n] = false;
  core.marked_exits.clear();
  if (core.exit_marks.size() < graph.size()) core.exit_marks.resize(graph.size(), false);
  auto mark = [&](Node n) {
    core.exit_marks[n] = true;
    core.marked_exits.push_back(n);
  };
  for (ManholeId e : mission_.exits) {
    mark(graph.in_manhole(e));
    for (std::uint16_t s = 0; s < map_.manhole(e).slot_count; ++s) {
      mark(graph.at_slot(e, SlotIndex{s}));
    }
  }
}

bool SewerTaskCompiler::needs_unbounded_diagnosis() const {
  const PositionGraph& graph = *result_.graph_;
  for (TaskId t : pending_) {
    const Task& task = mission_.task(t);
    bool reached = false;
    for (std::size_t e = 0; e < k() && !reached; ++e) {
      const bool at_task =
          std::holds_alternative<ManholeId>(task.place)
              ? manhole_of(graph.position(keys_[e])) == std::get<ManholeId>(task.place)
              : graph.pipe_of(keys_[e]) == std::get<PipeSpot>(task.place).pipe;
      reached = at_task && dist_[e] <= bound_;
    }
    if (!reached) return true;
  }
  return false;
}

void SewerTaskCompiler::store_routes(GraphSearch& search, std::size_t a, std::optional<Node> exit,
                                     const std::vector<bool>* only) {
  for (std::size_t b = 0; b < k(); ++b) {
    if (only != nullptr && b != a && !(*only)[b]) continue;
    dist_[a * k() + b] = search.distance(keys_[b]);
    if (a != b && dist_[a * k() + b] != kInfiniteCost)
      keep_path(search, keys_[b], routes_[a * k() + b]);
  }
  if (exit) {
    exit_dist_[a] = search.distance(*exit);
    keep_path(search, *exit, exit_routes_[a]);
  }
}

void SewerTaskCompiler::route_to_exits(GraphSearch& search, const std::vector<Node>& targets,
                                       detail::ChQuery* index) {
  for (std::size_t a = 0; a < k(); ++a) {
    const Node n = keys_[a];
    const bool in_reach =
        a == 0 || landing(a) ||
        (std::find(targets.begin(), targets.end(), n) != targets.end() && dist_[a] <= bound_);
    if (!in_reach || exit_dist_[a] != kInfiniteCost) continue;
    if (reuse_exit_search(a)) continue;
    if (std::optional<Node> exit; index != nullptr && index_exit(*index, a, bound_, &exit)) {
      ++result_.statistics_.index_rows;
      remember_exit_search(a, exit);
      continue;
    }
    const std::optional<Node> exit = search.run_to_nearest(n, exit_node(), bound_);
    ++result_.statistics_.route_searches;
    if (exit) {
      exit_dist_[a] = search.distance(*exit);
      keep_path(search, *exit, exit_routes_[a]);
    }
    remember_exit_search(a, exit);
  }
}

bool SewerTaskCompiler::reuse_exit_search(std::size_t a) {
  if (!change_) return false;
  const PositionGraph& graph = *result_.graph_;
  const bool extra = graph.is_extra_spot(keys_[a]);
  const detail::RouteMemo::ExitSearch* old = nullptr;
  if (extra) {
    if (!change_->pipe.empty() && change_->pipe[graph.pipe_of(keys_[a])->index()]) return false;
    const auto it = old_memo_->spot_exit_searches.find(spot_key(a));
    if (it != old_memo_->spot_exit_searches.end()) old = &it->second;
  } else if (const auto it = old_memo_->exit_searches.find(keys_[a]);
             it != old_memo_->exit_searches.end()) {
    old = &it->second;
  }
  if (old == nullptr || bound_ > old->bound) return false;
  const std::optional<detail::RouteMemo::Found>& exit = old->exit;
  std::optional<Node> kept;
  if (exit && exit->cost <= bound_) {
    const std::span<const Node> route = old_memo_->store.route(exit->route);
    const std::span<const Node> rest = extra && !route.empty() ? route.subspan(1) : route;
    if (change_->touches(graph, rest)) return false;
    kept = exit->to;
    exit_dist_[a] = exit->cost;
    exit_routes_[a] = extra ? route_store_.keep(keys_[a], rest) : route_store_.keep(route);
  }
  ++result_.statistics_.reused_searches;
  remember_exit_search(a, kept);
  return true;
}

void SewerTaskCompiler::remember_exit_search(std::size_t a, std::optional<Node> exit) {
  if (options_.cache == nullptr) return;
  detail::RouteMemo::ExitSearch s{.bound = bound_};
  if (exit) s.exit = detail::RouteMemo::Found{*exit, exit_dist_[a], exit_routes_[a]};
  if (result_.graph_->is_extra_spot(keys_[a])) {
    memo_->spot_exit_searches.insert_or_assign(spot_key(a), std::move(s));
  } else {
    memo_->exit_searches.insert_or_assign(keys_[a], std::move(s));
  }
}

}  // namespace sewerplan::domain
