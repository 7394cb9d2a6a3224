// SPDX-License-Identifier: MIT
// The shape of a tour task (tour_search.h): one mover over places, goals done by actions at places.
// Private to search: read by the tour search and by the exact search over goal subsets.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "sewerplan/core/check.h"
#include "sewerplan/core/clock.h"
#include "sewerplan/core/stop_condition.h"
#include "sewerplan/domain/compiled_task.h"
#include "sewerplan/search/tour_search.h"

#include "move_map.h"

namespace sewerplan::search::detail {

using domain::ActionId;
using domain::CompiledTask;
using domain::Cost;
using domain::kInfiniteCost;

constexpr std::int32_t kStays = -1;

struct Option {
  std::int32_t at = 0;  // the position the action needs
  std::int32_t to = 0;  // where it leaves the robot (kStays: where it was)
  Cost cost = 0;
  ActionId action{0};
  Cost reserve = 0;  // CompiledTask::reserve: battery needed beyond the cost when it starts
};

struct Goal {
  std::vector<Option> options;
  std::optional<ActionId> forgo;
  Cost forgo_cost = 0;
  bool last = false;  // needs every other goal done first
};

struct Shape {
  std::int32_t places = 0;
  std::int32_t start = 0;
  std::optional<std::int32_t> end;  // a position the goal asks for
  // The cheapest move between two places, its cost and action. Where places <= kDensePlaces they
  // are two places x places matrices (cost 0 on the diagonal), and `moves` holds only the moves
  // that stay in place: the tour search reads a move's cost in its innermost loop, and a hash
  // lookup there took half its time (issue 16: 50 tasks on 1,000 manholes); and a hash map's nodes
  // are freed one by one, 3.5 to 5.4 ms for 200 tasks' 160,000 moves between a stop and the
  // return (issue 14), a matrix at once. Beyond kDensePlaces, `moves` holds them all, in one flat
  // table (move_map.h) for the same reason.
  MoveMap moves;
  std::vector<Cost> move_matrix;
  std::vector<ActionId> move_actions;  // beside move_matrix; kNoAction where there is no move
  std::vector<Goal> goals;             // goal i is variable i + 1
  Cost bound = kInfiniteCost;          // the task's cost bound
  std::unordered_map<std::int64_t, Cost> move_reserves;  // the moves' nonzero reserves

  static constexpr std::int32_t kDensePlaces = 2048;  // 48 MB at most
  static constexpr ActionId kNoAction{std::numeric_limits<ActionId::rep_type>::max()};

  Cost move_cost(std::int32_t a, std::int32_t b) const {
    if (!move_matrix.empty()) {
      return move_matrix[static_cast<std::size_t>(a) * static_cast<std::size_t>(places) +
                         static_cast<std::size_t>(b)];
    }
    if (a == b) return 0;
    const MoveMap::Move* m = moves.find(static_cast<std::int64_t>(a) * places + b);
    return m == nullptr ? kInfiniteCost : m->cost;
  }
  // The action of the cheapest move from a to b (a != b); precondition: there is one.
  ActionId move_action(std::int32_t a, std::int32_t b) const {
    if (!move_actions.empty()) {
      return move_actions[static_cast<std::size_t>(a) * static_cast<std::size_t>(places) +
                          static_cast<std::size_t>(b)];
    }
    const MoveMap::Move* m = moves.find(static_cast<std::int64_t>(a) * places + b);
    SEWER_CHECK(m != nullptr, "Shape::move_action: no move between the two places");
    return m->action;
  }
  // Whether any move or option keeps a contingency reserve: then whether a move fits depends on
  // what was spent before it, not only on costs.
  bool has_reserves() const {
    if (!move_reserves.empty()) return true;
    for (const Goal& g : goals) {
      for (const Option& o : g.options) {
        if (o.reserve > 0) return true;
      }
    }
    return false;
  }
  Cost move_reserve(std::int32_t a, std::int32_t b) const {
    if (a == b || move_reserves.empty()) return 0;
    auto it = move_reserves.find(static_cast<std::int64_t>(a) * places + b);
    return it == move_reserves.end() ? 0 : it->second;
  }
  // Whether an action of cost `cost` and reserve `reserve`, started with `g` spent, stays within
  // the bound (CompiledTask::exceeds_bound_before, for real costs).
  bool fits(Cost g, Cost cost, Cost reserve) const {
    return reserve == 0 || bound >= kInfiniteCost || g + cost + reserve <= bound;
  }
};

// The task read as places, moves and goals; empty if it is not of that shape, or if `stop` (may
// be null) fired: it is asked every 1,024 actions, before each row of the move matrices and
// between slices of the move map (issue 14: 200 tasks have 160,000 moves, 59 ms of reading), so a
// caller given nothing asks `stop` why.
std::optional<Shape> read_shape(const CompiledTask& task, const StopCondition* stop = nullptr);

// The tour search and the exact search (tour_search.h) on the shape read_shape() gave for `task`
// (`shape`, read since `start_s` on `clock`): the planner reads it once for both (reading it
// costs as much as a fifth of the exact search on 10 manholes and 10 tasks).
std::optional<SearchResult> tour_search(const CompiledTask& task, const std::optional<Shape>& shape,
                                        const StopCondition& stop, const Clock& clock,
                                        double start_s, TourReport& report,
                                        bool local_search = true);
std::optional<SearchResult> exact_tour_search(const CompiledTask& task,
                                              const std::optional<Shape>& shape,
                                              const StopCondition& stop, const Clock& clock,
                                              double start_s, std::size_t max_bytes, Cost upper);

}  // namespace sewerplan::search::detail
