// SPDX-License-Identifier: MIT
// plan_mission: from a map, a mission and the robot's progress to a plan in the paper's actions.
//
// The entry point for programs that plan: it compiles the mission (domain/compile.h), runs the
// chosen search engine on the compiled task under the given limits, expands the result into the
// primitive plan, and reports what it cost. Algorithms: enforced hill-climbing with FF's heuristic
// and helpful actions (FF's own strategy: fast, not optimal); greedy best-first search; weighted
// A*; A* with h_max (optimal); and auto, which picks A* when the task is small enough.
//
//   PlannerOptions options{.algorithm = Algorithm::kAstar, .time_limit_s = 1.0};
//   Result<PlanOutcome> outcome = plan_mission(map, mission, initial_progress(mission, map),
//                                              options);
//   if (!outcome.has_value()) std::cerr << outcome.error().message;  // kNoPlan, kSearchLimit, ...
//   std::cout << format_plan(outcome->plan, map, mission);
//
// Thread-safety: plan_mission() is reentrant: concurrent calls are safe as long as each caller's
// map and mission are not modified meanwhile (they are only read); PlannerOptions::cancel may be
// set from any thread.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/domain/robot_state.h"
#include "sewerplan/search/heuristic.h"
#include "sewerplan/search/search_engine.h"

namespace sewerplan::search {

// kAuto: A* with h_max (optimal) when the compiled task has at most 2^12 states (a handful of
// tasks); otherwise the tour search's plan (tour_search.h: ordering the tasks by insertion and
// local search, in milliseconds), or weighted A* with FF where a task is not of its shape; then
// the improvement phase (PlannerOptions::improvement_expansions). On the paper's mission A* takes
// tens of microseconds (bench/search/planner_bench.cc).
// kExact: the optimum, proven: the exact tour search (tour_search.h: dynamic programming over
// subsets of tasks, up to kMaxExactGoals tasks, with the battery and goal selection), else A* with
// h_max.
enum class Algorithm { kAuto, kEhc, kGbfs, kWeightedAstar, kAstar, kExact };

std::string_view to_string(Algorithm algorithm);
// auto, ehc, gbfs, wastar, astar, exact
std::optional<Algorithm> algorithm_from_string(std::string_view name);
// The names algorithm_from_string reads, "auto, ehc, gbfs, wastar, astar, exact", for messages.
std::string algorithm_names();

struct PlannerOptions {
  Algorithm algorithm = Algorithm::kAuto;
  // Default: FF for ehc, gbfs and wastar; h_max for astar (admissible, so its plans are optimal).
  std::optional<HeuristicKind> heuristic{};
  double weight = 2.0;               // wastar
  double time_limit_s = 0;           // 0: none
  std::uint64_t max_expansions = 0;  // 0: none
  const std::atomic<bool>* cancel = nullptr;
  const Clock* clock = nullptr;  // default: a steady clock
  // After a first plan from a non-optimal algorithm, weighted A* with weights 3, 2, 1.5 and then
  // A* with h_max look for cheaper plans (each bounded by the best so far), as LAMA's anytime
  // search does (Richter and Westphal 2010), within this many expansions in all: an expansion
  // budget rather than a time budget, so that the plan does not depend on the machine's speed.
  // 0: keep the first plan. With adaptive_improvement, this is a cap.
  std::uint64_t improvement_expansions = 10'000;
  // Issue 16: the improvement budget follows the problem's size (portfolio.h, choose_portfolio:
  // since issue 33 from sizes alone, never from the compile's own work), so a small network does
  // not pay 10,000 expansions for a plan found in microseconds; where the tour search applies and
  // the exact tour search (tour_search.h) fits that budget, or its table is small beside the
  // estimated route work (docs/planning.md, "The portfolio"), it replaces the improvement and
  // proves the plan optimal. Deterministic: counts and sizes, not time.
  bool adaptive_improvement = true;
  // Goal selection (domain/compile.h, CompileOptions::select_goals): do as many tasks as can be
  // done and still end the mission, rather than fail when not all can. The plan's dropped tasks
  // say which were left out, and why.
  bool select_goals = false;
  // Risk-aware planning (domain/compile.h, RiskCosts) where the mission has hazards: routes and
  // task orders that weigh the expected cost of being stopped. The expected cost is not energy:
  // the risk-aware search gets a battery larger by the most a plan's expected cost can be, and its
  // plan must fit the real battery by its true cost. It never costs a task or the mission: when
  // the risk-aware plan does not fit, none is found, or (with goal selection) it does fewer tasks
  // than a risk-blind one, the risk-blind plan is the answer (PlanOutcome::risk_note).
  domain::RiskCosts risk{};
  // Contingency-aware battery planning (domain::CompileOptions::contingency, docs/planning.md):
  // where the mission has hazards, keep at every drive past one enough battery to back out and
  // reach an exit another way. Where no plan can keep those reserves, the plan without them is
  // the answer (PlanOutcome::contingency_note), so this never turns a plan into no plan.
  bool contingency = true;
  // Chance-constrained contingency (issue 34, docs/planning.md, "A bound on the chance of being
  // stranded"): the most the plan's computed stranding risk (PlanOutcome::strand_probability)
  // may be, 0..1. 0: every hazard keeps its reserve (as `contingency` alone); 1: none does (as
  // contingency = false); in between, the planner insures the hazards whose reserves cost the
  // fewest tasks per unit of risk they remove, until the plan's risk is within the bound (at
  // most kMaxStrandRounds plans more; deterministic). Only with `contingency`.
  double max_strand_risk = 0;
  // Which hazards keep their reserve (domain::CompileOptions::insured; empty: all). Set by the
  // search for max_strand_risk; a caller may set it to plan with one set.
  std::vector<bool> insured{};
  // Keeps the map's indices and the route searches' arrays from one plan to the next on the same
  // map (domain::CompileCache: a replan need not rebuild them); null: none. The plans are the
  // same with or without it.
  domain::CompileCache* compile_cache = nullptr;
};

struct PlanOutcome {
  domain::Plan plan;
  double cost_s = 0;  // by the compiled task's costs (integer milliseconds per action)
  double energy_wh = 0;
  SearchStatistics search;
  domain::CompileStatistics compile;
  std::string algorithm;  // engine and heuristic, e.g. "enforced hill-climbing + ff"
  // The plan is proven optimal (by A* with an admissible heuristic, or by an improvement search
  // that exhausted every cheaper plan).
  bool optimal = false;
  std::size_t improvements = 0;  // cheaper plans found after the first
  // With goal selection: the tasks left out, in mission order, with the reason.
  std::vector<domain::DroppedTask> dropped;
  // Risk-aware: the expected cost of stops the plan was chosen with (not in cost_s), and why the
  // risk-blind plan was taken instead, if it was.
  double risk_cost_s = 0;
  std::string risk_note;
  // Set when no plan keeps the contingency reserves (PlannerOptions::contingency) and the plan
  // was made without them.
  std::string contingency_note;
  // The plan's computed stranding risk (domain::SewerTask::strand_risk): the chance that it meets
  // a blockage at a hazard none of its reserves covers, 1 - prod(1 - p) over those hazards
  // (`uninsured`, indices into Mission::hazards). 0 without hazards or where every hazard passed
  // keeps its reserve.
  double strand_probability = 0;
  std::vector<std::size_t> uninsured;
  // With 0 < max_strand_risk < 1: the plans tried to choose which hazards go uninsured, and
  // what was chosen, for people ("2 of 31 hazards uninsured (p <= 0.05): 1 more task").
  std::size_t strand_plans = 0;
  std::string strand_note;
  // The time limit (or a cancel) stopped the planner after a first plan, before it had done all
  // it meant to (the tour search's local search, the exact search or the improvement): the plan
  // is the best found by then (the Replanner's anytime answer "best-so-far").
  bool best_so_far = false;
};

// At most this many plans beyond the fully insured one choose which hazards go without their
// reserve (PlannerOptions::max_strand_risk): the plan with none, then per round one plan for each
// of at most kStrandCandidates hazards the current plan passes uninsured (docs/planning.md).
inline constexpr std::size_t kMaxStrandRounds = 12;
inline constexpr std::size_t kStrandCandidates = 4;

// kAuto's choice for `task`; any other algorithm is returned as it is.
Algorithm resolve(Algorithm algorithm, const domain::CompiledTask& task);

std::unique_ptr<SearchEngine> make_engine(Algorithm algorithm, const domain::CompiledTask& task,
                                          Heuristic& heuristic, double weight);

// kNoPlan: the mission (or what is left of it) cannot be completed, with the reasons;
// kSearchLimit / kCancelled: the search stopped first.
Result<PlanOutcome> plan_mission(const SewerMap& map, const Mission& mission,
                                 const domain::MissionProgress& progress,
                                 const PlannerOptions& options);

// The quick answers of a planner past its deadline (the Replanner's anytime ladder,
// executor/replanner.h, docs/planning.md): one compile without a time limit (options.cancel is
// honoured), risk-blind, then a tour without local search or improvement (tour_search.h):
// deterministic, and microseconds beyond the compile. Where no plan keeps the contingency reserves,
// the plan without them (PlanOutcome::contingency_note), as plan_mission does.
// plan_greedily: the cheapest insertion of the tasks left from the robot's place, leaving out
// those that do not fit the battery (with options.select_goals; else kNoPlan when not all fit).
// plan_in_order: the tasks of `order` still pending, in that order (the mission's final task last),
// every other task left out, and while that does not fit the battery, the task whose absence
// leaves the cheapest plan left out too (needs options.select_goals to leave any out).
// kNoPlan: the task is not of the tour's shape, or nothing fits; kCancelled.
Result<PlanOutcome> plan_greedily(const SewerMap& map, const Mission& mission,
                                  const domain::MissionProgress& progress,
                                  const PlannerOptions& options);
Result<PlanOutcome> plan_in_order(const SewerMap& map, const Mission& mission,
                                  const domain::MissionProgress& progress,
                                  std::span<const TaskId> order, const PlannerOptions& options);

}  // namespace sewerplan::search
