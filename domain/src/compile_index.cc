// SPDX-License-Identifier: MIT
// The sewer compiler's routes from the routing index (issue 35, CompileCache::RoutingIndex): a
// key's row taken from the contraction hierarchy of the cache's core where it is exactly what the
// route search would give (sewer_task_compiler.h).
//
// Why the index's route is the search's, where it is taken: the index is built over the core's
// adjacency, the moves of a graph without closures, blockages or hazards (G). The mission's graph
// (G') has those moves less the ones its closures, blockages and closed passages remove, some
// dearer by a hazard's risk, and none cheaper or new among the map's nodes (extra spots are never
// entered by a move). A route that is the only shortest way in G (ChQuery's `unique`, from a
// hierarchy built with keep_ties) and whose every move G' has at the same cost
// (PositionGraph::reads_adjacency) is then the only shortest way in G' too: any other way of G' of
// no greater cost would be a way of G of no greater cost. Each of its prefixes is the only
// shortest way to its node, so the route search, which keeps a node's first shortest parent
// (graph_search.h), finds that route, whatever order it settles nodes of equal distance in. A
// key beyond the bound in G is beyond it in G'. The nearest exit is taken only where one exit
// node is strictly nearest (an exit reached in G' at its G distance stays the nearest in G');
// which of several at one distance a search settles first depends on its order, not only on
// the nodes' numbers, where moves cost 0 (a pipe's end to its slot, a free passage).
#include <algorithm>
#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "contraction_hierarchy.h"
#include "sewer_task_compiler.h"

namespace sewerplan::domain {

namespace {
// kAuto builds the index when the searches from the other keys would settle this many times the
// graph's positions: its build takes 60 to 150 plain Dijkstras over the map, and the compile's
// searches cost 1.2 to 1.6 times a plain Dijkstra per node settled (docs/benchmarks.md), so that
// below this one compile pays more for the build than it saves. Measured 2026-12-07 on 100,000
// scrambled manholes, 20 tasks over the whole network (31 times): a compile of 4.7 s searching,
// 4.4 s building the index and 0.04 s taking the routes from it; on 10,000, 0.14 s against 0.34 s.
// The Replanner's later compiles take most rows from the last one's (route_memo.h), so they
// seldom repay it either; an index built once beside the map is the way to have it.
constexpr std::size_t kIndexFactor = 100;
// The nearest exits come from the index when the exit nodes are at most this many per key
// (index_exit).
constexpr std::size_t kIndexExitsPerKey = 4;
// The searches toward single targets of a row (guided_routes) settle at most this share of the
// graph's nodes (1 / kGuidedShare) before the rest go to one search of the row: each settles the
// nodes near a way not much dearer than its target's, hundreds where the search settles the
// network, but a target cut off settles all that could reach it without the closure.
constexpr std::size_t kGuidedShare = 16;
// After this many guided searches that found a tie, and more of them than ways found, a compile
// guides no more (guided_routes).
constexpr std::size_t kGuidedTiesTried = 4;

// A table's sources: sorted, each once (rows are found by binary search: best_start).
void sort_unique(std::vector<Node>& nodes) {
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
}
}  // namespace

detail::ChQuery* SewerTaskCompiler::routing_index(bool may_build, std::size_t settled_estimate) {
  if (options_.cache == nullptr) return nullptr;
  PositionGraph& graph = *result_.graph_;
  detail::GraphCore& core = graph.core();
  if (core.hierarchy_query != nullptr) return core.hierarchy_query.get();
  const CompileCache::RoutingIndex policy = options_.cache->routing_index();
  if (!may_build || !core_is_cached_ || core.hierarchy_failed ||
      policy == CompileCache::RoutingIndex::kNever) {
    return nullptr;
  }
  // kAuto: not where the build costs more than the searches, nor under a deadline or a cancel (a
  // build stopped half-way serves nothing, and the searches it held up may have finished).
  if (policy == CompileCache::RoutingIndex::kAuto &&
      (settled_estimate <= kIndexFactor * graph.size() || options_.stop.can_interrupt())) {
    return nullptr;
  }
  if (!graph.has_adjacency() && !graph.build_adjacency(&options_.stop)) return nullptr;
  auto built = detail::ContractionHierarchy::build(
      core.adjacency_begin, core.adjacency_to, core.adjacency_cost,
      {.keep_ties = true, .stop = options_.stop.can_interrupt() ? &options_.stop : nullptr});
  if (!built.has_value()) {
    // Stopped: the next search stops at its check. A cost too large for the index's edges: the
    // searches serve this map.
    core.hierarchy_failed = built.error().code != ErrorCode::kCancelled;
    return nullptr;
  }
  core.hierarchy = std::make_shared<const detail::ContractionHierarchy>(std::move(*built));
  core.hierarchy_query = std::make_shared<detail::ChQuery>(*core.hierarchy);
  return core.hierarchy_query.get();
}

std::vector<SewerTaskCompiler::IndexStart> SewerTaskCompiler::index_starts(std::size_t a) const {
  const PositionGraph& graph = *result_.graph_;
  const Node n = keys_[a];
  if (!graph.is_extra_spot(n)) return {{n, 0}};
  std::vector<IndexStart> starts;
  graph.for_each_successor(n, [&](Node to, Cost c) { starts.push_back({to, c}); });
  return starts;
}

const std::vector<Node>& SewerTaskCompiler::index_sources() {
  if (!index_sources_.empty()) return index_sources_;
  // Every key that is a node of the map, and the slots at the ends of the others' pipes (where
  // their drives out end).
  const PositionGraph& graph = *result_.graph_;
  for (Node n : keys_) {
    if (!graph.is_extra_spot(n)) {
      index_sources_.push_back(n);
      continue;
    }
    for (const PipeEnd& end : map_.pipe(*graph.pipe_of(n)).ends) {
      if (end.manhole) index_sources_.push_back(graph.at_slot(*end.manhole, end.slot));
    }
  }
  sort_unique(index_sources_);
  return index_sources_;
}

template <class Distance>
std::optional<std::size_t> SewerTaskCompiler::best_start(std::span<const IndexStart> starts,
                                                         std::span<const Node> sources,
                                                         Distance distance, Cost* cost) {
  *cost = kInfiniteCost;
  std::optional<std::size_t> best;
  bool tied = false;
  for (const IndexStart& start : starts) {
    const auto at = std::lower_bound(sources.begin(), sources.end(), start.node);
    const auto i = static_cast<std::size_t>(at - sources.begin());
    const Cost d = distance(i);
    if (d == kInfiniteCost) continue;
    if (start.cost + d < *cost) {
      *cost = start.cost + d;
      best = i;
      tied = false;
    } else if (start.cost + d == *cost) {
      tied = true;
    }
  }
  if (tied) return std::nullopt;
  return best;
}

SewerTaskCompiler::IndexTable& SewerTaskCompiler::index_table(detail::ChQuery& index,
                                                              std::size_t a) {
  // A replan (the last compile's rows kept on the core, route_memo.h) takes most rows from
  // them: the start's row has a table of its own then, and the others one only if some row
  // needs it. A first compile needs every row's: one table for all.
  const bool own = a == 0 && result_.graph_->core().route_memo != nullptr;
  IndexTable& table = own ? start_table_ : keys_table_;
  if (table.built) return table;
  table.built = true;
  if (own) {
    for (const IndexStart& start : index_starts(0)) table.sources.push_back(start.node);
    sort_unique(table.sources);
  } else {
    table.sources = index_sources();
  }
  // The routes between the sources and every target at once (ChQuery::table_with_ways): one
  // upward search per source and per target, where a query per pair took two each.
  index.table_with_ways(table.sources, index_table_targets_, table.table);
  return table;
}

SewerTaskCompiler::IndexAnswer SewerTaskCompiler::index_route(detail::ChQuery& index, std::size_t a,
                                                              std::span<const IndexStart> starts,
                                                              Node t, Cost bound, Cost* cost) {
  const IndexTable& table = index_table(index, a);
  const auto column = std::lower_bound(index_table_targets_.begin(), index_table_targets_.end(), t);
  const auto j = static_cast<std::size_t>(column - index_table_targets_.begin());
  const std::optional<std::size_t> row = best_start(
      starts, table.sources, [&](std::size_t i) { return table.table.distance(i, j); }, cost);
  if (*cost > bound) return IndexAnswer::kTaken;
  if (!row || !table.table.unique(*row, j)) return IndexAnswer::kTied;
  const PositionGraph& graph = *result_.graph_;
  const std::function<bool(Node, Node)> reads = [&](Node from, Node to) {
    return graph.reads_move(from, to);
  };
  if (!table.table.way(*row, j, index_path_, &reads)) return IndexAnswer::kTouched;
  return takes_index_path(a) ? IndexAnswer::kTaken : IndexAnswer::kTouched;
}

bool SewerTaskCompiler::takes_index_path(std::size_t a) {
  const PositionGraph& graph = *result_.graph_;
  if (!graph.reads_adjacency(index_path_)) return false;
  if (graph.is_extra_spot(keys_[a])) index_path_.insert(index_path_.begin(), keys_[a]);
  return true;
}

void SewerTaskCompiler::index_row(detail::ChQuery& index, GraphSearch& search, std::size_t a,
                                  std::span<const Node> targets, Cost bound, bool exit_goal,
                                  std::optional<Node>* exit) {
  const std::vector<IndexStart> starts = index_starts(a);
  // The targets whose route the index does not give: a search finds those, and only those (its
  // route to a node does not depend on its other targets or where it stops: the nodes settle in
  // (distance, node) order and a settled node's parent is final). Those whose route is the only
  // shortest way without closures but touched by one are searched toward alone (guided_routes),
  // which settles far fewer nodes where the closure's detour is short; but only where the row
  // needs no search for a tied route: one that does settles most of them on its way (on 10,000
  // scrambled manholes, a replan's guided searches cost more than they saved it).
  std::vector<Node> missed;
  std::vector<Node> touched;
  for (Node t : targets) {
    const std::uint32_t b = key_of_.at(t);
    if (b == a) continue;
    Cost d = kInfiniteCost;
    switch (index_route(index, a, starts, t, bound, &d)) {
      case IndexAnswer::kTied:
        missed.push_back(t);
        break;
      case IndexAnswer::kTouched:
        touched.push_back(t);
        break;
      case IndexAnswer::kTaken:
        if (d <= bound) {
          dist_[a * k() + b] = d;
          routes_[a * k() + b] = route_store_.keep(index_path_);
        }
        break;
    }
  }
  dist_[a * k() + a] = 0;
  *exit = std::nullopt;
  const bool exit_missed = exit_goal && !index_exit(index, a, bound, exit);
  if (missed.empty() && !touched.empty()) guided_routes(index, search, a, bound, touched);
  missed.insert(missed.end(), touched.begin(), touched.end());
  std::sort(missed.begin(), missed.end());
  if (missed.empty() && !exit_missed) {
    ++result_.statistics_.index_rows;
    return;
  }
  const std::optional<Node> nearest =
      search.run(std::span<const Node>(&keys_[a], 1), missed, bound,
                 GraphSearch::Direction::kForward, exit_missed ? &exit_node() : nullptr);
  ++result_.statistics_.route_searches;
  for (Node t : missed) {
    const std::uint32_t b = key_of_.at(t);
    dist_[a * k() + b] = search.distance(t);
    if (dist_[a * k() + b] != kInfiniteCost) keep_path(search, t, routes_[a * k() + b]);
  }
  if (exit_missed && nearest) {
    *exit = nearest;
    exit_dist_[a] = search.distance(*nearest);
    keep_path(search, *nearest, exit_routes_[a]);
  }
}

void SewerTaskCompiler::guided_routes(detail::ChQuery& index, GraphSearch& search, std::size_t a,
                                      Cost bound, std::vector<Node>& touched) {
  const PositionGraph& graph = *result_.graph_;
  const Node source = keys_[a];
  std::size_t budget = graph.size() / kGuidedShare;
  const std::function<bool(Node, Node)> reads = [&](Node from, Node to) {
    return graph.reads_move(from, to);
  };
  std::vector<Node> left;
  for (Node t : touched) {
    // Where the guided searches mostly find ties (a profile with free passages: every way
    // through a manhole then has a cycle of cost 0, and none is the only shortest), the row's
    // search finds them anyway: this compile guides no more.
    const bool tie_bound = guided_tied_ > kGuidedTiesTried && guided_tied_ > guided_unique_;
    if (budget == 0 || tie_bound || search.interrupted()) {
      left.push_back(t);
      continue;
    }
    index.aim_at(t);
    const std::size_t before = search.settled_total();
    // An extra spot (the source, never entered by a move) is no node of the index: 0 bounds it.
    // The search stops where the rest of the way is the index's own (way_to_aim).
    Cost rest_cost = 0;
    const std::function<bool(Node)> rest_known = [&](Node n) {
      return !graph.is_extra_spot(n) && index.way_to_aim(n, rest_, &reads, &rest_cost);
    };
    const GraphSearch::Toward toward = search.run_toward(
        source, t, bound, budget,
        [&](Node n) { return graph.is_extra_spot(n) ? 0 : index.distance_to_aim(n); },
        graph.core().free_passages ? nullptr : &rest_known);
    budget -= std::min(budget, search.settled_total() - before);
    const std::uint32_t b = key_of_.at(t);
    switch (toward) {
      case GraphSearch::Toward::kUnique:
        if (const std::optional<Node> joined = search.joined()) {
          dist_[a * k() + b] = search.distance(*joined) + rest_cost;
          search.path(*joined, index_path_);
          index_path_.insert(index_path_.end(), rest_.begin() + 1, rest_.end());
          routes_[a * k() + b] = route_store_.keep(index_path_);
        } else {
          dist_[a * k() + b] = search.distance(t);
          keep_path(search, t, routes_[a * k() + b]);
        }
        ++result_.statistics_.guided_searches;
        ++guided_unique_;
        break;
      case GraphSearch::Toward::kUnreached:
        dist_[a * k() + b] = kInfiniteCost;
        ++result_.statistics_.guided_searches;
        break;
      case GraphSearch::Toward::kTied:
        ++guided_tied_;
        left.push_back(t);
        break;
      case GraphSearch::Toward::kGaveUp:
        left.push_back(t);
        break;
    }
  }
  touched = std::move(left);
}

bool SewerTaskCompiler::index_exit(detail::ChQuery& index, std::size_t a, Cost bound,
                                   std::optional<Node>* exit) {
  const PositionGraph& graph = *result_.graph_;
  const std::vector<Node>& exits = graph.core().marked_exits;
  // The index's table costs an upward search per exit node; a search from the key stops at the
  // first exit it settles, which is near where exits are many (2 % of the manholes on the
  // scrambled networks: 8,000 exit nodes at 100,000 manholes, and a table of 0.3 s).
  if (exits.size() > kIndexExitsPerKey * k()) return false;
  IndexTable& table = index_table(index, a);
  if (!table.exits_built) {
    // The table's sources' distances to every exit node at once.
    table.exits_built = true;
    if (!exits.empty()) index.table(table.sources, exits, table.exits);
  }
  // The exit a search settles first: the one nearest, when no other exit node lies as near. (With
  // moves of cost 0, a pipe's end to its slot or a free passage, the search does not settle the
  // nodes at one distance by number: a slot reached at no cost from one settled after another
  // exit at that distance is settled after it. Exits tied in distance go to the search.)
  Cost best = kInfiniteCost;
  std::optional<std::size_t> best_exit;
  std::optional<std::size_t> best_row;
  bool tied = false;
  const std::vector<IndexStart> starts = index_starts(a);
  for (std::size_t j = 0; j < exits.size(); ++j) {
    Cost d = kInfiniteCost;
    const std::optional<std::size_t> row = best_start(
        starts, table.sources, [&](std::size_t i) { return table.exits[i * exits.size() + j]; },
        &d);
    if (d == kInfiniteCost) continue;
    if (d < best) {
      best = d;
      best_exit = j;
      best_row = row;
      tied = false;
    } else if (d == best) {
      tied = true;
    }
  }
  if (!best_exit || best > bound) {
    *exit = std::nullopt;
    return true;
  }
  if (tied || !best_row) return false;
  bool unique = false;
  (void)index.path(table.sources[*best_row], exits[*best_exit], index_path_, &unique);
  if (!unique || !takes_index_path(a)) return false;
  exit_dist_[a] = best;
  exit_routes_[a] = route_store_.keep(index_path_);
  *exit = exits[*best_exit];
  return true;
}

}  // namespace sewerplan::domain
