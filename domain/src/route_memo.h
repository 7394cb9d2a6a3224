// SPDX-License-Identifier: MIT
// RouteMemo: a compile's route searches, kept for the next compile on the same map (issue 35).
//
// Private to domain. A replan compiles the mission again from where the robot is: most of the
// keys are the same, and what changed since (a pipe found blocked, a passage closed, the battery
// a little lower) leaves most routes as they were. The memo keeps, for each key whose routes a
// search of the last compile found within the key's own bound (a "row": the routes to the other
// keys and to its nearest exit), what that search found; the next compile takes a row from it
// instead of searching again when the answer is provably the search's own:
//   - the same searched graph, or one with edges only taken away or made dearer: the same map
//     and robot (the memo lives in the GraphCore), the same risk weights and exits, the closed
//     pipes, closed passages and blockages a superset of the memo's, and (when risks weigh) each
//     of the memo's hazards still there, as likely or more (a hazard learnt, or met blocked, only
//     makes the drives past it dearer; one passed, less likely, makes them cheaper: no row is
//     taken then);
//   - a bound no larger than the memo's, and targets it knew: a key the memo's search had as a
//     target and did not reach lies beyond its bound, so beyond the new one too;
//   - no route of the row through a pipe or a manhole the new closures touch, or a pipe whose
//     hazards changed.
// A route search breaks ties by (distance, node) and replaces a parent only for a shorter way
// (graph_search.h), so a route whose nodes keep their distances is the one a new search would
// find, node for node: taking edges away (or making them dearer) elsewhere only lengthens other
// ways. A row that fails any
// condition is searched again, as before.
//
// Rows from task spots and from landing keys the start does not reach (SpotRow) search within the
// whole bound and keep every key they settle before they stop, targets or not: what they hold
// depends on where the search stopped. Why they may be taken too: with edges only taken away, a
// node whose route keeps its edges ("clean") keeps its distance, its parent and its place in the
// order of settling relative to the other clean nodes (by induction on that order: it is offered
// its distance by the same parent at the same point, and nothing offers less); any other node is
// offered its distance by a node settled no earlier, or a larger one, so it is settled no earlier
// relative to the clean ones. Hence, when the new targets and the exit the row found are within
// the bound and clean, the new search stops at the last of them and settles exactly the keys the
// old one settled at a smaller distance than that stop (each must be clean); a key at exactly the
// stop's distance that is not a target could fall on either side, and sends the row back to a
// search. When a target or the exit lies beyond the new bound, the new search runs out within it
// and settles the keys within the bound, all of which the old one settled (it stopped beyond the
// bound, or ran out within a larger one); a new target the old search did not reach although it
// stopped early sends the row back to a search. A spot's own moves are its pipe's drives: any
// change in that pipe does too. A spot's node number is the compile's own (extra spots are
// numbered in the order a compile meets them): spot rows and the spots' exit searches are kept by
// pipe and offset, their routes renumbered from their first node.
//
// Thread-safety: one compile uses a memo at a time (the one holding its GraphCore).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "sewerplan/core/mission.h"

#include "position_graph.h"
#include "route_store.h"

namespace sewerplan::domain::detail {

struct RouteMemo {
  // What the searches depended on besides the keys and bounds.
  struct Context {
    double blockage_weight_s = 0;  // the risk weights of the rows' and the exits' searches
    double return_weight_s = 0;
    bool exit_goal = false;  // the rows searched on to their nearest exit
    std::vector<ManholeId> exits;
    std::vector<Hazard> hazards;  // compared only when a weight is set
    std::vector<PipeId> closed_pipes;
    std::vector<ClosedPassage> closed_passages;
    std::vector<Blockage> blockages;
  };
  // The context of a compile on `mission` (sorted, so that order does not count).
  static Context context_of(const Mission& mission, double blockage_weight_s,
                            double return_weight_s, bool exit_goal);

  // What a compile in `now` may take from this memo: the pipes and manholes whose moves the new
  // closures or hazards change (routes through them are searched again). Null when nothing may be
  // taken: another context, one that opened something the memo's had closed, or one with a
  // hazard less likely or gone.
  struct Change {
    std::vector<bool> pipe;  // by pipe index
    // The nodes of the changed pipes' ends and of the changed manholes (in the manhole, at its
    // slots), sorted: a route passes a pipe at one of its ends, or starts inside it at an extra
    // spot, and passes a manhole at its slots.
    std::vector<Node> nodes;
    // A node's bit (n mod 4096) is set if it may be one of `nodes`: most of a route's nodes are
    // passed over by one read of these 512 bytes rather than a search (a replan checks hundreds
    // of thousands of nodes; the search alone was 15 M instructions at 100,000 manholes).
    std::array<std::uint64_t, 64> maybe{};
    bool any = false;
    // Whether `route` passes a changed pipe or manhole.
    bool touches(const PositionGraph& graph, std::span<const Node> route) const;
  };
  std::optional<Change> change_to(const Context& now, const PositionGraph& graph) const;

  struct Found {
    Node to = 0;
    Cost cost = 0;
    RouteRef route;
  };
  // One key's search: its bound, the keys it reached (each a target; the source itself at cost
  // 0), and the nearest exit it settled when it searched for one (Context::exit_goal).
  struct Row {
    Cost bound = 0;
    std::vector<Found> found;
    std::optional<Found> exit;
  };
  // A key's search for its nearest exit alone (route_to_exits), within `bound`.
  struct ExitSearch {
    Cost bound = 0;
    std::optional<Found> exit;
  };

  // A search from a task's spot, or from a landing key the start does not reach, within the whole
  // bound: every key it settled (the source at cost 0, as `source`) and the exit it found.
  struct SpotRow {
    Node source = 0;  // the source's node number in the compile that searched
    Row row;
  };
  // An extra spot by (true, pipe, offset), a node of the map by (false, node, 0).
  using SpotKey = std::tuple<bool, std::uint32_t, double>;

  Context context;
  std::vector<Node> targets;  // sorted: the rows' targets (the keys the start reaches)
  std::unordered_map<Node, Row> rows;
  std::map<SpotKey, SpotRow> spot_rows;
  std::unordered_map<Node, ExitSearch> exit_searches;
  std::map<SpotKey, ExitSearch> spot_exit_searches;  // from task spots (SpotKey)
  RouteStore store;                                  // the routes of rows and exit_searches
};

}  // namespace sewerplan::domain::detail
