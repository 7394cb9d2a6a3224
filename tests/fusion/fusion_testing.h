// SPDX-License-Identifier: MIT
// Helpers for the fusion tests: parse a plan text, and fuse it from the mission's start.
#pragma once

#include <string_view>

#include <gtest/gtest.h>

#include "sewerplan/domain/plan_text.h"
#include "sewerplan/fusion/fuse.h"

namespace sewerplan::fusion::testing {

// The plan, or (with a test failure) an empty one.
inline domain::Plan parse(std::string_view text, const SewerMap& map, const Mission& mission) {
  Diagnostics diagnostics;
  Result<domain::Plan> plan = domain::parse_plan(text, "test.plan", map, mission, diagnostics);
  EXPECT_TRUE(plan.has_value()) << plan.error();
  return plan.has_value() ? *plan : domain::Plan{};
}

inline Result<FusedPlan> fuse_text(std::string_view text, const SewerMap& map,
                                   const Mission& mission, const FuseOptions& options = {}) {
  return fuse(parse(text, map, mission), map, mission, domain::initial_progress(mission, map),
              options);
}

}  // namespace sewerplan::fusion::testing
