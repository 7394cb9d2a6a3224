// SPDX-License-Identifier: MIT
// Checks that two compiled tasks are the same (issue 35: a compile from the route memo, the
// routing index or a loaded index against one afresh; a compile of a renumbered map).
#pragma once

#include <vector>

#include "sewerplan/domain/compile.h"

namespace sewerplan::testing {

// The same up to a renaming of the map's objects: the same variables, the same actions with the
// same preconditions, effects, costs, reserves and names, each expanding to as many steps.
void expect_same_task(const domain::SewerTask& a, const domain::SewerTask& b);

// The same, and each action expanding to the same steps: route for route.
void expect_identical_task(const domain::SewerTask& a, const domain::SewerTask& b);

// The pipes the routes of `task`'s moves drive, in action order, each once (the pipes a test
// blocks or closes to make a replan's routes change).
std::vector<PipeId> driven_pipes(const domain::SewerTask& task);

}  // namespace sewerplan::testing
