// SPDX-License-Identifier: MIT
// Checks that two compiled tasks are the same (issue 35: a compile from the route memo, the
// routing index or a loaded index against one afresh; a compile of a renumbered map).
#pragma once

#include "sewerplan/domain/compile.h"

namespace sewerplan::testing {

// The same up to a renaming of the map's objects: the same variables, the same actions with the
// same preconditions, effects, costs, reserves and names, each expanding to as many steps.
void expect_same_task(const domain::SewerTask& a, const domain::SewerTask& b);

// The same, and each action expanding to the same steps: route for route.
void expect_identical_task(const domain::SewerTask& a, const domain::SewerTask& b);

}  // namespace sewerplan::testing
