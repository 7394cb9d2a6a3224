// SPDX-License-Identifier: MIT
// ContractionHierarchy: a per-map routing index over the position graph's moves (issue 35).
//
// Private to domain. A contraction hierarchy (Geisberger, Sanders, Schultes and Delling,
// "Contraction Hierarchies: Faster and Simpler Hierarchical Routing in Road Networks", WEA 2008)
// orders the nodes of a directed graph and contracts them one by one, lowest first: a node v is
// taken out, and for each pair of moves u -> v -> w whose cost no other way between u and w
// matches without v (a bounded "witness" Dijkstra finds such a way), a shortcut u -> w with that
// cost is added, remembering v as its middle node. Every shortest path then has an equally short
// form that climbs to higher nodes only, then descends: a query searches upward from the source
// (on the moves and shortcuts to higher nodes) and upward from the target backward, and meets at
// the highest node of the way. On a road-like graph each side settles a few hundred nodes where a
// Dijkstra settles the map. Many-to-many tables use the bucket method (Knopp, Sanders, Schultes,
// Schulz and Wagner, "Computing Many-to-Many Shortest Paths Using Highway Hierarchies", ALENEX
// 2007): an upward backward search from each target leaves (target, distance) in a bucket at every
// node it settles, and an upward forward search from each source scans the buckets it settles.
// Both sides prune with stall-on-demand (a node reached more cheaply from above is not expanded).
//
// The graph is the GraphCore's adjacency (position_graph.h: the moves out of each of the map's
// nodes, without closures, blockages or hazards), or any compressed-sparse-row graph with integer
// costs. The hierarchy stores its edges by rank, each once: the upward edges u -> w (rank w >
// rank u) at u, and the upward edges of the reverse graph (moves w -> u with rank w > rank u) at u,
// each with a 32-bit cost (build fails if a move or shortcut costs 2^32 - 1 ms, 49 days, or more:
// a shortcut costs no more than the shortest way between its ends, and the longest key-to-key
// route on 100,000 scrambled manholes is 25 h) and its middle node (none for a move of the graph).
// About 140-160 bytes per manhole + pipe of the map; a ChQuery's buffers add 30 bytes per node
// (about 80 per manhole + pipe).
//
// The compile takes its routes from it on a CompileCache that asks for it (compile_index.cc),
// where a route is the only shortest way: among equal-cost alternatives the route search keeps
// a node's first shortest parent (graph_search.h) and a hierarchy's path may be another one
// (docs/benchmarks.md, issue 35). Built with
// ChOptions::keep_ties, the hierarchy keeps every shortest way (Geisberger et al. drop a shortcut
// for a witness of equal cost; here it must be shorter), and a query counts the shortest ways
// (1 or more): each shortest way of the graph has exactly one up-down form (its nodes that are
// higher than every node between them and the source, or the target), so where the count is 1
// the unpacked way is the only shortest one, the route search's.
// Not customisable: its ways are those of the graph without closures, blockages or hazards. A
// mission with some takes a way from it only where none of them touches it (compile_index.cc
// says why that way is then the mission's); the others are searched on the mission's graph
// toward their target, with the hierarchy's distances as the guide (ChQuery::aim_at,
// GraphSearch::run_toward): a few hundred nodes where a closure's detour is short. A
// customisable hierarchy (Dibbelt, Strasser and Wagner, 2014) would answer those too, from
// the index alone; not built (docs/benchmarks.md).
//   auto ch = ContractionHierarchy::build(core.adjacency_begin, core.adjacency_to,
//                                         core.adjacency_cost, {.keep_ties = true});
//   ChQuery query(*ch);
//   Cost d = query.distance(s, t);               // kInfiniteCost: no way
//   query.table(sources, targets, table, &unique);  // table[i * targets.size() + j]
//   query.path(s, t, nodes);                     // s ... t, the graph's own moves
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <utility>
#include <vector>

#include "sewerplan/core/result.h"
#include "sewerplan/core/stop_condition.h"
#include "sewerplan/domain/compiled_task.h"

#include "position_graph.h"

namespace sewerplan::domain::detail {

struct ChOptions {
  // Nodes a witness search settles at most while a node's priority is estimated, and while it is
  // contracted (a witness not found in time only adds a shortcut that was not needed). On 10k
  // scrambled manholes (2026-12-07): 40 and 500 built in 370 ms, 5 and 100 in 230 ms with 3 %
  // more shortcuts and tables 10 % slower; 1 and 100 in 190 ms with 17 % more shortcuts and
  // tables 50 % slower.
  std::size_t estimate_settled = 5;
  std::size_t contract_settled = 100;
  // Keep every shortest way (a witness must be strictly shorter, moves of equal cost between the
  // same nodes are counted), so that a query can tell whether a shortest way is the only one
  // (ChQuery: `unique`). 3 % more shortcuts on 10k scrambled manholes (docs/benchmarks.md).
  bool keep_ties = false;
  // Asked between slices of 1,024 contractions (null: never): a build that it stops fails with
  // kCancelled (the build of 100,000 scrambled manholes takes seconds, a million's a minute).
  const StopCondition* stop = nullptr;
};

struct ChStatistics {
  std::size_t nodes = 0;
  std::size_t moves = 0;      // the graph's, parallel moves and loops merged away
  std::size_t shortcuts = 0;  // in the hierarchy at the end
  std::size_t up_edges = 0;
  std::size_t down_edges = 0;
  std::size_t bytes = 0;  // of the hierarchy's arrays (not of a query's)
};

class ContractionHierarchy {
 public:
  // The graph: the moves out of node n are to[e], cost[e] for e in [begin[n], begin[n + 1]).
  // Errors: a negative cost, a move or shortcut of 2^32 - 1 ms or more, 2^31 - 1 nodes or more
  // (kInvalidArgument); stopped by options.stop (kCancelled).
  // Runtime: about O(nodes x (degree^2 x witness limit)) in practice; no bound in theory.
  static Result<ContractionHierarchy> build(std::span<const std::uint32_t> begin,
                                            std::span<const Node> to, std::span<const Cost> cost,
                                            const ChOptions& options = {});

  std::size_t size() const { return rank_.size(); }
  const ChStatistics& statistics() const { return statistics_; }

 private:
  friend class ChQuery;
  friend class ChTable;
  friend class ChBuilder;
  friend struct ChFile;  // route_index.cc: the file format (docs/formats/route-index.md)
  static constexpr std::uint32_t kNoMiddle = 0x7fffffffU;
  struct Edge {
    std::uint32_t head;  // by rank
    std::uint32_t cost;  // ms
    // Bits 0-30: the middle node by rank (kNoMiddle: a move of the graph); bit 31: the edge
    // stands for more than one shortest way between its ends (kept with keep_ties only).
    std::uint32_t middle_tied;
    std::uint32_t middle() const { return middle_tied & kNoMiddle; }
    std::uint32_t ways() const { return (middle_tied >> 31) + 1; }
  };
  static_assert(sizeof(Edge) == 12);

  // By rank, low below high: the edge of the move low -> high (find_up), high -> low
  // (find_down). Each pair has at most one (parallel moves are merged when built).
  const Edge& find_up(std::uint32_t low, std::uint32_t high) const;
  const Edge& find_down(std::uint32_t low, std::uint32_t high) const;

  // Appends the graph's nodes of the edge tail -> head (by rank; `middle` its middle node, or
  // kNoMiddle) after tail: its shortcuts unpacked, head last. With `check` (not null), each move
  // is asked before its node is appended; false at the first it refuses (`out` then ends at
  // the move's tail).
  bool unpack(std::uint32_t tail, std::uint32_t head, std::uint32_t middle, std::vector<Node>& out,
              const std::function<bool(Node from, Node to)>* check = nullptr) const;

  std::vector<std::uint32_t> rank_;  // by node
  std::vector<Node> node_;           // by rank
  // By rank u: [up_begin_[u], up_begin_[u + 1]) the moves u -> head with a higher head;
  // [down_begin_[u], down_begin_[u + 1]) the moves head -> u with a higher head.
  std::vector<std::uint32_t> up_begin_;
  std::vector<Edge> up_;
  std::vector<std::uint32_t> down_begin_;
  std::vector<Edge> down_;
  ChStatistics statistics_;
};

// A many-to-many table that keeps what unpacks its ways (ChQuery::table_with_ways): each
// source's upward search tree, each target's backward one, and each pair's meeting node. A few
// dozen bytes per node the searches settle (about a thousand per key on 100,000 scrambled
// manholes), where a way unpacked per pair takes a point-to-point query of its own.
class ChTable {
 public:
  std::size_t sources() const { return tree_begin_.empty() ? 0 : tree_begin_.size() - 1; }
  std::size_t targets() const { return targets_; }
  Cost distance(std::size_t i, std::size_t j) const { return dist_[i * targets_ + j]; }
  // Whether the pair's shortest way is the only one (on a hierarchy built with keep_ties; false
  // if there is none).
  bool unique(std::size_t i, std::size_t j) const { return ways_[i * targets_ + j] == 1; }
  // The pair's way into `out` (source first, target last, every step a move of the graph),
  // empty if there is none; among several shortest ways, one of them. With `check` (not null),
  // each move is asked in order, source first, as the way is assembled: false at the first it
  // refuses, with the way assembled no further (`out` ends at the move's tail; issue 35: a
  // replan's start row has its routes past the blockage refused at their first moves). Each
  // tree edge is unpacked whole on first use and kept for the table's other ways (segment()).
  // Not for use from two threads at once: the kept edges are the table's own.
  bool way(std::size_t i, std::size_t j, std::vector<Node>& out,
           const std::function<bool(Node from, Node to)>* check = nullptr) const;

 private:
  friend class ChQuery;
  struct Parent {
    std::uint32_t node;    // by rank
    std::uint32_t target;  // in down_ only: the target's index
    std::uint32_t parent;  // by rank; none at the search's root
  };
  // The parent of `node` in source i's tree (up_) or in target j's (down_), and its entry there.
  std::uint32_t up_parent(std::size_t i, std::uint32_t node) const;
  std::uint32_t down_parent(std::size_t j, std::uint32_t node) const;
  std::size_t up_entry(std::size_t i, std::uint32_t node) const;
  std::size_t down_entry(std::size_t j, std::uint32_t node) const;
  // The graph's nodes of a tree edge (up: the entry's parent -> its node; down: its node -> its
  // parent), its tail left out: unpacked on first use, then kept.
  std::span<const Node> segment(bool up, std::size_t entry) const;
  struct Segment {
    static constexpr std::uint32_t kUnknown = 0xffffffffU;
    std::size_t begin = 0;
    std::uint32_t size = kUnknown;
  };

  const ContractionHierarchy* ch_ = nullptr;
  std::size_t targets_ = 0;
  std::vector<Cost> dist_;               // by pair, i * targets + j
  std::vector<std::uint8_t> ways_;       // by pair: 0 none, 1 one, 2 more
  std::vector<std::uint32_t> middle_;    // by pair: the meeting node, by rank
  std::vector<Parent> up_;               // by source, then node
  std::vector<std::size_t> tree_begin_;  // source i's in up_[tree_begin_[i], tree_begin_[i + 1])
  std::vector<Parent> down_;             // by node, then target
  // way()'s unpacked tree edges (segment()), by entry of up_ and down_, and its buffer.
  mutable std::vector<Segment> up_segments_;
  mutable std::vector<Segment> down_segments_;
  mutable std::vector<Node> segment_nodes_;
  mutable std::vector<std::size_t> way_entries_;
};

// Queries on one hierarchy, with their buffers (sized to the hierarchy once, reset through the
// nodes touched). One per thread; the hierarchy may be shared.
class ChQuery {
 public:
  explicit ChQuery(const ContractionHierarchy& ch);

  // The cost of the cheapest way from s to t; kInfiniteCost if none. With `unique` (not null),
  // also whether that way is the only shortest one (false if there is none), on a hierarchy
  // built with keep_ties over a graph with no cycle of cost 0. Moves of cost 0 (the position
  // graph's from a pipe's end to its slot) are fine: the upward searches settle nodes of equal
  // distance by rank and every edge climbs, so a node's ways are counted before it is expanded.
  Cost distance(Node s, Node t, bool* unique = nullptr);
  // The same, and the way's nodes in `out` (s first, t last; empty if none): every step a move
  // of the graph, the shortcuts unpacked.
  Cost path(Node s, Node t, std::vector<Node>& out, bool* unique = nullptr);
  // out[i * targets.size() + j] = distance(sources[i], targets[j]); with `unique` (not null),
  // unique[i * targets.size() + j] as distance() gives it.
  // Runtime: one upward search per source and target, and the buckets of the nodes settled.
  void table(std::span<const Node> sources, std::span<const Node> targets, std::vector<Cost>& out,
             std::vector<bool>* unique = nullptr);
  // The same, with the ways kept to be unpacked (ChTable::way), and the unique flags.
  // Runtime: as table(), and the trees' nodes sorted.
  void table_with_ways(std::span<const Node> sources, std::span<const Node> targets, ChTable& out);
  // A guide for a search on a graph with fewer or dearer moves (GraphSearch::run_toward, the
  // mission's graph with its closures and blockages): the cost of the cheapest way from any node
  // to `target` in the hierarchy's graph, a lower bound of the way there in such a graph that
  // no move breaks. aim_at() runs the upward backward search from the target whole;
  // distance_to_aim(n) then takes the best of n's upward search space, each node's value kept
  // for the next call (Strasser and Zeitz, "Using Incremental Many-to-One Queries to Build a
  // Fast and Tight Heuristic for A* in Road Networks", 2021: CH-Potentials). Any other query
  // ends the aim (a call then is a defect: checked). kInfiniteCost: no way to the target.
  // Runtime: aim_at, the target's backward search space (hundreds of nodes on 100,000
  // scrambled manholes); distance_to_aim, the nodes of n's upward space not seen before.
  void aim_at(Node target);
  Cost distance_to_aim(Node n);
  // The way from n to the aim that distance_to_aim(n) stands for, into `out` (n first, the
  // target last), if it is the only shortest one (on a hierarchy built with keep_ties) and every
  // move passes `check` (if not null; asked in order, as in ChTable::way); false otherwise (`out`
  // then holds a part of it), `*cost` its cost. Runtime: the way's length and the upward edges of
  // the nodes it climbs through; no search.
  bool way_to_aim(Node n, std::vector<Node>& out,
                  const std::function<bool(Node from, Node to)>* check, Cost* cost);
  // Nodes settled over all queries (a measure of work).
  std::size_t settled_total() const { return settled_total_; }

 private:
  struct Side {
    std::vector<Cost> dist;             // by rank; kInfiniteCost: not reached
    std::vector<std::uint32_t> parent;  // by rank: the node whose edge reached it
    std::vector<std::uint8_t> ways;     // by rank: upward ways at its distance, 1 or 2 (more)
    std::vector<std::uint32_t> touched;
    std::vector<std::pair<Cost, std::uint32_t>> heap;
  };
  struct BucketEntry {
    std::uint32_t node;
    std::uint32_t target;
    Cost dist;
    std::uint32_t ways;
    std::uint32_t parent;  // in the target's backward search
  };
  // table() and table_with_ways(): with `kept` (not null), the trees and meeting nodes too.
  void fill_table(std::span<const Node> sources, std::span<const Node> targets,
                  std::vector<Cost>& out, std::vector<bool>* unique, ChTable* kept);

  void start(Side& side, std::uint32_t source);
  static void clear(Side& side);
  // Settles the next node of `side` (forward: on the up edges, else on the down edges, stalled by
  // the others) and returns it with its distance in `*d`, or kNone if the heap ran dry. A stalled
  // node (`*stalled`: reached more cheaply from a higher node) is not expanded.
  template <bool kForward>
  std::uint32_t settle_next(Side& side, Cost* d, bool* stalled);
  // The distance, the meeting node in `*middle`, and (with `ways`) the shortest ways, 1 or 2.
  Cost meet(Node s, Node t, std::uint32_t* middle, std::uint32_t* ways);

  const ContractionHierarchy& ch_;
  Side forward_;
  Side backward_;
  std::vector<BucketEntry> buckets_;
  std::vector<std::uint32_t> bucket_begin_;  // by rank, for the nodes with a bucket: index + 1
  std::vector<std::uint32_t> bucket_nodes_;
  std::vector<std::uint32_t> row_ways_;    // by target: the ways at the row's distance
  std::vector<std::uint32_t> row_middle_;  // by target: where the row's best way meets it
  // aim_at(): the target's backward search in backward_, the distances found so far in
  // forward_.dist (distance_to_aim says how), `aim_stack_` the nodes whose distance waits for
  // their upward neighbours'.
  bool aimed_ = false;
  std::vector<std::uint32_t> aim_stack_;
  std::size_t settled_total_ = 0;
};

}  // namespace sewerplan::domain::detail
