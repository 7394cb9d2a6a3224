// SPDX-License-Identifier: MIT
// CompileReasons: why a mission cannot be done, found from the compile's route searches.
//
// Private to domain. Before any search, a pending task whose pipe or manhole no route reaches,
// within the robot's limits, the mission's closures and the battery, or (for a mission that ends
// at an exit) from which no exit is reachable, makes the mission impossible. Each reason names the
// task and what stands in the way: the battery, or each limit of the robot and closure of the
// mission on the edge of what the robot can reach (reach_barriers.h), or the network itself.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "position_graph.h"
#include "reach_barriers.h"

namespace sewerplan::domain::detail {

class CompileReasons {
 public:
  // `origin`: the node the robot is at (the compile's first key). Not thread-safe (a cache).
  CompileReasons(const PositionGraph& graph, const Mission& mission,
                 const MissionProgress& progress, Cost bound, Node origin)
      : graph_(graph), mission_(mission), progress_(progress), bound_(bound), origin_(origin) {}

  // "\n  - reason" per problem; empty when none is known. `dist` is k x k (row 0: from the
  // start), `exit_dist` per key (empty unless the mission ends at an exit).
  std::string explain(const std::vector<Node>& keys, const std::vector<TaskId>& pending,
                      const std::vector<Cost>& dist, const std::vector<Cost>& exit_dist,
                      bool ends_at_exit) const;

  // The reasons that no choice of tasks can help: the battery spent, a start the robot cannot
  // move from, no exit in reach (for a mission that ends at one). Same form as explain().
  std::string fatal(const std::vector<Cost>& exit_dist, bool ends_at_exit) const;
  // Why `task` cannot be done (and the mission still ended); empty if nothing is known against it.
  std::string task_reason(const Task& task, const std::vector<Node>& keys,
                          const std::vector<Cost>& dist, const std::vector<Cost>& exit_dist,
                          bool ends_at_exit) const;

 private:
  std::string unreachable(const Task& task, const std::vector<Node>& keys) const;
  // What stands between `from` and `to` when no route joins them (reach_barriers.h): ": in the
  // way: ..." naming each limit or closure and its object, ": the network does not connect them",
  // or, when only the battery is in the way, nothing.
  std::string barriers(std::span<const Node> from, std::span<const Node> to) const;
  std::vector<Node> exit_nodes() const;
  // The diagnosis from the origin, built on first use: every unreachable task asks it.
  const ReachDiagnoser& from_origin() const;
  std::string energy(Cost cost) const;
  std::string limits() const;
  // "the start (place)" when the robot is where the mission starts and has used no energy, else
  // "here (place)".
  std::string origin() const;
  bool at_task(const Task& task, Node n) const;

  const PositionGraph& graph_;
  const Mission& mission_;
  const MissionProgress& progress_;
  Cost bound_;
  Node origin_;
  mutable std::unique_ptr<ReachDiagnoser> from_origin_;
};

}  // namespace sewerplan::domain::detail
