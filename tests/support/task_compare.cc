// SPDX-License-Identifier: MIT
#include "support/task_compare.h"

#include <algorithm>
#include <variant>

#include <gtest/gtest.h>

namespace sewerplan::testing {

using domain::ActionId;
using domain::CompiledTask;
using domain::DrivePipeToManhole;
using domain::PlanStep;

void expect_same_task(const domain::SewerTask& a, const domain::SewerTask& b) {
  const CompiledTask& x = a.task();
  const CompiledTask& y = b.task();
  ASSERT_EQ(x.variable_count(), y.variable_count());
  ASSERT_EQ(x.action_count(), y.action_count());
  EXPECT_EQ(x.cost_bound(), y.cost_bound());
  for (ActionId id : x.action_ids()) {
    ASSERT_EQ(x.action_name(id), y.action_name(id));
    EXPECT_EQ(x.cost(id), y.cost(id)) << x.action_name(id);
    EXPECT_EQ(x.reserve(id), y.reserve(id)) << x.action_name(id);
    const auto pre_x = x.preconditions(id), pre_y = y.preconditions(id);
    const auto eff_x = x.effects(id), eff_y = y.effects(id);
    EXPECT_TRUE(std::equal(pre_x.begin(), pre_x.end(), pre_y.begin(), pre_y.end()));
    EXPECT_TRUE(std::equal(eff_x.begin(), eff_x.end(), eff_y.begin(), eff_y.end()));
    const ActionId one[] = {id};
    EXPECT_EQ(a.expand(one).steps.size(), b.expand(one).steps.size()) << x.action_name(id);
  }
}

void expect_identical_task(const domain::SewerTask& a, const domain::SewerTask& b) {
  expect_same_task(a, b);
  for (ActionId id : b.task().action_ids()) {
    const ActionId one[] = {id};
    EXPECT_EQ(a.expand(one).steps, b.expand(one).steps) << b.task().action_name(id);
  }
}

std::vector<PipeId> driven_pipes(const domain::SewerTask& task) {
  std::vector<PipeId> pipes;
  for (ActionId id : task.task().action_ids()) {
    const ActionId one[] = {id};
    for (const PlanStep& s : task.expand(one).steps) {
      if (const auto* d = std::get_if<DrivePipeToManhole>(&s)) {
        if (std::find(pipes.begin(), pipes.end(), d->pipe) == pipes.end()) pipes.push_back(d->pipe);
      }
    }
  }
  return pipes;
}

}  // namespace sewerplan::testing
