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
//   if (auto r = tour_search(task)) plan = r->plan;  // empty: not of this shape, or no tour found
#pragma once

#include <optional>

#include "sewerplan/domain/compiled_task.h"
#include "sewerplan/search/search_engine.h"

namespace sewerplan::search {

// A plan of `task` within its cost bound (with forgo actions for the goals left out when the
// bound calls for it and the task has them), checked by replaying it on the task. Empty when the
// task is not of the shape above, or no order found fits the bound. Runtime: O(goals^3 x
// places-per-goal^2) for the insertion, and as much per round of improvement (at most 50 rounds).
std::optional<SearchResult> tour_search(const domain::CompiledTask& task);

}  // namespace sewerplan::search
