// SPDX-License-Identifier: MIT
// PipeKeyRoutes: the routes of the keys in one pipe, from searches of the pipe's end slots.
//
// Private to domain. A key in a pipe (a pipe end, or a task's spot) has no move but out of the
// pipe: its first move drives to one of the pipe's end slots (two at most). So its routes are
// the cheaper of the slots' routes, each after that first drive. A pipe task has three keys (its
// two ends and its spot): two searches, one from each end slot, give all three rows, where the
// compile searched from every key (issue 16: 116 route searches against 51 Dijkstras at 50
// tasks on 1,000 manholes).
//
// The rows are those of a search from the key itself (GraphSearch::run with the same targets,
// goal and bound), route for route: where one slot is strictly cheaper, the key's search settles
// the nodes on that side in the slot search's order, so it takes the same parents. Where both
// slots give a key (or the nearest exit) the same cost, the key's own search could take either
// way: row() says so, and the caller searches from that key. The rows are exact when every key
// a search may settle besides its targets is one no move enters (usable() checks this).
//
//   PipeKeyRoutes pipe(graph, keys);
//   if (pipe.usable(group, ...) && pipe.search(search, group, targets, exits)) {
//     for (const PipeKeyRoutes::Key& key : group)
//       if (!pipe.row(key, dist_row, route_row, store, exit)) ... search from the key ...
//   }
//
// Thread safety: a value; one compile uses it on one thread.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "graph_search.h"
#include "position_graph.h"
#include "route_store.h"

namespace sewerplan::domain::detail {

class PipeKeyRoutes {
 public:
  // A key of the compile (its index in `keys`) and the bound of its search.
  struct Key {
    std::size_t index = 0;
    Cost bound = 0;
  };
  // A key's way to its nearest exit.
  struct Exit {
    Cost cost = kInfiniteCost;
    RouteRef route;
  };

  // `keys`: the compile's keys, all of them (a row has an entry per key).
  PipeKeyRoutes(const PositionGraph& graph, std::span<const Node> keys);

  // Whether the keys of `group` (two or more, in one pipe) can take their rows from searches of
  // the pipe's end slots, fewer of those than keys: the pipe can be entered (from a key in it a
  // search reaches only positions the robot can drive to, so no key that no move enters), and
  // `only_targets_entered`: every key a move enters is a target of the searches (the caller knows:
  // a key the start reaches within the bound, searched within what is left, settles no key the
  // start does not reach; a task's spot, searched within the whole bound, may).
  bool usable(std::span<const Key> group, bool only_targets_entered) const;

  // Searches from each end slot the group's keys drive to first, within the largest bound a key
  // leaves for it, for `targets` and (if not null) the nearest node with goal[node], as the keys'
  // own searches would. False if the search was interrupted.
  bool search(GraphSearch& search, std::span<const Key> group, std::span<const Node> targets,
              const std::vector<bool>* goal);

  // The row of `key` (one of the last search()'s group): its distance to every key (dist, an entry
  // per key; kInfiniteCost: not reached), its routes (kept in `store`, none to itself or where
  // not reached) and, with a goal, its way to the nearest one. False, with nothing written, where
  // two slots tie for a key or the goal: the key's own search must decide.
  bool row(const Key& key, std::span<Cost> dist, std::span<RouteRef> routes, RouteStore& store,
           Exit& exit) const;

  // Sizes the slot searches' route store for two rows of `row_nodes` (issue 14: not grown by
  // doubling between two stop checks).
  void reserve(std::size_t row_nodes);

  // Searches run by search() since construction.
  std::size_t searches() const { return searches_; }

 private:
  // A search from an end slot: its distance to every key, its routes to them (in store_), and the
  // nearest goal it settled.
  struct SlotRow {
    Node slot = 0;
    std::vector<Cost> dist;
    std::vector<RouteRef> routes;
    std::optional<Node> goal;
    Cost goal_dist = kInfiniteCost;
    RouteRef goal_route;
  };
  // A key's first moves: (slot, cost).
  using FirstMoves = std::vector<std::pair<Node, Cost>>;

  FirstMoves first_moves(Node key) const;
  const SlotRow* slot_row(Node slot) const;
  // The cheapest (cost, row) over the first moves `moves` and a row's `value` (kInfiniteCost:
  // none within `bound`); `tie` is set where two rows give that cost.
  template <class Value>
  std::pair<Cost, const SlotRow*> cheapest(const FirstMoves& moves, Cost bound, Value&& value,
                                           bool& tie) const;

  const PositionGraph& graph_;
  std::span<const Node> keys_;
  std::vector<SlotRow> rows_;  // the last group's slots
  std::size_t row_count_ = 0;
  RouteStore store_;  // the slot rows' routes
  std::size_t searches_ = 0;
};

}  // namespace sewerplan::domain::detail
