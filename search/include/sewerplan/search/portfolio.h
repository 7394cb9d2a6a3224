// SPDX-License-Identifier: MIT
// Portfolio: which searches plan_mission runs on a compiled task, in which order, and with which
// budget each, as a plain value (as Fast Downward's and OMPL's configurable portfolios are).
//
// choose_portfolio picks it from the problem's size (ProblemSize: manholes, pipes, positions,
// tasks, key places, the compiled task's facts and actions) and the planner's options, and from
// nothing else: never from how much work the compile did (issue 33; before, two budgets rested on
// the compile's settled-node count, so a faster compile changed plans). run_portfolio runs it:
//
//   - first-plan stages (kExactTour, kTourSearch, kSearch), in order, until one gives a plan; a
//     stage that does not apply to the task (not of the tour's shape, too many tasks for the
//     exact search) passes to the next;
//   - then each improving stage (kExactImprovement, kImprovement) while the plan is not proven
//     optimal: the exact tour search only after the tour search's plan (it reuses the task's shape
//     the tour search read).
//
//   const ProblemSize size = problem_size(map, compiled->task(), compiled->statistics());
//   const Portfolio portfolio = choose_portfolio(size, options);
//   Result<PortfolioRun> run = run_portfolio(portfolio, compiled->task(), stop, clock, failure);
//
// Budgets are counts and sizes, never time, so plans are the same on every machine
// (docs/planning.md, "The portfolio").
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/search/heuristic.h"
#include "sewerplan/search/planner.h"
#include "sewerplan/search/search_engine.h"

namespace sewerplan::search {

// The sizes of a problem that choose_portfolio reads: the map's and the compiled task's, all known
// once the task is compiled, the same however the compile found its routes.
struct ProblemSize {
  std::size_t manholes = 0;
  std::size_t pipes = 0;
  std::size_t positions = 0;  // of the position graph (CompileStatistics::graph_nodes)
  std::size_t tasks = 0;      // goal variables of the compiled task (tasks still to do)
  std::size_t keys = 0;       // the task's key places (CompileStatistics::keys)
  std::size_t facts = 0;
  std::size_t actions = 0;
  double states = 1;  // the product of the task's domain sizes
  friend bool operator==(const ProblemSize&, const ProblemSize&) = default;
};

// Reads only the sizes from `statistics` (keys, graph_nodes); its work figures (settled nodes,
// route searches, time) are ignored. Runtime: O(variables).
ProblemSize problem_size(const SewerMap& map, const domain::CompiledTask& task,
                         const domain::CompileStatistics& statistics);

// The product of the task's domain sizes (ProblemSize::states). Runtime: O(variables).
double state_count(const domain::CompiledTask& task);

// kAuto's choice for a problem of this size: A* with h_max when the task has at most 2^12 states,
// else weighted A* (behind the tour search where the task has its shape); any other algorithm is
// returned as it is.
Algorithm resolve(Algorithm algorithm, const ProblemSize& size);

enum class Engine {
  // The exact tour search (tour_search.h): a proven optimum; does not apply to a task not of the
  // tour's shape or with more than kMaxExactGoals tasks.
  kExactTour,
  // The tour search's first plan (insertion and local search); does not apply to a task not of
  // its shape. Where no order of the tasks fits the battery, the exact tour search proves it, or
  // the stage fails with kSearchLimit.
  kTourSearch,
  // A search engine (make_engine) of Stage::algorithm with Stage::heuristic.
  kSearch,
  // After the tour search's plan: the exact tour search, bounded by that plan when it does every
  // task, with a table of at most Stage::budget bytes; its plan is proven optimal.
  kExactImprovement,
  // Anytime weighted A* (weights 3, 2, 1.5, then A* with h_max), each only for plans cheaper than
  // the best so far, within Stage::budget expansions in all.
  kImprovement,
};

std::string_view to_string(Engine engine);

struct Stage {
  Engine engine = Engine::kSearch;
  Algorithm algorithm = Algorithm::kWeightedAstar;  // kSearch
  HeuristicKind heuristic = HeuristicKind::kFf;     // kSearch
  double weight = 2;                                // kSearch with kWeightedAstar
  // kExactImprovement: bytes of the table; kImprovement: expansions; else 0.
  std::uint64_t budget = 0;
  friend bool operator==(const Stage&, const Stage&) = default;
};

struct Portfolio {
  std::vector<Stage> stages;
  friend bool operator==(const Portfolio&, const Portfolio&) = default;
};

// Which stages, in which order, with which budgets (docs/planning.md, "The portfolio"):
// - kAuto: A* with h_max where the task has at most 2^12 states; else the tour search, weighted A*
//   (options.weight) with FF where the task is not of its shape, the exact tour search as the
//   improvement where its table fits the budget below, and the anytime improvement;
// - kExact: the exact tour search, A* with h_max where it does not apply;
// - any other algorithm: that engine (options.heuristic, or h_max for A*, FF for the others),
//   then the anytime improvement unless its plan is optimal by construction.
// Budgets (with options.adaptive_improvement): the route work a compile of this size does,
// estimated as keys x min(positions, kReachPositions), stands in for the compile's own work:
// the improvement gets 4 x that + 200,000 units (one a fact or action a heuristic evaluation
// visits), capped by options.improvement_expansions; the exact tour search replaces it where
// 2^K x 9K^2 units fit in that, or its table takes at most kExactBytesPerReach bytes per unit of
// route work and kAutoExactBytes in all. An improvement of no more expansions than there are
// tasks is left out (it could not find a plan).
Portfolio choose_portfolio(const ProblemSize& size, const PlannerOptions& options);

// The positions one route search of the compile settles, at most, in the estimate of the route
// work: the battery bounds the searches, and on the generated instances (1,000 to 100,000
// manholes) they settled 120 to 2,500 positions per key, median about 400 (docs/planning.md).
inline constexpr std::size_t kReachPositions = 1024;
inline constexpr std::size_t kExactBytesPerReach = 512;
inline constexpr std::size_t kAutoExactBytes = std::size_t{32} << 20U;

// What running a portfolio found: the best plan, whether it is proven optimal, how many cheaper
// plans the improving stages found, and the name of what found it ("tour search, improved by the
// exact tour search").
struct PortfolioRun {
  SearchResult result;
  bool optimal = false;
  std::size_t improvements = 0;
  std::string algorithm;
};

// How a run that found no plan is reported: from the status of the search that failed, or,
// for a tour search that found no order within the battery, from the cheapest order's cost.
struct PortfolioFailure {
  std::function<Error(SearchStatus)> status;
  std::function<Error(Cost cheapest_order)> battery_exceeded;
};

// Runs `portfolio` on `task` under `stop` (which may carry an expansion limit for the first-plan
// searches). Errors: those of `failure`.
Result<PortfolioRun> run_portfolio(const Portfolio& portfolio, const domain::CompiledTask& task,
                                   const StopCondition& stop, const Clock& clock,
                                   const PortfolioFailure& failure);

}  // namespace sewerplan::search
