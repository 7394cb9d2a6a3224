// SPDX-License-Identifier: MIT
#include "tour_shape.h"

namespace sewerplan::search::detail {

using domain::Fact;
using domain::VarId;

namespace {
constexpr std::size_t kCheckEvery = 1024;
bool fired(const StopCondition* stop, std::size_t i) {
  return i % kCheckEvery == 0 && stop != nullptr && stop->interrupted().has_value();
}
}  // namespace

std::optional<Shape> read_shape(const CompiledTask& task, const StopCondition* stop) {
  if (task.variable_count() < 1) return std::nullopt;
  Shape s;
  const VarId pos{0};
  s.places = task.domain_size(pos);
  s.bound = task.cost_bound();
  s.start = task.initial_state()[0];
  const std::size_t goals = task.variable_count() - 1;
  s.goals.resize(goals);
  for (std::size_t v = 1; v < task.variable_count(); ++v) {
    if (task.domain_size(VarId{static_cast<std::uint32_t>(v)}) != 2) return std::nullopt;
    if (task.initial_state()[v] != 0) return std::nullopt;
  }
  std::vector<bool> goal_var(task.variable_count(), false);
  for (const Fact& g : task.goal()) {
    if (g.var == pos) {
      s.end = g.value;
    } else if (g.value == 1) {
      goal_var[g.var.index()] = true;
    } else {
      return std::nullopt;
    }
  }
  for (std::size_t v = 1; v < goal_var.size(); ++v) {
    if (!goal_var[v]) return std::nullopt;
  }
  const bool dense = s.places > 0 && s.places <= Shape::kDensePlaces;
  const auto n = static_cast<std::size_t>(s.places);
  if (dense) {
    // Filled a row at a time with a check between rows: the whole matrix at once was fresh memory
    // of 7.5 ms to touch on 200 tasks (issue 14).
    s.move_matrix.reserve(n * n);
    s.move_actions.reserve(n * n);
    for (std::size_t a = 0; a < n; ++a) {
      if (fired(stop, 0)) return std::nullopt;
      s.move_matrix.insert(s.move_matrix.end(), n, kInfiniteCost);
      s.move_matrix[a * n + a] = 0;
      s.move_actions.insert(s.move_actions.end(), n, Shape::kNoAction);
    }
    if (!s.moves.reserve(n, stop)) return std::nullopt;  // the moves that stay in place
  } else {
    // Sized once: rehashing every move at once as the map grew took 6 to 14 ms on 200 tasks
    // between two checks (issue 14). At most one move per action.
    if (!s.moves.reserve(task.action_count(), stop)) return std::nullopt;
  }
  if (fired(stop, 0)) return std::nullopt;
  for (ActionId a : task.action_ids()) {
    if (fired(stop, a.index())) return std::nullopt;
    const auto pre = task.preconditions(a);
    const auto eff = task.effects(a);
    std::optional<std::int32_t> at, to;
    std::optional<std::size_t> goal;
    std::size_t others = 0;
    for (const Fact& f : pre) {
      if (f.var == pos) {
        at = f.value;
      } else if (f.value == 0) {
        if (goal) return std::nullopt;
        goal = f.var.index() - 1;
      } else {
        ++others;
      }
    }
    bool sets_goal = false;
    for (const Fact& f : eff) {
      if (f.var == pos) {
        to = f.value;
      } else if (goal && f.var.index() - 1 == *goal && f.value == 1) {
        sets_goal = true;
      } else {
        return std::nullopt;
      }
    }
    if (!goal) {  // a move
      if (!at || !to || others != 0 || eff.size() != 1) return std::nullopt;
      auto key = static_cast<std::int64_t>(*at) * s.places + *to;
      // The first move between two places, or a cheaper one later.
      bool chosen = false;
      if (dense && *at != *to) {
        const auto i = static_cast<std::size_t>(key);
        if (s.move_actions[i] == Shape::kNoAction || task.cost(a) < s.move_matrix[i]) {
          s.move_matrix[i] = task.cost(a);
          s.move_actions[i] = a;
        }
        chosen = s.move_actions[i] == a;
      } else {
        auto [move, added] = s.moves.try_emplace(key, {task.cost(a), a});
        if (!added && task.cost(a) < move->cost) *move = {task.cost(a), a};
        chosen = move->action == a;
      }
      if (chosen) {
        if (task.reserve(a) > 0) {
          s.move_reserves[key] = task.reserve(a);
        } else {
          s.move_reserves.erase(key);
        }
      }
      continue;
    }
    if (!sets_goal) return std::nullopt;
    Goal& g = s.goals[*goal];
    if (others != 0 && others + 1 != goals) return std::nullopt;  // all others, or none
    if (others != 0) g.last = true;
    if (!at) {  // a forgo action
      if (to || others != 0) return std::nullopt;
      g.forgo = a;
      g.forgo_cost = task.cost(a);
      continue;
    }
    g.options.push_back({*at, to.value_or(kStays), task.cost(a), a, task.reserve(a)});
  }
  return s;
}

}  // namespace sewerplan::search::detail
