// SPDX-License-Identifier: MIT
// RouteStore: the compile's routes between keys, each a stretch of one vector of nodes.
//
// Private to domain. A compile keeps a route per pair of keys it searched (k^2 of them: 2,500 at 50
// tasks) and one per key to its nearest exit. Kept as vectors of their own, 13,000 routes on 1,000
// manholes were allocated, copied and freed one by one (a seventh of the plan's time, issue 16);
// here each is a (begin, size) reference into one store.
//
// The store grows as routes are kept. Grown by doubling on a large map it would copy itself whole
// between two stop checks (issue 14), so the compile sizes it once, after the start's search,
// from that search's routes: one row of k routes, times k searches and a half again. That guess
// is capped (kMaxReservedNodes): a long first row on a large mission would otherwise reserve
// gigabytes it never fills; past the cap the store grows by doubling as any vector.
//
//   RouteStore store;
//   RouteRef r = store.keep(search, node);        // the last search's path to `node`
//   for (Node n : store.route(r)) ...
//
// Thread safety: a value; one compile uses it on one thread.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "graph_search.h"
#include "position_graph.h"

namespace sewerplan::domain::detail {

// A route of the store: `size` nodes from `begin`. Empty: no route kept.
struct RouteRef {
  std::size_t begin = 0;
  std::size_t size = 0;
};

class RouteStore {
 public:
  // The most nodes reserve_rows() reserves at once: 16 Mi nodes, 64 MiB.
  static constexpr std::size_t kMaxReservedNodes = std::size_t{1} << 24U;

  void clear() { nodes_.clear(); }
  // Nodes held (the routes kept so far).
  std::size_t size() const { return nodes_.size(); }
  std::size_t capacity() const { return nodes_.capacity(); }

  // Sizes the store for `keys` rows like the one kept so far (and half as many again), at most
  // kMaxReservedNodes.
  void reserve_rows(std::size_t keys);

  // Appends the last run of `search`'s path to `n` (GraphSearch::append_path).
  RouteRef keep(const GraphSearch& search, Node n);
  // Appends `route` (of another store: a RouteMemo's).
  RouteRef keep(std::span<const Node> route);
  // Appends `first` and then `rest`: a RouteMemo's route from a task's spot, whose node number
  // is the compile's own (RouteMemo::SpotRow).
  RouteRef keep(Node first, std::span<const Node> rest);

  std::span<const Node> route(RouteRef r) const { return {nodes_.data() + r.begin, r.size}; }

 private:
  std::vector<Node> nodes_;
};

}  // namespace sewerplan::domain::detail
