// SPDX-License-Identifier: MIT
// Reach barriers: what keeps the robot from a place, named by the limit and the object.
//
// Private to domain. When no route leads from where the robot is (or from a task's place) to a
// task or an exit, the reason is one of three: the battery (a route exists, but costs more than
// is left), the robot's limits and the mission's closures (every way there leaves the part of the
// network the robot can reach through a pipe it does not fit, a passage beyond its turn or step
// limit or without a planned motion, a closed pipe or passage, a blockage), or the network itself
// (no pipe connects the two at all). diagnose_reach tells which, and for the second lists each
// barrier on the edge of what the robot can reach behind which a target lies:
//   - the part the robot can reach: every position the planner's moves reach from the origins,
//     with no bound on the battery;
//   - the part from which a target can be reached if nothing stopped the robot: every position
//     from which moves that ignore the limits and the closures lead to a target;
//   - a barrier: a move from the first part into the second that the limits or closures forbid.
// One function for every caller: the compile's reasons (compile_reasons.h) serve `plan`,
// `simulate`, the Replanner and the station alike.
//
//   ReachDiagnoser from_start(graph, mission, reachable_from(graph, {&start, 1}));
//   ReachDiagnosis d = from_start.diagnose(exit_nodes);
//   if (!d.reachable && !d.barriers.empty()) why += ": in the way: " + barrier_list(d);
//
// Runtime: O(positions + moves) of the graph once per place, with each passage judged once
// (judge_passage); then O(barriers + targets) per diagnosis.
#pragma once

#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "position_graph.h"

namespace sewerplan::domain::detail {

struct ReachDiagnosis {
  bool reachable = false;  // a target is reachable (then only the battery can stand in the way)
  // Each barrier once ("pipe P3 is 0.25 m, too narrow for makro-plus (0.30-0.60 m)"), in the
  // order of the positions they are met from (deterministic).
  std::vector<std::string> barriers;
};

// Every position the planner's moves reach from `origins`, by node, with no bound on the battery.
std::vector<bool> reachable_from(const PositionGraph& graph, std::span<const Node> origins);

// The diagnosis from one place, for any number of targets: built once (O(positions + moves)),
// each diagnosis then costs O(barriers found + targets). Holds `graph` (by reference).
class ReachDiagnoser {
 public:
  // `reached`: reachable_from(graph, origins).
  ReachDiagnoser(const PositionGraph& graph, const Mission& mission, std::vector<bool> reached);
  // `targets`: nodes of the graph (a target that is an extra spot counts as its pipe's ends, from
  // which a task action reaches it).
  ReachDiagnosis diagnose(std::span<const Node> targets) const;

 private:
  struct Found {
    Node part;  // the part of the unreached network the barrier leads into
    std::string key;
    std::string text;
  };
  const PositionGraph& graph_;
  std::vector<bool> reached_;
  std::vector<Node> part_;  // by node
  std::vector<Found> found_;
  std::set<std::pair<Node, std::string>> seen_;
};

// The barriers joined with "; ", at most `shown`, then "and N more".
std::string barrier_list(const ReachDiagnosis& diagnosis, std::size_t shown = 6);

}  // namespace sewerplan::domain::detail
