// SPDX-License-Identifier: MIT
// PositionGraph: the robot's primitive moves on a map, as an implicit weighted graph.
//
// Private to domain. Nodes are the positions of docs/domain.md, numbered densely:
//   [0, M)               in manhole m                    (M = manholes)
//   [M, M + S)           at manhole m, slot s            (S = slots; the map's global slot order)
//   [M + S, M + S + 2P)  in pipe p at end e: 2p + e      (P = pipes)
//   [M + S + 2P, ...)    in pipe p at an extra spot      (a task's or the start's offset)
// Edges are the movement actions (ENTER_PIPE, DRIVE_MANHOLE_..., DRIVE_PIPE_TO_MANHOLE) that the
// robot's limits and the mission's closures allow, with their costs in milliseconds. Nothing is
// materialised: successors and predecessors are generated from the map on demand, so a graph over
// a million manholes costs only the per-pipe drivability flags, a slot-to-manhole index and a
// cache of the passages judged so far (each manhole's on its first visit: judging a passage takes
// trigonometry, and a Dijkstra over a city asks for the same passages again from every key:
// issue 16, bench/domain/compile_bench.cc).
//
// What depends only on the map and the robot (the pipes it fits, the slot index, the judged
// passages) and the route searches' scratch arrays live in a GraphCore, which the graphs of
// successive compiles on one map may share (CompileCache, compile.h): building them touches every
// manhole and pipe of the map, a fifth of a replan's time at 100,000 manholes (issue 16). The
// mission's closures, closed passages, blockages and hazards are applied by each graph on top.
//
// Not thread-safe: the passage cache fills as searches visit manholes, so one graph serves one
// thread, and a core one graph at a time.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/core/stop_condition.h"
#include "sewerplan/domain/compiled_task.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/domain/robot_state.h"

#include "zeroed_array.h"

namespace sewerplan::domain::detail {

using Node = std::uint32_t;

// A route search's arrays over every node (graph_search.h), kept clean between runs: every
// distance infinite, no parent, nothing settled or targeted, so a search can start at once.
// Distances and parents are stored so that clean is zero (zeroed_array.h: a search touches only
// the pages it reaches, issue 16): kInfiniteCost - distance, and parent + 1.
struct SearchScratch {
  ZeroedArray<Cost> dist_left;
  ZeroedArray<Node> parent_plus_one;
  std::vector<bool> settled;
  std::vector<bool> is_target;
  std::vector<bool> tied;  // GraphSearch::run_toward: reached at its distance by two settled nodes
  std::vector<Node> touched;
  std::vector<std::pair<Cost, Node>> heap;
};

struct RouteMemo;
class ContractionHierarchy;
class ChQuery;

// The part of a PositionGraph that depends on the map and the robot alone, with the scratch
// arrays of the compile's route searches and its exit marks.
struct GraphCore {
  // Built at once, asking `stop` (if not null) between slices of the map's pipes, manholes and
  // passages (issue 14: 2 to 4 ms on 100,000 manholes). If it fires, the core is left incomplete:
  // `complete` is false, and it serves nothing.
  GraphCore(const SewerMap& map, const RobotProfile& profile,
            std::shared_ptr<const PassageMotionTable> motion, const StopCondition* stop = nullptr);
  // Whether this core was built for `map` (the same object, of the same size) and this robot,
  // completely.
  bool serves(const SewerMap& map, const RobotProfile& profile,
              const PassageMotionTable* motion) const;

  const SewerMap* map;
  RobotProfile profile;
  std::shared_ptr<const PassageMotionTable> motion;  // held, so that its address stays its own
  std::size_t manholes;
  std::size_t pipes;
  std::size_t slots;
  std::vector<bool> fits;                      // by pipe: the robot fits its diameter
  std::vector<std::uint32_t> manhole_of_slot;  // by global slot index
  std::vector<std::size_t> passage_begin;      // by manhole: its slot_count^2 passages
  // The passages' costs by the robot's limits and the motion table alone (kInfiniteCost: not
  // allowed), judged on a manhole's first visit; closures are applied by the graph.
  std::vector<Cost> passages;
  std::vector<bool> judged;
  SearchScratch scratch;  // the compile's route searches
  // Issue 35: the moves out of each of the map's own nodes (not extra spots) as a graph without
  // closures, blockages or hazards has them, in compressed sparse rows, in the order
  // PositionGraph::for_each_successor gives them; empty until PositionGraph::build_adjacency.
  // Generating the moves from the map reads a manhole, its slots, a pipe and the judged
  // passages for every node settled, each in its own array: on a network numbered without
  // spatial order, cache misses that made a compile's searches cost 3 times a plain Dijkstra's
  // per node (bench/domain/compile_bound_bench.cc, docs/benchmarks.md).
  std::vector<std::uint32_t> adjacency_begin;
  std::vector<Node> adjacency_to;
  std::vector<Cost> adjacency_cost;
  // Whether a move out of a slot costs nothing (a profile with no pass, turn or step cost): only
  // then has the graph cycles of cost 0 (every cycle leaves a slot; a pipe's end to its slot is
  // the other move of cost 0, and the robot lowered in a manhole is never entered again). Set
  // with the adjacency.
  bool free_passages = false;
  // Exit marks by node (the last compile's), the nodes marked, and the exits they mark.
  std::vector<bool> exit_marks;
  std::vector<Node> marked_exits;
  std::vector<ManholeId> exits_marked;
  // The last compile's route searches, for the next compile on this core (route_memo.h).
  std::shared_ptr<RouteMemo> route_memo;
  // Issue 35: the routing index over the adjacency (contraction_hierarchy.h, built with
  // keep_ties) and a query's buffers, built by the first compile on a CompileCache that asks for
  // it (compile_index.cc) or handed a loaded one (CompileCache::use_route_index); null until
  // then. Shared, as a loaded index may serve several caches' cores. `hierarchy_failed`: a build
  // failed (a cost too large for its edges), not to be tried again on this core.
  std::shared_ptr<const ContractionHierarchy> hierarchy;
  std::shared_ptr<ChQuery> hierarchy_query;
  bool hierarchy_failed = false;
  bool complete = false;

 private:
  bool build(const SewerMap& map, const StopCondition* stop);
};

// Grows `bits` to `size` entries of false in slices, asking `stop` (if not null) between them;
// false if it fired first (the entries added so far are false: the next call goes on).
bool grow_in_slices(std::vector<bool>& bits, std::size_t size, const StopCondition* stop);

class PositionGraph {
 public:
  struct Spot {
    PipeId pipe;
    double offset_m;
  };

  // `core`: one built for this map and the mission's robot and motion table (GraphCore::serves),
  // used by no other graph meanwhile; a fresh one if null, built under `stop` (if not null): if it
  // fires, the graph is incomplete (core().complete is false) and must not be searched.
  PositionGraph(const SewerMap& map, const Mission& mission,
                std::shared_ptr<GraphCore> core = nullptr, const StopCondition* stop = nullptr);

  // Builds the core's adjacency (GraphCore::adjacency_begin), asking `stop` (if not null) between
  // slices; false if it fired first (the core is left without one). Afterwards, the moves out of
  // the map's own nodes are read from it (closed and excluded pipes are filtered as the moves are
  // read), with the same moves, costs and order as generated from the map; only the nodes whose
  // moves the mission changes otherwise are generated still: the ends of a pipe with a blockage,
  // the slots of a closed passage, and (while a risk weight is set) the ends of a pipe with a
  // hazard. Runtime: O(nodes + moves), judging every passage.
  bool build_adjacency(const StopCondition* stop);
  bool has_adjacency() const { return !core_->adjacency_begin.empty(); }

  // Adds an extra spot in a pipe (or returns the node of an end, or of an existing spot, there).
  Node spot(PipeId pipe, double offset_m);
  Node node(const RobotPosition& position);

  Node in_manhole(ManholeId m) const { return m.value(); }
  Node at_slot(ManholeId m, SlotIndex s) const {
    return manholes_ + map_.manhole(m).first_slot + s.value();
  }
  Node pipe_end(PipeId p, std::size_t end) const {
    return manholes_ + slots_ + 2 * p.value() + static_cast<Node>(end);
  }
  std::size_t size() const { return manholes_ + slots_ + 2 * pipes_ + spots_.size(); }
  // Extra spots are entered only by task actions, never by a move.
  bool is_extra_spot(Node n) const { return n >= manholes_ + slots_ + 2 * pipes_; }

  RobotPosition position(Node n) const;
  // The pipe a pipe node is in.
  std::optional<PipeId> pipe_of(Node n) const;
  // The manhole a manhole or slot node is in.
  std::optional<ManholeId> manhole_at(Node n) const {
    if (n < manholes_) return ManholeId{n};
    if (n >= manholes_ + slots_) return std::nullopt;
    return ManholeId{core_->manhole_of_slot[n - manholes_]};
  }
  double offset_of(Node n) const;  // pipe nodes only
  const std::vector<Node>& extra_spots_in(PipeId pipe) const;

  // The robot can enter p: it fits p's diameter and the mission does not close p.
  bool pipe_drivable(PipeId p) const { return drivable_[p.index()]; }
  // The robot fits p's diameter: it can move in p if it is there (a closed pipe can be left).
  bool pipe_fits(PipeId p) const { return core_->fits[p.index()]; }
  bool passage_allowed(ManholeId m, SlotIndex from, SlotIndex to) const {
    return passage(m, from, to) != kInfiniteCost;
  }
  // Whether a blockage of the mission lies strictly between offsets a and b of pipe p.
  bool blocked_between(PipeId p, double a, double b) const {
    return has_blockages_ && blockage_between(mission_, p, a, b).has_value();
  }
  // Whether the whole of p can be driven (an inspection): no blockage anywhere in it.
  bool fully_open(PipeId p) const { return !blocked_between(p, -1.0, map_.pipe(p).length_m + 1.0); }
  // Precondition: the passage is allowed.
  Cost passage_cost(ManholeId m, SlotIndex from, SlotIndex to) const {
    return passage(m, from, to);
  }
  Cost drive_cost(double distance_m) const;
  // Risk-aware planning (compile.h, RiskCosts): driving pipe p from offset a to b, past hazards
  // (Mission::hazards) strictly between them that stop the robot with probabilities p_i, costs
  // (1 - prod(1 - p_i)) x `weight_s` more. 0 without hazards or weight.
  Cost risk_cost(PipeId p, double a, double b, double weight_s) const {
    return weight_s > 0 && !hazards_.empty() ? risk_cost_uncached(p, a, b, weight_s) : 0;
  }
  // The farthest hazard from `from` strictly between offsets `from` and `to` of p, if any; with
  // `insured` (by index into Mission::hazards; null or empty: all), only those it marks.
  std::optional<double> farthest_hazard(PipeId p, double from, double to,
                                        const std::vector<bool>* insured = nullptr) const;
  // Appends the hazards strictly between offsets `from` and `to` of p to `out`: each as its index
  // into Mission::hazards and its distance from `from`.
  void hazards_between(PipeId p, double from, double to,
                       std::vector<std::pair<std::uint32_t, double>>& out) const;
  bool has_hazards() const { return !hazards_.empty(); }
  // Contingency-aware battery planning (compile.h): while excluded, no move enters `pipe`, as if
  // it were found blocked (none is, by default).
  void exclude_pipe(PipeId pipe, bool excluded) {
    if (excluded_.empty()) excluded_.assign(pipes_, false);
    if (excluded_[pipe.index()] != excluded) {
      if (excluded) {
        ++excluded_count_;
      } else {
        --excluded_count_;
      }
    }
    excluded_[pipe.index()] = excluded;
  }
  bool excluded(PipeId pipe) const { return excluded_count_ > 0 && excluded_[pipe.index()]; }

  // The weight the moves' costs carry (0: none, the default); the compiler sets it per search.
  void set_risk_weight(double weight_s) { risk_weight_s_ = weight_s; }
  // The risk cost that `route` (nodes, as routes are stored) carries at `weight_s`.
  Cost route_risk(std::span<const Node> route, double weight_s) const;

  // f(to, cost) for each move out of `from`.
  template <class F>
  void for_each_successor(Node from, F&& f) const;
  // Whether each step of `route` (nodes of the map, not extra spots) that the core's adjacency
  // has is a move of this graph with the adjacency's cost: no step leaves a node whose moves the
  // mission's blockages, closed passages or (with a risk weight set) hazards change, and none
  // enters a closed or excluded pipe. This graph's moves are the adjacency's less those, and
  // those costing more (issue 35: a route of the routing index that passes this check is one
  // of this graph's, at the index's cost).
  bool reads_adjacency(std::span<const Node> route) const {
    for (std::size_t i = 0; i + 1 < route.size(); ++i) {
      if (!reads_move(route[i], route[i + 1])) return false;
    }
    return true;
  }
  // The same for one step of such a route.
  bool reads_move(Node from, Node to) const {
    const Node first_end = manholes_ + slots_;
    if (from >= first_end + 2 * pipes_ || generated(from)) return false;
    if (to >= first_end) {
      const PipeId p{(to - first_end) / 2};
      if (!drivable_[p.index()] || excluded(p)) return false;
    }
    return true;
  }
  // f(from, cost) for each move into `to`.
  template <class F>
  void for_each_predecessor(Node to, F&& f) const;
  // The primitive action of the move from -> to. Precondition: that move exists.
  PlanStep step(Node from, Node to) const;

  const SewerMap& map() const { return map_; }
  const RobotProfile& profile() const { return profile_; }
  GraphCore& core() const { return *core_; }
  const std::shared_ptr<GraphCore>& shared_core() const { return core_; }

 private:
  ManholeId manhole_of_slot_node(Node n, SlotIndex* slot) const {
    const std::uint32_t global = n - manholes_;
    const ManholeId m{core_->manhole_of_slot[global]};
    *slot = SlotIndex{static_cast<std::uint16_t>(global - map_.manhole(m).first_slot)};
    return m;
  }
  // The passage's cost, kInfiniteCost where not allowed (the robot's limits and the motion
  // table from the core's cache, judged on first use; then the mission's closures).
  Cost passage(ManholeId m, SlotIndex from, SlotIndex to) const {
    GraphCore& core = *core_;
    if (!core.judged[m.index()]) judge_manhole(m);
    const std::size_t slots = map_.manhole(m).slot_count;
    const Cost cost =
        core.passages[core.passage_begin[m.index()] + from.value() * slots + to.value()];
    if (cost == kInfiniteCost || !drivable_[map_.slot(m, to).pipe.index()]) return kInfiniteCost;
    if (!closed_passages_.empty() && closed(m, from, to)) return kInfiniteCost;
    return cost;
  }
  bool closed(ManholeId m, SlotIndex from, SlotIndex to) const;
  Cost risk_cost_uncached(PipeId p, double a, double b, double weight_s) const;
  void judge_manhole(ManholeId m) const;
  template <class F>
  void drive_out_of_pipe(Node from, PipeId p, double x, F&& f) const;

  const SewerMap& map_;
  const Mission& mission_;
  const RobotProfile& profile_;
  bool has_blockages_ = false;
  // Issue 35: the map's nodes whose moves the mission's blockages or closed passages change
  // (irregular_), and those a hazard's risk cost changes while a risk weight is set
  // (hazard_ends_); by node, as long as the largest such node (empty: none). Their moves are
  // generated from the map; every other node of the map reads its moves from the core's
  // adjacency (closed pipes are filtered as they are read). Before, a single blockage sent every
  // node back to the map: after a blockage on 100,000 scrambled manholes each search of a replan
  // settled a node in 3 times the time (docs/benchmarks.md, issue 35).
  std::vector<bool> irregular_;
  std::vector<bool> hazard_ends_;
  bool has_closed_pipes_ = false;
  bool generated(Node from) const {
    return (from < irregular_.size() && irregular_[from]) ||
           (risk_weight_s_ > 0 && from < hazard_ends_.size() && hazard_ends_[from]);
  }
  Node manholes_;
  Node slots_;
  Node pipes_;
  std::shared_ptr<GraphCore> core_;
  std::vector<bool> drivable_;                  // by pipe: fits, and the mission does not close it
  std::vector<ClosedPassage> closed_passages_;  // normalised: from < to, sorted
  std::vector<Spot> spots_;
  std::vector<Hazard> hazards_;              // the mission's, sorted by pipe and offset
  std::vector<std::uint32_t> hazard_index_;  // each of hazards_' index into Mission::hazards
  double risk_weight_s_ = 0;
  std::vector<bool> excluded_;  // by pipe; empty until one is excluded
  std::size_t excluded_count_ = 0;
  std::vector<std::pair<PipeId, std::vector<Node>>> spots_by_pipe_;  // sorted by pipe
};

template <class F>
void PositionGraph::drive_out_of_pipe(Node, PipeId p, double x, F&& f) const {
  if (!core_->fits[p.index()]) return;
  const Pipe& pipe = map_.pipe(p);
  for (std::size_t e = 0; e < 2; ++e) {
    if (!pipe.ends[e].manhole) continue;
    const double offset = e == 0 ? 0.0 : pipe.length_m;
    if (blocked_between(p, x, offset)) continue;
    f(at_slot(*pipe.ends[e].manhole, pipe.ends[e].slot),
      drive_cost(x > offset ? x - offset : offset - x) + risk_cost(p, x, offset, risk_weight_s_));
  }
}

template <class F>
void PositionGraph::for_each_successor(Node from, F&& f) const {
  const GraphCore& core = *core_;
  if (from < manholes_ + slots_ + 2 * pipes_ && !core.adjacency_begin.empty() && !generated(from)) {
    const Node first_end = manholes_ + slots_;
    const bool filter = has_closed_pipes_ || excluded_count_ > 0;
    for (std::uint32_t e = core.adjacency_begin[from]; e < core.adjacency_begin[from + 1]; ++e) {
      const Node to = core.adjacency_to[e];
      // Only a move out of a manhole or a slot ends at a pipe's end: it enters that pipe.
      if (filter && to >= first_end) {
        const PipeId p{(to - first_end) / 2};
        if (!drivable_[p.index()] || excluded(p)) continue;
      }
      f(to, core.adjacency_cost[e]);
    }
    return;
  }
  if (from < manholes_) {  // in manhole: ENTER_PIPE
    const ManholeId m{from};
    for (const Slot& s : map_.slots(m)) {
      if (drivable_[s.pipe.index()] && !excluded(s.pipe)) {
        f(pipe_end(s.pipe, s.pipe_end), to_cost(profile_.manhole_pass_s));
      }
    }
  } else if (from < manholes_ + slots_) {  // at a slot: DRIVE_MANHOLE
    SlotIndex i{0};
    const ManholeId m = manhole_of_slot_node(from, &i);
    const auto slots = map_.slots(m);
    for (std::uint16_t j = 0; j < slots.size(); ++j) {
      if (j == i.value()) continue;
      const Cost cost = passage(m, i, SlotIndex{j});
      if (cost == kInfiniteCost || excluded(slots[j].pipe)) continue;
      f(pipe_end(slots[j].pipe, slots[j].pipe_end), cost);
    }
  } else if (from < manholes_ + slots_ + 2 * pipes_) {  // at a pipe's end: DRIVE_PIPE_TO_MANHOLE
    const Node end = from - manholes_ - slots_;
    const PipeId p{end / 2};
    drive_out_of_pipe(from, p, end % 2 == 0 ? 0.0 : map_.pipe(p).length_m, f);
  } else {  // at an extra spot in a pipe
    const Spot& spot = spots_[from - manholes_ - slots_ - 2 * pipes_];
    drive_out_of_pipe(from, spot.pipe, spot.offset_m, f);
  }
}

template <class F>
void PositionGraph::for_each_predecessor(Node to, F&& f) const {
  if (to < manholes_) return;     // nothing moves into "in manhole"
  if (to < manholes_ + slots_) {  // reached by DRIVE_PIPE_TO_MANHOLE from any spot of the pipe
    SlotIndex s{0};
    const ManholeId m = manhole_of_slot_node(to, &s);
    const Slot& slot = map_.slot(m, s);
    if (!core_->fits[slot.pipe.index()]) return;
    const Pipe& pipe = map_.pipe(slot.pipe);
    const double target = slot.pipe_end == 0 ? 0.0 : pipe.length_m;
    for (std::size_t e = 0; e < 2; ++e) {
      const double x = e == 0 ? 0.0 : pipe.length_m;
      if (blocked_between(slot.pipe, x, target)) continue;
      f(pipe_end(slot.pipe, e), drive_cost(x > target ? x - target : target - x) +
                                    risk_cost(slot.pipe, x, target, risk_weight_s_));
    }
    for (Node n : extra_spots_in(slot.pipe)) {
      const double x = offset_of(n);
      if (blocked_between(slot.pipe, x, target)) continue;
      f(n, drive_cost(x > target ? x - target : target - x) +
               risk_cost(slot.pipe, x, target, risk_weight_s_));
    }
    return;
  }
  const Node first_spot = manholes_ + slots_ + 2 * pipes_;
  if (to >= first_spot) return;  // extra spots are reached only by task actions
  const PipeId p{(to - manholes_ - slots_) / 2};
  const std::size_t e = (to - manholes_ - slots_) % 2;
  const PipeEnd& end = map_.pipe(p).ends[e];
  if (!end.manhole || !drivable_[p.index()]) return;
  const ManholeId m = *end.manhole;
  f(in_manhole(m), to_cost(profile_.manhole_pass_s));  // ENTER_PIPE
  for (std::uint16_t i = 0; i < map_.manhole(m).slot_count; ++i) {
    if (i == end.slot.value()) continue;
    const Cost cost = passage(m, SlotIndex{i}, end.slot);
    if (cost != kInfiniteCost) f(at_slot(m, SlotIndex{i}), cost);
  }
}

}  // namespace sewerplan::domain::detail
