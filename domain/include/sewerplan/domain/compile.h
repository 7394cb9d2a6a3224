// SPDX-License-Identifier: MIT
// compile_sewer_task: a map, a mission and the robot's progress, as a CompiledTask to search.
//
// The sewer domain's primitive actions (docs/domain.md) move the robot one pipe or one manhole at a
// time; a plan on a city network has hundreds of them. Between two tasks, though, an optimal plan
// always follows a cheapest route. So the compiler picks the *key positions* where something
// happens (the start, the ends of task pipes and the spots of tasks in them, the slots of task
// manholes), finds the cheapest route between every two of them with Dijkstra's algorithm over the
// primitive moves that the robot's limits and the mission's closures allow, and one backward
// search gives every key's cheapest way to an exit. The CompiledTask then has:
//   - a position variable over the keys (and "at an exit" when the mission ends at one);
//   - a variable per pending task (0 pending, 1 done);
//   - GO(a, b) actions costing the cheapest route a -> b; one action per task and key it can start
//     from, with the task's own cost; GO_EXIT(a) to the nearest exit; FINISH(a) for a final go-to;
//   - the battery less the reserve, less the energy used, as the cost bound.
// These are macro-operators in the sense of Botea et al. 2005 ("Macro-FF", JAIR 24), built
// from exact shortest paths, so an optimal plan of the compiled task expands to an optimal
// primitive plan; expand() turns a compiled plan back into the paper's actions.
//
// The compile reports what makes a mission impossible before any search: a task or every exit
// out of reach (naming the task and the limit, closure or battery that prevents it).
//
// The SewerTask refers to the map and the mission: keep both alive while using it.
//
//   Result<SewerTask> task = compile_sewer_task(map, mission, initial_progress(mission, map));
//   if (!task.has_value()) std::cerr << task.error().message;  // kNoPlan, with the reasons
//   SearchResult r = engine.search(task->task(), stop);
//   Plan plan = task->expand(r.plan);
//
// Thread-safety: compile_sewer_task() is reentrant (it only reads the map and mission). A SewerTask
// is immutable once built: its const methods may be called from any number of threads.
#pragma once

#include <atomic>
#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/core/stop_condition.h"
#include "sewerplan/domain/compiled_task.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/domain/robot_state.h"
#include "sewerplan/domain/route_index.h"

namespace sewerplan::domain {

namespace detail {
class PositionGraph;
}

// CompileCache: what successive compiles on one map keep from one to the next (issue 16).
//
// A compile's primitive graph has indices over the whole map (the pipes the robot fits, each
// slot's manhole, room for every manhole's passages) and its route searches arrays over every
// position: building them touched every manhole and pipe, a fifth of a replan at 100,000
// manholes. A cache keeps them, with the passages judged so far, for the next compile on the
// same map with the same robot profile and motion table (it starts afresh when those change).
// What a replan changes (blockages, closed pipes and passages, hazards, the robot's position and
// the tasks done) is applied by each compile on top, so a plan is the same with or without it.
// It also keeps the last compile's route searches (issue 35, incremental replanning): the next
// compile takes a key's routes from them instead of searching again when nothing that changed
// since can alter them (new closures off those routes, a bound no larger, the same risk weights,
// hazards and exits), and searches only the rest: after a blockage, the keys whose routes pass
// it (CompileStatistics::reused_searches counts the searches saved).
//
//   CompileCache cache;  // e.g. the Replanner's, for the whole mission
//   auto task = compile_sewer_task(map, mission, progress, {.cache = &cache});
//
// Thread-safe: one compile uses what it holds at a time (until its SewerTask is destroyed);
// a compile that finds it in use builds its own. Precondition: the map is not modified while
// the cache lives (it is recognised by its address and sizes).
class CompileCache {
 public:
  // Issue 35: whether the compiles on this cache take their routes from a routing index of the
  // map (a contraction hierarchy over the robot's moves, docs/benchmarks.md), built by the first
  // compile that wants it and kept with the map's indices. kAuto builds it when the searches
  // from the keys would settle more than 100 times the graph's positions (so many tasks spread
  // over a network the battery does not bound that the build, 60 to 150 Dijkstras over the map,
  // costs less than those searches); kAlways on the first compile; kNever not at all. Routes,
  // tasks and plans are the same either way: a route is taken from the index only where it is
  // the only shortest way and no closure, blockage or hazard of the mission touches it, else a
  // search finds it as without one.
  enum class RoutingIndex { kAuto, kAlways, kNever };
  explicit CompileCache(RoutingIndex index = RoutingIndex::kAuto);
  RoutingIndex routing_index() const;
  // A routing index made beforehand (route_index.h: built by `sewerplan index build`, loaded from
  // beside the map) for the compiles on `map` with this robot and motion table (`motion`, as the
  // missions' Mission::passage_motion, the same pointer): they take their routes from it,
  // whatever the policy, and build none. Checked here, where the cache builds the map's indices
  // and moves as the first compile would (so that it need not): an index whose fingerprint is
  // not theirs is refused (kInvalidArgument, naming its file), and the cache is left as it
  // was. Compiles on another map or robot do without it. Plans are the same as without it.
  // Runtime: O(positions + moves), judging every passage (tens of ms at 100,000 manholes).
  Result<void> use_route_index(RouteIndex index, const SewerMap& map, const RobotProfile& profile,
                               std::shared_ptr<const PassageMotionTable> motion,
                               const StopCondition& stop = {});
  CompileCache(const CompileCache&) = delete;
  CompileCache& operator=(const CompileCache&) = delete;
  ~CompileCache();

 private:
  friend class SewerTaskCompiler;
  struct State;
  std::unique_ptr<State> state_;
};

struct CompileStatistics {
  std::size_t keys = 0;
  std::size_t graph_nodes = 0;    // positions of the primitive graph
  std::size_t settled_nodes = 0;  // Dijkstra work over all searches
  std::size_t route_searches = 0;
  // Searches not run: their routes taken from the last compile on the same cache (issue 35:
  // CompileCache, incremental replanning).
  std::size_t reused_searches = 0;
  // Searches not run: a key's routes, or its way to its nearest exit, taken from the routing
  // index (CompileCache::RoutingIndex) whole, or with the routes a closure touches found by
  // guided searches (guided_searches). A row the index gave in part (a route tied, an exit
  // among many, a guided search that found a tie) counts a route search, for the rest.
  std::size_t index_rows = 0;
  // Routes found by a search toward the one target, guided by the routing index's distances
  // (issue 35: a route the index has but a closure, blockage or hazard touches; after a blockage
  // the robot's row has several).
  std::size_t guided_searches = 0;
  std::size_t actions = 0;
  // The searches read the moves from the map's adjacency in the compile cache's core, built
  // by this compile or kept from an earlier one (issue 35).
  bool adjacency = false;
  double time_s = 0;
};

// The chance that a plan meets a blockage it keeps no battery to back out of (issue 34,
// SewerTask::strand_risk): the hazards (Mission::hazards) its drives pass without a contingency
// reserve that covers them, and 1 - prod(1 - p) over them. A bound on the chance of being
// stranded: where a stop at such a hazard still leaves the battery for another way out, the
// robot is not stranded.
struct StrandRisk {
  double probability = 0;
  std::vector<std::size_t> uninsured;  // indices into Mission::hazards, ascending, each once
  friend bool operator==(const StrandRisk&, const StrandRisk&) = default;
};

// A task that goal selection left out, and why.
struct DroppedTask {
  TaskId task{0};
  std::string reason;
  friend bool operator==(const DroppedTask&, const DroppedTask&) = default;
};

// Risk-aware planning (plan --risk expected; docs/planning.md, "Risk-aware planning"). A move
// past hazards (Mission::hazards) that stop the robot with probabilities p_i carries, on top of
// its time, the expected cost of being stopped: P x C, where P = 1 - prod(1 - p_i) is the chance
// that one of them stops it and C what a stop costs: `blockage_s` on the way to and between the
// tasks (backing out, the recovery attempts and the detour), `return_s` on the way from a key to
// the exit, where a stop may leave no way out at all. So a risky pipe is taken while tasks remain
// rather than as the way back, and a safe detour wins where it costs less than the expected stop.
// In the compiled task the expected cost counts against the bound like time (plan_mission gives a
// risk-aware compile a larger battery, and checks the plan's true cost against the real one);
// SewerTask::risk_cost() separates it again. Defaults: kDefaultRiskCosts; 0: risk-blind.
struct RiskCosts {
  double blockage_s = 0;
  double return_s = 0;
  bool active() const { return blockage_s > 0 || return_s > 0; }
  friend bool operator==(const RiskCosts&, const RiskCosts&) = default;
};

// 10 minutes for a stop on the way out (about what MAKRO's recovery, backing out and a detour
// take on the paper's network) and an hour on the way back (the robot may need to be fetched).
inline constexpr RiskCosts kDefaultRiskCosts{.blockage_s = 600, .return_s = 3600};

struct CompileOptions {
  // Goal selection (the paper, section 4.7: "tick off the highest possible number of goals"):
  // instead of failing, leave out the tasks that cannot be reached (dropped()), and let the
  // search forgo others at a penalty (CompiledTask::penalty_unit()), so that an optimal plan does
  // as many tasks as the battery allows and still ends the mission. What stays impossible: a
  // battery already spent, a start the robot cannot move from, no exit within reach (or the
  // final task out of reach).
  bool select_goals = false;
  // Cancellation and deadline (issue 14): the stop condition of every algorithm
  // (core/stop_condition.h; its cancel flag and time limit, not its expansion limit), checked
  // before each phase, between slices of the map-wide arrays it builds, and every 256 nodes the
  // route searches settle: the compile then fails
  // with kCancelled or kSearchLimit.
  StopCondition stop;
  // Risk-aware routes and task orders (RiskCosts); risk-blind by default.
  RiskCosts risk;
  // Contingency-aware battery planning (docs/planning.md): where the mission has hazards
  // (Mission::hazards) and ends at an exit, every action that drives a pipe past a hazard keeps
  // enough battery, when it starts, to drive to the farthest hazard it passes, back out, and
  // reach an exit without that pipe (CompiledTask::reserve). A pipe that is the only way out
  // asks for nothing (no battery would help there). Missions without hazards are unchanged.
  bool contingency = true;
  // Chance-constrained contingency (issue 34, docs/planning.md): which hazards keep their
  // reserve, by index into Mission::hazards; empty: every one (a hazard beyond the end of the
  // vector keeps none). A drive past hazards keeps the battery to back out of the farthest
  // insured one (which covers every nearer one too); only with `contingency`.
  std::vector<bool> insured{};
  // Keeps the map's indices and the searches' arrays for the next compile (CompileCache); null:
  // none.
  CompileCache* cache = nullptr;
};

class SewerTask {
 public:
  SewerTask(SewerTask&&) noexcept;
  SewerTask& operator=(SewerTask&&) noexcept;
  ~SewerTask();

  const CompiledTask& task() const { return task_; }
  const CompileStatistics& statistics() const { return statistics_; }

  // The primitive plan of a plan of task(). Precondition: `plan` is a plan of task().
  Plan expand(std::span<const ActionId> plan) const;

  // With goal selection: the tasks left out before the search, with the reason.
  const std::vector<DroppedTask>& dropped() const { return dropped_; }
  // With goal selection: the tasks that `plan` forgoes, in mission order (not those dropped()).
  std::vector<TaskId> forgone(std::span<const ActionId> plan) const;
  // The task each goal variable of task() stands for: variable i + 1 is goal_tasks()[i] (variable
  // 0 is the robot's position), in mission order.
  const std::vector<TaskId>& goal_tasks() const { return goal_tasks_; }
  // With CompileOptions::risk: the expected cost of stops (RiskCosts) that `plan`'s actions
  // carry; the plan's true cost is its cost less this. 0 when risk-blind.
  Cost risk_cost(std::span<const ActionId> plan) const;
  // The plan's computed stranding risk (StrandRisk): every hazard a drive of `plan` passes
  // strictly, counted once, uninsured when at the first drive past it neither a reserve covers
  // it nor the battery the plan has left there (`budget`, by default task().cost_bound(), less
  // the plan's true cost before the drive) would back out from it and reach an exit another way,
  // backing out of any hazard on that way too. Such a hazard adds its probability p, or, where
  // the battery left covers the way out but not backing out of its hazards, p times the chance
  // that one of those blocks as well. No battery helps at a pipe with no other way out or a
  // drive that does not start at a pipe end; without CompileOptions::contingency no way out is
  // computed, so every hazard passed counts its p. A blockage is met where the plan first passes
  // it, and a hazard passed safely is open after, so later passes do not count; nor does a second
  // blockage on the way out after a first (the reserve's second level). Runtime: O(hazards passed x
  // distinct hazards passed).
  StrandRisk strand_risk(std::span<const ActionId> plan,
                         std::optional<Cost> budget = std::nullopt) const;

 private:
  friend class SewerTaskCompiler;
  SewerTask();

 public:
  // The battery to back out from a hazard and reach an exit another way, from the start of the
  // action that passes it: `plain` without a reserve on the way out, `full` with one at every
  // hazard the way out passes; `risk` the chance that one of those blocks it too (with `plain`
  // only, the robot would be stranded then). kInfiniteCost: no way out, or the drive does not
  // start at a pipe end.
  struct WayBack {
    Cost plain = kInfiniteCost;
    Cost full = kInfiniteCost;
    double risk = 0;
  };

 private:
  CompiledTask task_;
  CompileStatistics statistics_;
  std::unique_ptr<detail::PositionGraph> graph_;
  // Per action: its route as graph nodes (CSR), and the task step that ends it, if any.
  std::vector<std::uint32_t> route_begin_;
  std::vector<std::uint32_t> route_nodes_;
  std::vector<std::optional<PlanStep>> task_step_;
  std::vector<Cost> risk_;  // per action: its expected cost of stops (RiskCosts)
  // Per action: the hazards its drives pass (CSR), as index into Mission::hazards and whether a
  // reserve covers it; and each hazard's probability.
  struct HazardPass {
    std::uint32_t hazard = 0;
    bool covered = false;
    WayBack way_back{};
  };
  std::vector<std::uint32_t> pass_begin_;
  std::vector<HazardPass> passes_;
  std::vector<double> hazard_probability_;
  std::vector<DroppedTask> dropped_;
  std::vector<std::pair<ActionId, TaskId>> forgo_actions_;  // sorted by action
  std::vector<TaskId> goal_tasks_;
};

// Fails with kNoPlan, listing every reason found, when a pending task or (without a final task)
// every exit is out of reach of the start, within the robot's limits and the battery (with goal
// selection, only for the reasons CompileOptions names).
Result<SewerTask> compile_sewer_task(const SewerMap& map, const Mission& mission,
                                     const MissionProgress& progress,
                                     const CompileOptions& options = {});

}  // namespace sewerplan::domain
