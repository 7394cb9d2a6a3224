// SPDX-License-Identifier: MIT
// Tour search: plans for tasks where one mover visits places, by ordering the visits.
//
// The sewer compiler's tasks (domain/compile.h) have this shape: variable 0 is the robot's
// position over key places; every other variable is a goal that starts pending (0) and is done
// (1) by an action at a place (which may leave the robot elsewhere: an inspection ends at the far
// end of its pipe); moves between places cost the cheapest route; a final goal may require all the
// others done; the goal may ask for a position (at an exit); with goal selection a goal can be
// forgone at a penalty. A plan is then an order of the goals with a choice of action for each, and
// the best choices for a given order follow by dynamic programming over the few places each goal
// can be done at. Tour search builds an order by cheapest insertion and improves it by moving
// single goals and reversing stretches (the local search of vehicle routing, Or-opt and 2-opt),
// in milliseconds where a best-first search over goal subsets takes seconds. It proves nothing:
// the planner uses its plan as a first plan, and improves on it by search when asked to.
//
// It honours the stop condition (time limit, cancel, injected clock) at every order it evaluates,
// so a cancel from another thread stops it within one evaluation (microseconds:
// bench/search/cancel_bench.cc). Thread-safety: a free function without shared state; concurrent
// calls on one task are safe (the task is only read).
//
//   TourReport report;
//   if (auto r = tour_search(task, stop, clock, &report)) plan = r->plan;
//   // empty: not of this shape (!report.has_shape), stopped (report.stopped), or no tour found
#pragma once

#include <optional>
#include <span>

#include "sewerplan/domain/compiled_task.h"
#include "sewerplan/search/search_engine.h"

namespace sewerplan::search {

// A plan of `task` within its cost bound (with forgo actions for the goals left out when the
// bound calls for it and the task has them), checked by replaying it on the task. Empty when the
// task is not of the shape above, or no order found fits the bound. Runtime: O(goals^3 x
// options-per-goal^2) for the insertion, and as much per round of improvement (at most 50 rounds):
// each trial order is priced from the current one's costs, not evaluated whole.
// What a tour search found out besides its plan.
struct TourReport {
  bool has_shape = false;
  // The real cost of the cheapest order of all goals found (kInfiniteCost: none), also when it
  // does not fit the bound.
  Cost cheapest_order = domain::kInfiniteCost;
  // The stop condition fired: no plan, unless best_so_far.
  std::optional<SearchStatus> stopped;
  // It fired in the local search, after the cheapest insertion gave an order of every goal that
  // fits the bound: the plan is that order as far as the local search improved it (the planner's
  // anytime answer, PlanOutcome::best_so_far).
  bool best_so_far = false;
};

std::optional<SearchResult> tour_search(const domain::CompiledTask& task,
                                        const StopCondition& stop = {},
                                        const Clock* clock = nullptr, TourReport* report = nullptr);

// The exact tour search: the optimal plan of a task of the shape above, by dynamic programming
// over subsets of goals (Held and Karp 1962), with the bound (the battery) and optional goals
// (goal selection: the most goals that fit, then the cheapest). kSolved: the plan is optimal;
// kUnsolvable: proven that no plan fits the bound; kTimeLimit / kCancelled: stopped (checked
// every 256 subsets). Empty when the task is not of the shape, has more than kMaxExactGoals
// goals, or its memory would exceed `max_bytes`: the table, 2^(goals - 1) x leave places x 12
// bytes, and 17 bytes a subset (20 goals of 2 leave places take 257 MB), plus the move matrix
// (places^2 x 8 bytes) and the steps ((leave places + 1) x options x 24 bytes). `upper`: a known
// plan doing every goal costs this much (real cost; kInfiniteCost: none known): only plans doing
// every goal within it are then looked for, and subsets that cannot be completed within it are
// dropped early (the planner's improvement after the tour search). bench/search/exact_bench.cc has
// its speed and the default planner's gap to it.
// The quick answers of a planner past its deadline (the Replanner's anytime ladder,
// executor/replanner.h): no local search, so each is deterministic and takes microseconds on a
// compiled task (O(goals^3 x options-per-goal^2) at most, for the insertion).
// greedy_tour: the cheapest insertion from the start, with goals left out for the bound as
// tour_search does. ordered_tour: the goals of `order` (goal variables) in that order, the final
// goal (one that needs every other done) last wherever it is given, every other goal forgone;
// while that does not fit the bound, the goal whose absence leaves the cheapest plan is forgone
// too. Empty when the task is not of the tour's shape, `order` names a variable twice or one that
// is not a goal, a goal to forgo cannot be, or nothing fits; each plan is checked on the task.
std::optional<SearchResult> greedy_tour(const domain::CompiledTask& task,
                                        const StopCondition& stop = {},
                                        const Clock* clock = nullptr);
std::optional<SearchResult> ordered_tour(const domain::CompiledTask& task,
                                         std::span<const domain::VarId> order,
                                         const StopCondition& stop = {});

inline constexpr std::size_t kMaxExactGoals = 20;
inline constexpr std::size_t kExactDefaultBytes = std::size_t{600} << 20U;  // 600 MB
std::optional<SearchResult> exact_tour_search(const domain::CompiledTask& task,
                                              const StopCondition& stop = {},
                                              const Clock* clock = nullptr,
                                              std::size_t max_bytes = kExactDefaultBytes,
                                              Cost upper = domain::kInfiniteCost);

}  // namespace sewerplan::search
