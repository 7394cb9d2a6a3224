// SPDX-License-Identifier: MIT
// The brute-force oracle: a cheapest plan by uniform-cost search, for testing the planner.
//
// The planner's A* (search/) must return plans exactly as cheap as the cheapest; on small maps
// (up to about 8 tasks and 50 manholes) this oracle finds one with no cleverness at all: Dijkstra's
// algorithm over (robot position, tasks done), where every candidate step is tried, and applied,
// by the independent validator's PlanReplay::apply (sewerplan/domain/validator.h), so that the
// oracle shares nothing with the planner but docs/domain.md. Energy is proportional to time, so the
// cheapest way to each state is also the most frugal one, and the battery check of apply keeps
// the search exact.
//
//   BruteForceOutcome best = brute_force_optimal_plan(map, mission);
//   ASSERT_TRUE(best.has_value()) << to_string(best.status());
//   EXPECT_NEAR(planner_cost_s, best->cost_s, 1e-6);
//
// Candidate steps from each position: in pipe P, DRIVE_PIPE_TO_MANHOLE to each end's manhole and
// the actions of the tasks in P (INSPECT_PIPE finishing at either end); at M, slot i,
// DRIVE_MANHOLE to every other slot and GO_TO_MANHOLE; in manhole M, ENTER_PIPE into each slot's
// pipe and GO_TO_MANHOLE. Ties are broken by the order states were first reached, and candidates
// are tried in the order above, so the result is deterministic.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/domain/robot_state.h"

namespace sewerplan::testing {

struct BruteForceResult {
  domain::Plan plan;
  double cost_s = 0;  // the sum of the plan's step costs, in plan order, as the validator adds
};

enum class BruteForceStatus {
  kFound,       // a cheapest plan
  kNoPlan,      // every reachable state was expanded and none reaches the goal
  kStateLimit,  // more than max_states states were reached before a goal; nothing is known
};

std::string_view to_string(BruteForceStatus status);

// What the oracle found: used like std::optional<BruteForceResult> (has_value, *, ->), and says
// why there is no value.
class BruteForceOutcome {
 public:
  BruteForceOutcome(BruteForceStatus status, std::optional<BruteForceResult> result,
                    std::size_t states)
      : status_(status), result_(std::move(result)), states_(states) {}

  BruteForceStatus status() const { return status_; }
  // Distinct states reached (position and tasks done).
  std::size_t states() const { return states_; }
  bool has_value() const { return result_.has_value(); }
  const BruteForceResult& value() const { return result_.value(); }
  const BruteForceResult& operator*() const { return *result_; }
  const BruteForceResult* operator->() const { return &*result_; }

 private:
  BruteForceStatus status_;
  std::optional<BruteForceResult> result_;
  std::size_t states_;
};

// A cheapest plan from `start` (which must satisfy domain::start_problem). Memory: about 300
// bytes a state, so the default limit is some 600 MB at worst; small maps need far less.
BruteForceOutcome brute_force_optimal_plan(const SewerMap& map, const Mission& mission,
                                           const domain::MissionProgress& start,
                                           std::size_t max_states = 2'000'000);
// From the mission's start.
BruteForceOutcome brute_force_optimal_plan(const SewerMap& map, const Mission& mission,
                                           std::size_t max_states = 2'000'000);

}  // namespace sewerplan::testing
