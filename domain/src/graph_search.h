// SPDX-License-Identifier: MIT
// GraphSearch: Dijkstra's algorithm over a PositionGraph, reused for every key of a compile (and
// A* toward one target, guided by the routing index: run_toward).
//
// Private to domain. Forward from one source, or backward from many (every exit at once, giving
// each node's distance to its nearest exit). A run stops when every target is settled or the next
// node costs more than the bound, so on a large map it explores only the region around the
// mission's keys. The arrays are sized once and reset through the list of touched nodes; they may
// be a GraphCore's scratch (position_graph.h), kept clean for the next compile on the same map.
// Ties are broken by node number (among the nodes in the heap at once: a node reached at no cost
// from one settled at the same distance is settled after it), so the paths are the same on every
// run.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "position_graph.h"

namespace sewerplan::domain::detail {

class GraphSearch {
 public:
  enum class Direction { kForward, kBackward };

  // `scratch`: arrays to use (clean, see SearchScratch; they are left clean), or null for own.
  // Arrays smaller than the graph are grown here at once: see grow().
  explicit GraphSearch(const PositionGraph& graph, SearchScratch* scratch = nullptr);
  // Grows clean `scratch` arrays to `nodes` entries: distances and parents at once, as nothing is
  // written (zeroed_array.h), the bits in slices asking `stop` (if not null) between them (issue
  // 14: filling the arrays for a 100,000-manhole map took milliseconds without a check); false if
  // it fired first (the arrays stay clean; the next call goes on).
  static bool grow(SearchScratch& scratch, std::size_t nodes, const StopCondition* stop);
  GraphSearch(const GraphSearch&) = delete;
  GraphSearch& operator=(const GraphSearch&) = delete;
  ~GraphSearch();

  // With `goal`, the search also goes on until it has settled one node with goal[node], and
  // returns the first (the nearest), if one is within the bound: one search gives a key's routes
  // to the other keys and to its nearest exit (issue 16: a search per key and purpose was the
  // compile's cost).
  std::optional<Node> run(std::span<const Node> sources, std::span<const Node> targets, Cost bound,
                          Direction direction, const std::vector<bool>* goal = nullptr);
  // Forward from `source` until the first node with goal[node] is settled; returns it, if any
  // is reached within the bound.
  std::optional<Node> run_to_nearest(Node source, const std::vector<bool>& goal, Cost bound);
  // Issue 35: forward from `source` to `target` alone, toward it: A* (Hart, Nilsson and Raphael,
  // 1968), the nodes settled by their distance plus `to_target(node)`, a lower bound of the cost
  // from the node to the target that no move breaks (to_target(u) <= cost(u -> v) +
  // to_target(v); kInfiniteCost where the target cannot be reached at all). With the routing
  // index's distances on the graph without closures (ChQuery::distance_to_aim) it settles only
  // the nodes near some way not much dearer than the target's, where run() settles every node
  // nearer than the target. It goes on until every node that could lie on a shortest way is
  // settled, so that it can tell whether the way it found is the only shortest one: kUnique
  // then (and then it is the way run() finds: a node keeps its first shortest parent there, and
  // here each node of the way has exactly one), kTied if another is as short (either may be
  // run()'s), kUnreached
  // if the target lies beyond the bound (as run() leaves it), kGaveUp after `settle_limit`
  // settled nodes (the distances are then left unreached). path() and distance() give the way.
  //
  // With `rest_known` (not null), a settled node n whose estimate no node in the heap reaches
  // may end the search: rest_known(n) says whether the guide's own way from n to the target is
  // the only shortest one without closures, a way of this graph, and costs to_target(n) here
  // too (the caller unpacks it: ChQuery::way_to_aim). Then the way through n is the only
  // shortest one: kUnique, joined() is n, and path(n) and distance(n) give the way up to it (the
  // search walks no further along a way the guide knows: on a 100,000-manhole replan, 4 nodes
  // settled instead of the way's 160 to 620). Asked at the 1st, 2nd, 4th, 8th, ... node settled
  // while the target is not. Only on a graph with no cycle of cost 0 (GraphCore::free_passages
  // false): a node on such a cycle is tied by a later node of its own cycle, reached through
  // moves the question does not see yet.
  enum class Toward { kUnique, kTied, kUnreached, kGaveUp };
  Toward run_toward(Node source, Node target, Cost bound, std::size_t settle_limit,
                    const std::function<Cost(Node)>& to_target,
                    const std::function<bool(Node)>* rest_known = nullptr);
  // The node whose rest the last run_toward took (rest_known), if any; none after any other run.
  std::optional<Node> joined() const { return joined_; }
  // kInfiniteCost if not reached in the last run.
  Cost distance(Node n) const { return kInfiniteCost - dist_left_[n]; }
  // Forward: the nodes from the source to n. Backward: from n to its nearest source.
  void path(Node n, std::vector<Node>& out) const;
  // The same, appended to `out` (which keeps what it held).
  void append_path(Node n, std::vector<Node>& out) const;
  // Asked every 256 settled nodes; when it says stop, the run ends there and interrupted() holds.
  void set_interrupt(std::function<bool()> interrupt) { interrupt_ = std::move(interrupt); }
  bool interrupted() const { return interrupted_; }
  // Nodes settled over all runs (a measure of work).
  std::size_t settled_total() const { return settled_total_; }

 private:
  const PositionGraph& graph_;
  SearchScratch own_;
  SearchScratch& scratch_;
  // The scratch's encodings (SearchScratch): clean is zero.
  void set_distance(Node n, Cost d) { dist_left_[n] = kInfiniteCost - d; }
  Node parent(Node n) const { return parent_plus_one_[n] - 1U; }  // kNoParent: none
  void set_parent(Node n, Node p) { parent_plus_one_[n] = p + 1U; }

  ZeroedArray<Cost>& dist_left_;
  ZeroedArray<Node>& parent_plus_one_;
  std::vector<bool>& settled_;
  std::vector<bool>& is_target_;
  std::vector<bool>& tied_;
  std::vector<Node>& touched_;
  std::vector<std::pair<Cost, Node>>& heap_;
  Direction direction_ = Direction::kForward;
  std::size_t settled_total_ = 0;
  std::function<bool()> interrupt_;
  bool interrupted_ = false;
  std::optional<Node> joined_;

  void reset();
  // Settles the heap's nodes until done(node) says stop or the heap runs dry; returns the node
  // that stopped it.
  template <class Done>
  std::optional<Node> settle(Cost bound, Direction direction, Done&& done);
  // Whether every node of the way to `target` (but the source) has exactly one settled
  // predecessor that reaches it at its distance: none is tied_ (run_toward counts them as it
  // relaxes, each settled node's moves once, so a move that two settled nodes both make at the
  // same distance, or one node twice, marks it).
  bool only_shortest_way(Node target) const;
  // Leaves the nodes reached but not settled unreached.
  void forget_unsettled();
};

}  // namespace sewerplan::domain::detail
