// SPDX-License-Identifier: MIT
// The sewer compiler: keys, routes between them, and the compiled task (compile.h).
#include "sewerplan/domain/compile.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <iomanip>
#include <map>
#include <mutex>
#include <span>
#include <sstream>
#include <string_view>
#include <tuple>
#include <unordered_map>

#include "sewerplan/core/clock.h"

#include "compile_reasons.h"
#include "graph_search.h"
#include "position_graph.h"
#include "route_memo.h"
#include "route_store.h"

namespace sewerplan::domain {

using detail::GraphSearch;
using detail::Node;
using detail::PositionGraph;
using detail::RouteRef;

struct CompileCache::State {
  std::mutex mutex;
  std::shared_ptr<detail::GraphCore> core;
};

CompileCache::CompileCache() : state_(std::make_unique<State>()) {}
CompileCache::~CompileCache() = default;

SewerTask::SewerTask() = default;
SewerTask::SewerTask(SewerTask&&) noexcept = default;
SewerTask& SewerTask::operator=(SewerTask&&) noexcept = default;
SewerTask::~SewerTask() = default;

Plan SewerTask::expand(std::span<const ActionId> plan) const {
  Plan out;
  for (ActionId a : plan) {
    for (std::uint32_t i = route_begin_[a.index()]; i + 1 < route_begin_[a.index() + 1]; ++i) {
      out.steps.push_back(graph_->step(route_nodes_[i], route_nodes_[i + 1]));
    }
    if (task_step_[a.index()]) out.steps.push_back(*task_step_[a.index()]);
  }
  return out;
}

class SewerTaskCompiler {
 public:
  SewerTaskCompiler(const SewerMap& map, const Mission& mission, const MissionProgress& progress,
                    const CompileOptions& options)
      : map_(map), mission_(mission), progress_(progress), options_(options) {
    result_.graph_ = std::make_unique<PositionGraph>(map, mission, cached_core(), &options_.stop);
  }

  Result<SewerTask> run() {
    SteadyClock clock;
    const double start_s = clock.now_s();
    PositionGraph& graph = *result_.graph_;
    if (!graph.core().complete) return stop_error();
    select_tasks();
    collect_keys(graph);
    if (auto stopped = options_.stop.interrupted()) return stopped_error(*stopped, "the compile");
    // The arrays over every node, grown before the searches with checks between slices (on a
    // large map, one fill was the longest stretch without a check: issue 14).
    if (!GraphSearch::grow(graph.core().scratch, graph.size(), &options_.stop) ||
        !detail::grow_in_slices(graph.core().exit_marks, graph.size(), &options_.stop)) {
      return stop_error();
    }
    GraphSearch search(graph, &graph.core().scratch);
    if (options_.stop.can_interrupt()) {
      search.set_interrupt([this] { return options_.stop.interrupted().has_value(); });
    }
    route(search);
    if (search.interrupted()) return stop_error();
    detail::CompileReasons reasons(graph, mission_, progress_, bound_, keys_[0]);
    if (options_.select_goals) {
      if (auto why = select_goals(reasons); !why.empty()) {
        return Error{ErrorCode::kNoPlan, "the mission cannot be ended:" + why};
      }
    } else if (auto why = reasons.explain(keys_, pending_, dist_, exit_dist_, ends_at_exit_);
               !why.empty()) {
      return Error{ErrorCode::kNoPlan, "the mission cannot be completed:" + why};
    }
    for (const Hazard& h : mission_.hazards) {
      result_.hazard_probability_.push_back(std::clamp(h.probability, 0.0, 1.0));
    }
    contingency_ = options_.contingency && ends_at_exit_ && graph.has_hazards();
    if (contingency_) {
      if (!GraphSearch::grow(contingency_scratch_, graph.size(), &options_.stop))
        return stop_error();
      contingency_search_ = std::make_unique<GraphSearch>(graph, &contingency_scratch_);
      if (options_.stop.can_interrupt()) {
        contingency_search_->set_interrupt(
            [this] { return options_.stop.interrupted().has_value(); });
      }
    }
    build_task();
    if (build_stopped_) return stopped_error(*build_stopped_, "the compile");
    // Issue 30: a task cut off by a blockage or a closure is named with its cause before any
    // search, rather than the search's "no plan within the battery" blaming the battery.
    if (auto why = undoable_reasons(); !why.empty()) {
      return Error{ErrorCode::kNoPlan,
                   (options_.select_goals ? "the mission cannot be ended:"
                                          : "the mission cannot be completed:") +
                       why};
    }
    if (contingency_search_ && contingency_search_->interrupted()) return stop_error();
    result_.statistics_.keys = keys_.size();
    result_.statistics_.graph_nodes = graph.size();
    result_.statistics_.settled_nodes =
        search.settled_total() + (contingency_search_ ? contingency_search_->settled_total() : 0);
    result_.statistics_.actions = result_.task_.action_count();
    result_.statistics_.adjacency = graph.has_adjacency();
    result_.statistics_.time_s = clock.now_s() - start_s;
    return std::move(result_);
  }

 private:
  std::size_t k() const { return keys_.size(); }

  // The error of a compile stopped by its stop condition.
  Error stop_error() const {
    return stopped_error(options_.stop.interrupted().value_or(SearchStatus::kTimeLimit),
                         "the compile");
  }

  // The cache's core when it serves this map and robot and no other compile's task holds it
  // (then only the cache does: the count grows only here, under the lock); else a fresh one,
  // which the cache keeps if its own does not serve.
  std::shared_ptr<detail::GraphCore> cached_core() const {
    if (options_.cache == nullptr) return nullptr;
    CompileCache::State& state = *options_.cache->state_;
    const std::lock_guard lock(state.mutex);
    const auto& core = state.core;
    const PassageMotionTable* motion = mission_.passage_motion.get();
    if (core != nullptr && core->serves(map_, mission_.profile, motion)) {
      if (core.use_count() == 1) return core;
      return nullptr;
    }
    state.core = std::make_shared<detail::GraphCore>(map_, mission_.profile,
                                                     mission_.passage_motion, &options_.stop);
    return state.core;
  }

  // Leaves out the pending tasks known to be impossible; what remains impossible is returned.
  std::string select_goals(const detail::CompileReasons& reasons) {
    std::string why = reasons.fatal(exit_dist_, ends_at_exit_);
    if (!why.empty()) return why;
    std::vector<TaskId> kept;
    for (TaskId t : pending_) {
      const Task& task = mission_.task(t);
      std::string reason = reasons.task_reason(task, keys_, dist_, exit_dist_, ends_at_exit_);
      if (reason.empty()) {
        kept.push_back(t);
      } else if (task.final) {
        why += "\n  - the final task '" + task.name + "': " + reason;
      } else {
        result_.dropped_.push_back({t, std::move(reason)});
      }
    }
    pending_ = std::move(kept);
    return why;
  }

  void select_tasks() {
    for (TaskId t : mission_.task_ids()) {
      if (!progress_.done[t.index()]) pending_.push_back(t);
    }
    const auto final_task = mission_.final_task_id();
    ends_at_exit_ = !final_task.has_value();
    const double budget_wh = mission_.profile.battery_wh * (1 - mission_.battery_reserve_fraction) -
                             progress_.energy_used_wh;
    bound_ = budget_wh < 0 ? -1 : to_cost(mission_.profile.seconds_for(budget_wh));
  }

  std::uint32_t add_key(Node n) {
    auto [it, added] = key_of_.emplace(n, static_cast<std::uint32_t>(keys_.size()));
    if (added) keys_.push_back(n);
    return it->second;
  }

  void mark_landing(std::uint32_t key) {
    if (landing_.size() <= key) landing_.resize(key + 1, false);
    landing_[key] = true;
  }
  // A key a task action may leave the robot at (a spot, or a pipe end such as a go-to at a pipe's
  // very end: issue 14), which a route from the start need not reach.
  bool landing(std::size_t key) const {
    return result_.graph_->is_extra_spot(keys_[key]) || (key < landing_.size() && landing_[key]);
  }

  void collect_keys(PositionGraph& graph) {
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

  // Keys a route can end at: not task spots (only task actions enter them), and not pipe ends
  // that no move enters (the robot's limits forbid every passage into that pipe there). A route
  // search stops once all its targets are settled, so an unreachable target would make it
  // explore everything within the bound.
  std::vector<Node> route_targets() const {
    std::vector<Node> targets;
    for (Node n : keys_) {
      if (can_be_entered(n)) targets.push_back(n);
    }
    return targets;
  }

  // Whether some move ends at n from a position the robot can itself get to: "in manhole" only
  // as the start, a slot only out of a pipe it can drive (or starts in).
  bool can_be_entered(Node n) const {
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
    graph.for_each_predecessor(
        n, [&](Node from, Cost) { entered = entered || reachable_source(from); });
    return entered;
  }

  void route(GraphSearch& search) {
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
    // From the start first: only the keys it reaches within the bound take part after.
    auto found = search.run(std::span<const Node>(keys_.data(), 1), targets, bound_,
                            GraphSearch::Direction::kForward, exits);
    store_routes(search, 0, found);
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
    if (!result_.graph_->has_adjacency() &&
        (search.settled_total() + 1) * (k() - 1) > result_.graph_->size()) {
      (void)result_.graph_->build_adjacency(&options_.stop);
    }
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
    std::size_t searches = 1;
    for (std::size_t a = 1; a < k() && !search.interrupted(); ++a) {
      // A task's spot is reached by the task's action, not by a route: always route from it. So
      // is a pipe end a task leaves the robot at: when no route from the start reaches it within
      // the bound (a go-to at the far end of a pipe entered from its other end), route from it
      // within the whole bound (issue 14: it was a dead end, and a feasible go-to "no plan").
      const bool spot =
          landing(a) && (result_.graph_->is_extra_spot(keys_[a]) || dist_[a] > bound_);
      if (!spot && dist_[a] > bound_) continue;
      const Cost row_bound = spot ? bound_ : bound_ - dist_[a];
      // A row from a key the start reaches has the routes to the keys the start reaches within
      // the key's bound: those are its targets, and every other key lies beyond that bound. Only
      // its targets are kept, so that the row depends on them alone (RouteMemo).
      if (!spot && reuse_row(a, row_bound, reachable_key)) {
        ++result_.statistics_.reused_searches;
        continue;
      }
      if (spot && reuse_spot_row(a, reachable, reachable_key, exits != nullptr)) {
        ++result_.statistics_.reused_searches;
        continue;
      }
      found = search.run(std::span<const Node>(&keys_[a], 1), reachable, row_bound,
                         GraphSearch::Direction::kForward, exits);
      ++searches;
      store_routes(search, a, found, spot ? nullptr : &reachable_key);
      if (!spot) {
        remember_row(a, row_bound, found, reachable_key);
      } else if (!reachable.empty() || exits != nullptr) {
        remember_spot_row(a, found);
      }
    }
    result_.statistics_.route_searches = searches;
    result_.graph_->set_risk_weight(options_.risk.return_s);
    if (ends_at_exit_ && !search.interrupted()) route_to_exits(search, targets);
    result_.graph_->set_risk_weight(0);
    // Kept for the next compile on this core, once every search has run to its end.
    if (options_.cache != nullptr && !search.interrupted()) {
      result_.graph_->core().route_memo = memo_;
    }
  }

  // The last compile's rows (RouteMemo), when this compile may take from them, and this
  // compile's context for the next.
  void open_memo(const std::vector<Node>& reachable, bool exit_goal) {
    if (options_.cache == nullptr) return;
    const PositionGraph& graph = *result_.graph_;
    memo_->context = detail::RouteMemo::context_of(mission_, options_.risk.blockage_s,
                                                   options_.risk.return_s, exit_goal);
    memo_->targets = reachable;
    std::sort(memo_->targets.begin(), memo_->targets.end());
    old_memo_ = graph.core().route_memo;
    if (old_memo_ != nullptr) change_ = old_memo_->change_to(memo_->context, graph);
  }

  // Takes key a's row from the last compile's (RouteMemo), if it is what a search within `bound`
  // would find.
  bool reuse_row(std::size_t a, Cost bound, const std::vector<bool>& reachable_key) {
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
      if (f->cost <= bound && change_->touches(graph, old_memo_->store.route(f->route)))
        return false;
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

  // Keeps key a's row for the next compile (RouteMemo::Row).
  void remember_row(std::size_t a, Cost bound, std::optional<Node> exit,
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

  // A spot row's place in RouteMemo::spot_rows.
  detail::RouteMemo::SpotKey spot_key(std::size_t a) const {
    const PositionGraph& graph = *result_.graph_;
    const Node n = keys_[a];
    if (graph.is_extra_spot(n)) return {true, graph.pipe_of(n)->value(), graph.offset_of(n)};
    return {false, n, 0.0};
  }

  // Takes the row of key a, a spot's (a search within the whole bound keeping every key it
  // settles), from the last compile's (RouteMemo::SpotRow), if it is what the search would find:
  // see route_memo.h for the argument.
  bool reuse_spot_row(std::size_t a, const std::vector<Node>& reachable,
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

  // Keeps key a's spot row for the next compile (RouteMemo::SpotRow): every key it settled.
  void remember_spot_row(std::size_t a, std::optional<Node> exit) {
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

  // Marks the mission's exits in the core's exit marks (unmarking the last compile's, unless they
  // are the same).
  void mark_exits() {
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
  const std::vector<bool>& exit_node() const { return result_.graph_->core().exit_marks; }

  // Whether some pending task has no key the start reaches within the bound (row 0 of dist_).
  bool needs_unbounded_diagnosis() const {
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

  // The routes of the last search, from key a; `exit`: the nearest exit it settled. With `only`,
  // to a itself and the keys it marks.
  void store_routes(GraphSearch& search, std::size_t a, std::optional<Node> exit,
                    const std::vector<bool>* only = nullptr) {
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

  // Each key's cheapest way to its nearest exit, where the key's own search (bounded by what is
  // left of the battery after reaching the key) did not settle one: a forward search that stops
  // at the first exit it settles, within the whole battery, so that the reasons given for an
  // impossible mission name the right energy. (One backward search from all exits would grow a
  // ball around every exit of the city; with exits every few manholes the forward balls are
  // small.)
  void route_to_exits(GraphSearch& search, const std::vector<Node>& targets) {
    for (std::size_t a = 0; a < k(); ++a) {
      const Node n = keys_[a];
      const bool in_reach =
          a == 0 || landing(a) ||
          (std::find(targets.begin(), targets.end(), n) != targets.end() && dist_[a] <= bound_);
      if (!in_reach || exit_dist_[a] != kInfiniteCost) continue;
      if (reuse_exit_search(a)) continue;
      const std::optional<Node> exit = search.run_to_nearest(n, exit_node(), bound_);
      ++result_.statistics_.route_searches;
      if (exit) {
        exit_dist_[a] = search.distance(*exit);
        keep_path(search, *exit, exit_routes_[a]);
      }
      remember_exit_search(a, exit);
    }
  }

  // Takes key a's way to its nearest exit from the last compile's (RouteMemo::ExitSearch), if it
  // is what a search within the bound would find. A spot's is kept by its pipe and offset, its
  // route renumbered from its first node (RouteMemo::SpotRow).
  bool reuse_exit_search(std::size_t a) {
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

  void remember_exit_search(std::size_t a, std::optional<Node> exit) {
    if (options_.cache == nullptr) return;
    detail::RouteMemo::ExitSearch s{.bound = bound_};
    if (exit) s.exit = detail::RouteMemo::Found{*exit, exit_dist_[a], exit_routes_[a]};
    if (result_.graph_->is_extra_spot(keys_[a])) {
      memo_->spot_exit_searches.insert_or_assign(spot_key(a), std::move(s));
    } else {
      memo_->exit_searches.insert_or_assign(keys_[a], std::move(s));
    }
  }

  // What blocks a task in a pipe, for the reason given when it is dropped.
  std::string blocked_reason(const Task& task) const {
    if (const auto* spot = std::get_if<PipeSpot>(&task.place)) {
      for (const Blockage& b : mission_.blockages) {
        if (b.pipe == spot->pipe) {
          std::ostringstream out;
          out << "pipe " << map_.pipe(b.pipe).name << " is blocked at " << std::fixed
              << std::setprecision(2) << b.offset_m << " m";
          return out.str();
        }
      }
    }
    return "no way there within the robot's limits, the mission's closures and the battery left";
  }

  void build_task();
  // `risk`: the part of `cost` that is the expected cost of stops (RiskCosts). The action's
  // contingency reserve follows from its route and `need` (the battery a task action's own
  // drive needs when it starts: in_pipe_need).
  ActionId add_action(std::span<const Fact> pre, std::span<const Fact> eff, Cost cost,
                      std::string name, std::span<const Node> route, std::optional<PlanStep> step,
                      Cost risk = 0, Cost need = 0);

  // Contingency-aware battery planning (CompileOptions::contingency). A pipe with a hazard may
  // turn out blocked, and so may one more on the way out after it: two levels, each a plain
  // Dijkstra search.
  // The battery needed at `from` to reach an exit with `first` (and `second`) found blocked: the
  // cheapest way out avoiding them and, at the first level, enough on that way to back out of
  // each hazard pipe it drives and still reach an exit (route_need). kInfiniteCost: no way out
  // within the battery. Kept per place and pipes.
  Cost exit_need(Node from, PipeId first, std::optional<PipeId> second) {
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
  // Calls f(u, v, prefix) for each step u -> v of `route` in order, `prefix` the cost of the route
  // before that step (each step costs the cheapest move from u to v); stops at the first step the
  // graph has no move for.
  template <typename F>
  static void for_each_step(const PositionGraph& graph, std::span<const Node> route, F&& f) {
    Cost prefix = 0;
    for (std::size_t i = 0; i + 1 < route.size(); ++i) {
      const Node u = route[i];
      const Node v = route[i + 1];
      Cost step = kInfiniteCost;
      graph.for_each_successor(u, [&](Node to, Cost c) {
        if (to == v) step = std::min(step, c);
      });
      if (step >= kInfiniteCost) return;
      f(u, v, prefix);
      prefix += step;
    }
  }
  // For the stranding risk (SewerTask::strand_risk): the cheapest way out from `from` with
  // `first` found blocked (`plain`, as exit_need without reserves), the battery for it with a
  // reserve at every hazard it passes, insured or not (`full`: back out of that one too and reach
  // an exit avoiding both), and the chance that one of those hazards blocks it (`risk`).
  // kInfiniteCost: no way out within the battery. Kept per place and pipe.
  struct WayOut {
    Cost plain = kInfiniteCost;
    Cost full = kInfiniteCost;
    double risk = 0;
  };
  WayOut way_out(Node from, PipeId first) {
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
  // The battery needed, `prefix` before the robot drives pipe p from the end node `entry` (offset
  // `from`) towards offset `to` at `speed_mps`, should the farthest hazard on the way stop it:
  // the drive there, back to the entry's manhole, and from there to an exit another way
  // (exit_need; `blocked`: a pipe found blocked before, at the second level). 0 when no hazard
  // is on the way, the drive does not start at a pipe end with a manhole, or there is no other
  // way out at all (no battery would help then).
  // Only the insured hazards (CompileOptions::insured) ask for a reserve. At the first level
  // (no `blocked`), the hazards the drive passes are noted for the action being built, each
  // covered when the reserve kept reaches as far as it (SewerTask::strand_risk).
  Cost in_pipe_need(PipeId p, Node entry, double from, double to, Cost prefix, double speed_mps,
                    std::optional<PipeId> blocked = std::nullopt) {
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
  // in_pipe_need over every pipe a route drives.
  Cost route_need(std::span<const Node> route, std::optional<PipeId> blocked = std::nullopt) {
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
  // The hazards a route's pipe drives pass, noted uncovered (without contingency).
  void note_route(std::span<const Node> route) {
    const PositionGraph& graph = *result_.graph_;
    for (std::size_t i = 0; i + 1 < route.size(); ++i) {
      const std::optional<PipeId> p = graph.pipe_of(route[i]);
      if (!p || graph.pipe_of(route[i + 1])) continue;  // only DRIVE_PIPE_TO_MANHOLE
      const RobotPosition to = graph.position(route[i + 1]);
      const auto* at = std::get_if<AtSlot>(&to);
      if (at == nullptr) continue;
      const Slot& slot = map_.slot(at->manhole, at->slot);
      graph.hazards_between(*p, graph.offset_of(route[i]),
                            end_offset_m(map_.pipe(*p), slot.pipe_end), noted_);
    }
    covered_.resize(noted_.size(), false);
    noted_need_.resize(noted_.size());
  }
  // The task's actions from each key, each recorded in task_moves_.
  void add_task_actions(std::size_t index, VarId pos);
  void add_task_actions_from(std::size_t index, VarId pos, std::uint32_t y);
  // The pending tasks none of whose actions starts at a key the robot can get to: from where it
  // is within the battery, or from where another task's action (that it can get to) leaves it,
  // and on from there. Runtime: O(rounds x moves x k), on the keys only.
  std::vector<std::size_t> cut_off_tasks() const;
  // "\n  - task 'x' (kind): reason" for each task no action can do from where the robot can get
  // (undoable_); with goal selection only the final task's (the others are dropped).
  std::string undoable_reasons() const;
  std::vector<Fact> task_preconditions(std::size_t index, VarId pos, std::uint32_t key) const;

  const SewerMap& map_;
  const Mission& mission_;
  const MissionProgress& progress_;
  const CompileOptions& options_;
  // Pending tasks (indices into pending_) no action can do from where the robot can get: a
  // blockage or a closure in the way, found before any search.
  std::vector<std::size_t> undoable_;
  // Per pending task: its actions as (key it starts at, key it leaves the robot at).
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> task_moves_;
  SewerTask result_;
  CompiledTask::Builder builder_;
  std::vector<TaskId> pending_;
  std::vector<VarId> task_vars_;
  bool ends_at_exit_ = true;
  Cost bound_ = 0;
  std::vector<Node> keys_;
  std::vector<bool> landing_;  // per key, see landing(); shorter when the last keys are not
  std::unordered_map<Node, std::uint32_t> key_of_;
  std::vector<Cost> dist_;  // k x k, row = from
  // This compile's searches for the next compile on the core (route_memo.h), the last compile's,
  // and what changed since (null: nothing may be taken from it).
  std::shared_ptr<detail::RouteMemo> memo_ = std::make_shared<detail::RouteMemo>();
  std::shared_ptr<const detail::RouteMemo> old_memo_;
  std::optional<detail::RouteMemo::Change> change_;
  // The routes of the searches, each a stretch of one store (route_store.h), the memo's.
  detail::RouteStore& route_store_ = memo_->store;
  std::span<const Node> route(RouteRef r) const { return route_store_.route(r); }
  void keep_path(const GraphSearch& search, Node n, RouteRef& ref) {
    ref = route_store_.keep(search, n);
  }
  std::vector<RouteRef> routes_;
  std::vector<Cost> exit_dist_;
  std::vector<RouteRef> exit_routes_;
  bool contingency_ = false;
  detail::SearchScratch contingency_scratch_;  // declared first: outlives its search
  std::unique_ptr<GraphSearch> contingency_search_;
  // Issue 14: building the task's actions (k^2 moves, each with its route, its risk and its
  // reserve) took 20 to 30 ms on 10,000 manholes without a look at the stop condition. Checked
  // at every action built; once it fires, build_task() stops and run() reports it.
  std::optional<SearchStatus> build_stopped_;
  bool build_interrupted() {
    if (!build_stopped_ && options_.stop.can_interrupt()) {
      build_stopped_ = options_.stop.interrupted();
    }
    return build_stopped_.has_value();
  }
  std::map<std::tuple<Node, std::uint32_t, std::uint32_t>, Cost> exit_need_;
  // The hazards the action being built passes (index into Mission::hazards, distance from where
  // its drive in that pipe starts), and whether its reserve covers each; add_action takes them.
  std::vector<std::pair<std::uint32_t, double>> noted_;
  std::vector<bool> covered_;
  // Per hazard noted: the battery to back out from it and reach an exit another way, from the
  // start of the action being built (SewerTask::HazardPass).
  std::vector<SewerTask::WayBack> noted_need_;
  std::map<std::pair<Node, std::uint32_t>, WayOut> way_out_;
};

}  // namespace sewerplan::domain

namespace sewerplan::domain {
namespace {

// The name of a move between keys ("go key 3 -> 7", "exit from key 3"), written into one buffer
// (issue 16: k^2 such names, each joined by operator+ from std::to_string's, were a sixth of
// building a 10-manhole task).
std::string key_name(std::string_view head, std::uint32_t a, std::string_view middle = {},
                     std::optional<std::uint32_t> b = std::nullopt) {
  std::array<char, 64> text;  // the heads are short words, the numbers 10 digits at most
  SEWER_CHECK(head.size() + middle.size() + 20 <= text.size(), "key_name: a head too long");
  char* end = std::copy(head.begin(), head.end(), text.data());
  end = std::to_chars(end, text.data() + text.size(), a).ptr;
  end = std::copy(middle.begin(), middle.end(), end);
  if (b) end = std::to_chars(end, text.data() + text.size(), *b).ptr;
  return std::string(text.data(), end);
}

}  // namespace

ActionId SewerTaskCompiler::add_action(std::span<const Fact> pre, std::span<const Fact> eff,
                                       Cost cost, std::string name, std::span<const Node> route,
                                       std::optional<PlanStep> step, Cost risk, Cost need) {
  const ActionId id = builder_.add_action(pre, eff, cost, std::move(name));
  need = std::max(need, route_need(route));
  if (need > cost) builder_.set_reserve(id, need - cost);
  result_.risk_.push_back(risk);
  if (result_.pass_begin_.empty()) result_.pass_begin_.push_back(0);
  for (std::size_t i = 0; i < noted_.size(); ++i) {
    // A route's own drives were noted from its start; a task action's drive from where the
    // action starts it too (in_pipe_need's prefix).
    result_.passes_.push_back({noted_[i].first, covered_[i], noted_need_[i]});
  }
  result_.pass_begin_.push_back(static_cast<std::uint32_t>(result_.passes_.size()));
  noted_.clear();
  covered_.clear();
  noted_need_.clear();
  if (result_.route_begin_.empty()) result_.route_begin_.push_back(0);
  result_.route_nodes_.insert(result_.route_nodes_.end(), route.begin(), route.end());
  result_.route_begin_.push_back(static_cast<std::uint32_t>(result_.route_nodes_.size()));
  result_.task_step_.push_back(std::move(step));
  return id;
}

std::vector<Fact> SewerTaskCompiler::task_preconditions(std::size_t index, VarId pos,
                                                        std::uint32_t key) const {
  std::vector<Fact> pre{{pos, static_cast<std::int32_t>(key)}, {task_vars_[index], 0}};
  if (mission_.task(pending_[index]).final) {
    for (std::size_t j = 0; j < pending_.size(); ++j) {
      if (j != index) pre.push_back({task_vars_[j], 1});
    }
  }
  return pre;
}

void SewerTaskCompiler::add_task_actions(std::size_t index, VarId pos) {
  if (task_moves_.size() <= index) task_moves_.resize(index + 1);
  for (std::uint32_t y = 0; y < k(); ++y) add_task_actions_from(index, pos, y);
}

std::vector<std::size_t> SewerTaskCompiler::cut_off_tasks() const {
  std::vector<bool> reached(k(), false);
  const auto reach_from = [&](std::uint32_t from) {
    for (std::uint32_t b = 0; b < k(); ++b) {
      if (dist_[from * k() + b] <= bound_) reached[b] = true;
    }
  };
  reached[0] = true;
  reach_from(0);
  for (bool grew = true; grew;) {
    grew = false;
    for (const auto& moves : task_moves_) {
      for (const auto& [from, to] : moves) {
        if (!reached[from] || reached[to]) continue;
        reached[to] = true;
        reach_from(to);
        grew = true;
      }
    }
  }
  std::vector<std::size_t> cut_off;
  for (std::size_t i = 0; i < task_moves_.size(); ++i) {
    const auto& moves = task_moves_[i];
    if (std::none_of(moves.begin(), moves.end(), [&](const auto& m) { return reached[m.first]; })) {
      cut_off.push_back(i);
    }
  }
  return cut_off;
}

std::string SewerTaskCompiler::undoable_reasons() const {
  std::string out;
  for (std::size_t i : undoable_) {
    const Task& task = mission_.task(pending_[i]);
    if (options_.select_goals && !task.final) continue;
    out += "\n  - " + std::string(task.final ? "the final task '" : "task '") + task.name + "' (" +
           std::string(to_string(task.kind)) +
           "): no position the robot can reach lets it do the task: " + blocked_reason(task);
  }
  return out;
}

void SewerTaskCompiler::add_task_actions_from(std::size_t index, VarId pos, std::uint32_t y) {
  PositionGraph& graph = *result_.graph_;
  const TaskId t = pending_[index];
  const Task& task = mission_.task(t);
  const VarId var = task_vars_[index];
  const RobotProfile& profile = mission_.profile;
  const std::string label = "'" + task.name + "' from key ";
  const Fact done[] = {{var, 1}};
  auto& moves = task_moves_[index];
  if (const auto* m = std::get_if<ManholeId>(&task.place)) {
    if (manhole_of(graph.position(keys_[y])) != *m) return;
    std::optional<PlanStep> step;
    if (!task.final) step = GoToManhole{*m, t};
    add_action(task_preconditions(index, pos, y), done, 0,
               (task.final ? "finish " : "go-to ") + label + std::to_string(y), {}, step);
    moves.emplace_back(y, y);
    return;
  }
  const auto& spot = std::get<PipeSpot>(task.place);
  if (graph.pipe_of(keys_[y]) != spot.pipe) return;
  const double at = graph.offset_of(keys_[y]);
  const auto pre = task_preconditions(index, pos, y);
  auto blocked = [&](double x) { return graph.blocked_between(spot.pipe, at, x); };
  auto move_to = [&](double x, std::vector<Fact> eff) {
    const std::uint32_t to = x != at ? key_of_.at(graph.spot(spot.pipe, x)) : y;
    if (x != at) eff.push_back({pos, static_cast<std::int32_t>(to)});
    moves.emplace_back(y, to);
    return eff;
  };
  switch (task.kind) {
    case TaskKind::kTakeWaterSample: {
      const double x = spot.offset_m.value_or(at);
      if (blocked(x)) break;
      add_action(pre, move_to(x, {{var, 1}}),
                 to_cost(std::abs(x - at) / profile.speed_mps + profile.sample_s),
                 "sample " + label + std::to_string(y), {}, TakeWaterSample{spot.pipe, t}, 0,
                 in_pipe_need(spot.pipe, keys_[y], at, x, 0, profile.speed_mps));
      break;
    }
    case TaskKind::kGoTo: {
      if (task.final && !spot.offset_m) {
        add_action(pre, done, 0, "finish " + label + std::to_string(y), {}, std::nullopt);
        moves.emplace_back(y, y);
        break;
      }
      const double x = spot.offset_m.value_or(at);
      if (blocked(x)) break;
      add_action(pre, move_to(x, {{var, 1}}), to_cost(std::abs(x - at) / profile.speed_mps),
                 "go-to " + label + std::to_string(y), {}, GoToPoint{spot.pipe, t}, 0,
                 in_pipe_need(spot.pipe, keys_[y], at, x, 0, profile.speed_mps));
      break;
    }
    case TaskKind::kInspectPipe: {
      const Pipe& pipe = map_.pipe(spot.pipe);
      if (!graph.fully_open(spot.pipe)) break;
      for (std::uint8_t e = 0; e < 2; ++e) {
        const double start_end = end_offset_m(pipe, 1U - e);
        const Node finish = graph.pipe_end(spot.pipe, e);
        std::optional<std::uint8_t> finish_end;
        if (keys_[y] != graph.pipe_end(spot.pipe, 1U - e)) finish_end = e;
        // The inspection drives the whole pipe, past every hazard in it.
        const Cost risk =
            graph.risk_cost(spot.pipe, -1.0, pipe.length_m + 1.0, options_.risk.blockage_s);
        const Fact eff[] = {{var, 1}, {pos, static_cast<std::int32_t>(key_of_.at(finish))}};
        moves.emplace_back(y, key_of_.at(finish));
        add_action(pre, eff,
                   to_cost(std::abs(at - start_end) / profile.speed_mps +
                           pipe.length_m / profile.inspection_speed_mps) +
                       risk,
                   "inspect " + label + std::to_string(y) + " to end " + std::to_string(e), {},
                   InspectPipe{spot.pipe, t, finish_end}, risk,
                   in_pipe_need(spot.pipe, graph.pipe_end(spot.pipe, 1U - e), start_end,
                                end_offset_m(pipe, e),
                                to_cost(std::abs(at - start_end) / profile.speed_mps),
                                profile.inspection_speed_mps));
      }
      break;
    }
  }
}

void SewerTaskCompiler::build_task() {
  const auto exit_value = static_cast<std::int32_t>(k());
  const VarId pos =
      builder_.add_variable(static_cast<std::int32_t>(k()) + (ends_at_exit_ ? 1 : 0), "position");
  for (TaskId t : pending_) {
    task_vars_.push_back(builder_.add_variable(2, "task '" + mission_.task(t).name + "'"));
  }
  result_.goal_tasks_ = pending_;
  builder_.set_initial(std::vector<std::int32_t>(1 + pending_.size(), 0));
  for (VarId v : task_vars_) builder_.add_goal({v, 1});
  if (ends_at_exit_) builder_.add_goal({pos, exit_value});
  builder_.set_cost_bound(bound_);
  // Issue 14: growing the route table by doubling copied it whole (millions of nodes on 10,000
  // manholes), a stretch of several milliseconds between two stop checks; sized once instead.
  std::size_t nodes = 0;
  for (const RouteRef& r : routes_) nodes += r.size;
  for (const RouteRef& r : exit_routes_) nodes += r.size;
  result_.route_nodes_.reserve(nodes + nodes / 8 + 4096);  // and the tasks' own
  result_.route_begin_.reserve(routes_.size() + exit_routes_.size() + 1);
  // The actions' arrays sized once too: the moves and exits within the bound, the forgo actions
  // and (a guess, they may grow) two actions per task, two facts each.
  std::size_t actions = 2 * pending_.size() + (options_.select_goals ? pending_.size() : 0);
  for (std::uint32_t a = 0; a < k(); ++a) {
    for (std::uint32_t b = 0; b < k(); ++b) actions += a != b && dist_[a * k() + b] <= bound_;
    actions += ends_at_exit_ && exit_dist_[a] <= bound_;
  }
  builder_.reserve(actions, 2 * actions);
  result_.risk_.reserve(actions);
  result_.pass_begin_.reserve(actions + 1);
  result_.task_step_.reserve(actions);
  for (std::uint32_t a = 0; a < k(); ++a) {
    for (std::uint32_t b = 0; b < k(); ++b) {
      const Cost d = dist_[a * k() + b];
      if (a == b || d > bound_) continue;
      if (build_interrupted()) return;
      const std::span<const Node> route = this->route(routes_[a * k() + b]);
      const Fact pre[] = {{pos, static_cast<std::int32_t>(a)}};
      const Fact eff[] = {{pos, static_cast<std::int32_t>(b)}};
      add_action(pre, eff, d, key_name("go key ", a, " -> ", b), route, std::nullopt,
                 result_.graph_->route_risk(route, options_.risk.blockage_s));
    }
  }
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    if (build_interrupted()) return;
    // A task that no action can do from where the robot can get (a blockage in the way) is
    // dropped with that reason (goal selection) or named as the cause (issue 30), rather than
    // forgone or failed as if for the battery.
    add_task_actions(i, pos);
  }
  undoable_ = cut_off_tasks();
  if (options_.select_goals) {
    // Forgoing a task costs more than any plan within the bound (CompiledTask::penalty_unit()).
    const Cost penalty = 2 * (bound_ + 1);
    builder_.set_penalty_unit(penalty);
    for (std::size_t i = 0; i < pending_.size(); ++i) {
      const Task& task = mission_.task(pending_[i]);
      if (task.final) continue;
      if (std::find(undoable_.begin(), undoable_.end(), i) != undoable_.end()) {
        result_.dropped_.push_back(
            {pending_[i],
             "no position the robot can reach lets it do the task: " + blocked_reason(task)});
      }
      result_.forgo_actions_.emplace_back(
          ActionId{static_cast<std::uint32_t>(result_.task_step_.size())}, pending_[i]);
      const Fact pre[] = {{task_vars_[i], 0}};
      const Fact eff[] = {{task_vars_[i], 1}};
      add_action(pre, eff, penalty, "forgo '" + task.name + "'", {}, std::nullopt);
    }
  }
  for (std::uint32_t a = 0; ends_at_exit_ && a < k(); ++a) {
    if (exit_dist_[a] > bound_) continue;
    if (build_interrupted()) return;
    const Fact pre[] = {{pos, static_cast<std::int32_t>(a)}};
    const Fact eff[] = {{pos, exit_value}};
    add_action(pre, eff, exit_dist_[a], key_name("exit from key ", a), route(exit_routes_[a]),
               std::nullopt,
               result_.graph_->route_risk(route(exit_routes_[a]), options_.risk.return_s));
  }
  result_.task_ = std::move(builder_).build();
}

Result<SewerTask> compile_sewer_task(const SewerMap& map, const Mission& mission,
                                     const MissionProgress& progress,
                                     const CompileOptions& options) {
  SEWER_CHECK(progress.done.size() == mission.tasks.size(), "progress does not fit the mission");
  return SewerTaskCompiler(map, mission, progress, options).run();
}

Cost SewerTask::risk_cost(std::span<const ActionId> plan) const {
  Cost total = 0;
  for (ActionId a : plan) total += risk_[a.index()];
  return total;
}

StrandRisk SewerTask::strand_risk(std::span<const ActionId> plan,
                                  std::optional<Cost> budget) const {
  const Cost bound = budget.value_or(task_.cost_bound());
  struct Seen {
    std::uint32_t hazard = 0;
    double risk = 0;  // of being stranded by it
  };
  std::vector<Seen> seen;  // each hazard once, as its first drive past it leaves it
  Cost spent = 0;          // the plan's true cost before the action
  for (ActionId a : plan) {
    if (pass_begin_.empty()) break;
    for (std::uint32_t i = pass_begin_[a.index()]; i < pass_begin_[a.index() + 1]; ++i) {
      const HazardPass& pass = passes_[i];
      auto it = std::find_if(seen.begin(), seen.end(),
                             [&](const Seen& s) { return s.hazard == pass.hazard; });
      if (it != seen.end()) continue;
      const double p = hazard_probability_[pass.hazard];
      const WayBack& way = pass.way_back;
      // Insured, or the battery left backs out from it and on along a way out whose own hazards
      // it could back out of too: none; the battery for the way out but not for its hazards:
      // the chance that one of them blocks it as well; no battery for the way out: p.
      double risk = p;
      if (pass.covered || (way.full < kInfiniteCost && spent + way.full <= bound)) {
        risk = 0;
      } else if (way.plain < kInfiniteCost && spent + way.plain <= bound) {
        risk = p * way.risk;
      }
      seen.push_back({pass.hazard, risk});
    }
    const Cost cost = task_.real_cost(task_.cost(a));
    // A forgo action's cost is its penalty only (real cost 0); the expected cost of stops is
    // not battery.
    spent += cost - std::min(cost, risk_[a.index()]);
  }
  StrandRisk risk;
  double none = 1;
  for (const Seen& s : seen) {
    if (!(s.risk > 0)) continue;
    risk.uninsured.push_back(s.hazard);
    none *= 1 - s.risk;
  }
  std::sort(risk.uninsured.begin(), risk.uninsured.end());
  risk.probability = 1 - none;
  return risk;
}

std::vector<TaskId> SewerTask::forgone(std::span<const ActionId> plan) const {
  std::vector<TaskId> tasks;
  for (ActionId a : plan) {
    auto it = std::lower_bound(forgo_actions_.begin(), forgo_actions_.end(), a,
                               [](const auto& entry, ActionId id) { return entry.first < id; });
    if (it == forgo_actions_.end() || it->first != a) continue;
    // Tasks dropped already (no action does them) are forgone with the reason given then.
    const bool dropped = std::any_of(dropped_.begin(), dropped_.end(),
                                     [&](const DroppedTask& d) { return d.task == it->second; });
    if (!dropped) tasks.push_back(it->second);
  }
  std::sort(tasks.begin(), tasks.end());
  return tasks;
}

}  // namespace sewerplan::domain
