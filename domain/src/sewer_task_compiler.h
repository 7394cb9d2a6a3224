// SPDX-License-Identifier: MIT
// The sewer compiler's working state (private to domain): one compile of a map, a mission and its
// progress into a SewerTask (compile.h). Its parts live in four files:
//   compile.cc             the compile's course (run), the goals, the task's actions;
//   compile_routes.cc      the keys and the route searches between them, with the route memo's
//                          rows taken from and kept for the next compile (route_memo.h, issue 35);
//   compile_index.cc       the routes taken from the routing index where it gives the search's
//                          (CompileCache::RoutingIndex, issue 35);
//   compile_contingency.cc the contingency reserves: the battery to back out of a hazard and reach
//                          an exit another way (CompileOptions::contingency, issue 34).
// Thread safety: one compile per object, on one thread.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "sewerplan/domain/compile.h"

#include "compile_reasons.h"
#include "contraction_hierarchy.h"
#include "graph_search.h"
#include "position_graph.h"
#include "route_memo.h"
#include "route_store.h"

namespace sewerplan::domain {

using detail::GraphSearch;
using detail::Node;
using detail::PositionGraph;
using detail::RouteRef;

class SewerTaskCompiler {
 public:
  SewerTaskCompiler(const SewerMap& map, const Mission& mission, const MissionProgress& progress,
                    const CompileOptions& options)
      : map_(map), mission_(mission), progress_(progress), options_(options) {
    std::shared_ptr<detail::GraphCore> core = cached_core();
    core_is_cached_ = core != nullptr;
    result_.graph_ = std::make_unique<PositionGraph>(map, mission, std::move(core), &options_.stop);
  }

  Result<SewerTask> run();

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
  std::shared_ptr<detail::GraphCore> cached_core() const;

  // Leaves out the pending tasks known to be impossible; what remains impossible is returned.
  std::string select_goals(const detail::CompileReasons& reasons);

  void select_tasks();

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

  void collect_keys(PositionGraph& graph);

  // Keys a route can end at: not task spots (only task actions enter them), and not pipe ends
  // that no move enters (the robot's limits forbid every passage into that pipe there). A route
  // search stops once all its targets are settled, so an unreachable target would make it
  // explore everything within the bound.
  std::vector<Node> route_targets() const;

  // Whether some move ends at n from a position the robot can itself get to: "in manhole" only
  // as the start, a slot only out of a pipe it can drive (or starts in).
  bool can_be_entered(Node n) const;

  void route(GraphSearch& search);

  // What every row after the start's routes to (route()): the route targets, those the start
  // reaches within the bound (and by key), and the exit marks a row's search also goes to (null:
  // none).
  struct RowTargets {
    const std::vector<Node>& all;
    const std::vector<Node>& reachable;
    const std::vector<bool>& reachable_key;
    const std::vector<bool>* exits;
  };
  // Key a's row: from the last compile's memo, the routing index (`index`, if not null) or a
  // search, and kept in the memo for the next compile.
  void route_row(GraphSearch& search, detail::ChQuery* index, std::size_t a,
                 const RowTargets& rows);

  // The last compile's rows (RouteMemo), when this compile may take from them, and this
  // compile's context for the next.
  void open_memo(const std::vector<Node>& reachable, bool exit_goal);

  // Takes key a's row from the last compile's (RouteMemo), if it is what a search within `bound`
  // would find.
  bool reuse_row(std::size_t a, Cost bound, const std::vector<bool>& reachable_key);

  // Keeps key a's row for the next compile (RouteMemo::Row).
  void remember_row(std::size_t a, Cost bound, std::optional<Node> exit,
                    const std::vector<bool>& reachable_key);

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
                      const std::vector<bool>& reachable_key, bool exit_goal);

  // Keeps key a's spot row for the next compile (RouteMemo::SpotRow): every key it settled.
  void remember_spot_row(std::size_t a, std::optional<Node> exit);

  // Marks the mission's exits in the core's exit marks (unmarking the last compile's, unless they
  // are the same).
  void mark_exits();
  const std::vector<bool>& exit_node() const { return result_.graph_->core().exit_marks; }

  // Whether some pending task has no key the start reaches within the bound (row 0 of dist_).
  bool needs_unbounded_diagnosis() const;

  // The routes of the last search, from key a; `exit`: the nearest exit it settled. With `only`,
  // to a itself and the keys it marks.
  void store_routes(GraphSearch& search, std::size_t a, std::optional<Node> exit,
                    const std::vector<bool>* only = nullptr);

  // Issue 35: the routing index (contraction_hierarchy.h) of the cache's core, built here if the
  // cache's policy asks for it (CompileCache::RoutingIndex; `settled_estimate`: the nodes the
  // searches from the other keys would settle, for kAuto; `may_build`: false before any search);
  // null: every route comes from a search.
  detail::ChQuery* routing_index(bool may_build, std::size_t settled_estimate);
  // Where a route from key a starts in the index: the key itself, or (an extra spot, not in the
  // index) the slots its drives out of its pipe reach, with their cost in this graph.
  struct IndexStart {
    Node node;
    Cost cost;
  };
  std::vector<IndexStart> index_starts(std::size_t a) const;
  // The nodes the index's routes from the keys start at (index_starts, of every key), sorted;
  // computed once into index_sources_.
  const std::vector<Node>& index_sources();
  // Of `starts` (of key a), the one whose way to column j of `distance` (by row: the position
  // in `sources`, sorted) is shortest, as a search from a settles it: its row and the way's cost
  // in `*cost` (kInfiniteCost: none), or nothing where two starts tie.
  template <class Distance>
  std::optional<std::size_t> best_start(std::span<const IndexStart> starts,
                                        std::span<const Node> sources, Distance distance,
                                        Cost* cost);
  // The route from key a (starting at `starts`) to t (one of index_table_targets_), as a search
  // from a finds it: kTaken with its cost in `*cost` (kInfiniteCost: none), within `bound` the
  // route in index_path_. kTied where it lies within the bound but is not the only shortest way
  // (or two starts tie); kTouched where it is, but not one of this graph's (a closure, blockage
  // or hazard touches it).
  enum class IndexAnswer { kTaken, kTied, kTouched };
  IndexAnswer index_route(detail::ChQuery& index, std::size_t a, std::span<const IndexStart> starts,
                          Node t, Cost bound, Cost* cost);
  // Key a's routes to `touched` (targets whose index route a closure touches), each from a
  // search toward it guided by the index (GraphSearch::run_toward) where that finds the only
  // shortest way; the others are left in `touched` for a search from a. Stops guiding once the
  // guided searches have settled a sixteenth of the graph: beyond that one search costs less.
  void guided_routes(detail::ChQuery& index, GraphSearch& search, std::size_t a, Cost bound,
                     std::vector<Node>& touched);
  // Whether index_path_ (from one of key a's starts) is a route of this mission's graph
  // (PositionGraph::reads_adjacency); if so it becomes key a's, from a itself.
  bool takes_index_path(std::size_t a);
  // Key a's row, as a search from it within `bound` to `targets` (and to its nearest exit, with
  // `exit_goal`) would give it: the routes to the targets (and to a itself) within the bound, the
  // others left unreached, and the exit in `*exit`. From the index where its route is the only
  // shortest way and one of this mission's graph (PositionGraph::reads_adjacency); the others
  // from one search (`search`) to those targets alone.
  void index_row(detail::ChQuery& index, GraphSearch& search, std::size_t a,
                 std::span<const Node> targets, Cost bound, bool exit_goal,
                 std::optional<Node>* exit);
  // Key a's nearest exit within `bound` from the index, as a search would settle it first (least
  // distance, then node), with its route stored in exit_dist_ and exit_routes_; false, with
  // nothing stored, where a search must find it. `*exit`: none when no exit is within the bound.
  bool index_exit(detail::ChQuery& index, std::size_t a, Cost bound, std::optional<Node>* exit);

  // Each key's cheapest way to its nearest exit, where the key's own search (bounded by what is
  // left of the battery after reaching the key) did not settle one: a forward search that stops
  // at the first exit it settles, within the whole battery, so that the reasons given for an
  // impossible mission name the right energy. (One backward search from all exits would grow a
  // ball around every exit of the city; with exits every few manholes the forward balls are
  // small.)
  // Where the routing index (`index`, if not null) gives a key's way, it is taken from it.
  void route_to_exits(GraphSearch& search, const std::vector<Node>& targets,
                      detail::ChQuery* index);

  // Takes key a's way to its nearest exit from the last compile's (RouteMemo::ExitSearch), if it
  // is what a search within the bound would find. A spot's is kept by its pipe and offset, its
  // route renumbered from its first node (RouteMemo::SpotRow).
  bool reuse_exit_search(std::size_t a);

  void remember_exit_search(std::size_t a, std::optional<Node> exit);

  // What blocks a task in a pipe, for the reason given when it is dropped.
  std::string blocked_reason(const Task& task) const;

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
  Cost exit_need(Node from, PipeId first, std::optional<PipeId> second);
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
  WayOut way_out(Node from, PipeId first);
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
                    std::optional<PipeId> blocked = std::nullopt);
  // in_pipe_need over every pipe a route drives.
  Cost route_need(std::span<const Node> route, std::optional<PipeId> blocked = std::nullopt);
  // The hazards a route's pipe drives pass, noted uncovered (without contingency).
  void note_route(std::span<const Node> route);
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
  std::vector<Node> rest_;  // guided_routes: the index's rest of a way (ChQuery::way_to_aim)
  std::vector<RouteRef> routes_;
  std::vector<Cost> exit_dist_;
  std::vector<RouteRef> exit_routes_;
  // The routing index's tables between sources and the route targets (sorted), each built on
  // its first index_route: the start's from its own starts, the other keys' from
  // index_sources() (a replan takes most of those rows from the last compile, and needs no
  // table for them); and the same sources' distances to each exit node, on the first
  // index_exit.
  struct IndexTable {
    bool built = false;
    std::vector<Node> sources;  // sorted
    detail::ChTable table;
    bool exits_built = false;
    std::vector<Cost> exits;  // by source, then exit node (GraphCore::marked_exits)
  };
  IndexTable& index_table(detail::ChQuery& index, std::size_t a);
  std::vector<Node> index_sources_;  // index_sources(), on the first use
  std::vector<Node> index_table_targets_;
  IndexTable start_table_;
  IndexTable keys_table_;
  // The graph's core is the cache's (not a throwaway one made while another compile held it):
  // only then is an index built on it kept.
  bool core_is_cached_ = false;
  std::vector<Node> index_path_;  // a route's buffer
  // Guided searches of this compile that found the only shortest way, and that found a tie.
  std::size_t guided_unique_ = 0;
  std::size_t guided_tied_ = 0;
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
