// SPDX-License-Identifier: MIT
#include "sewerplan/domain/compiled_task.h"

#include <algorithm>
#include <cmath>

#include "sewerplan/core/check.h"

namespace sewerplan::domain {

Cost to_cost(double seconds) { return static_cast<Cost>(std::llround(seconds * 1000.0)); }
double to_seconds(Cost cost) { return static_cast<double>(cost) / 1000.0; }

std::span<const Fact> CompiledTask::preconditions(ActionId a) const {
  return std::span<const Fact>(facts_).subspan(pre_begin_[a.index()],
                                               eff_begin_[a.index()] - pre_begin_[a.index()]);
}

std::span<const Fact> CompiledTask::effects(ActionId a) const {
  return std::span<const Fact>(facts_).subspan(eff_begin_[a.index()],
                                               pre_begin_[a.index() + 1] - eff_begin_[a.index()]);
}

bool CompiledTask::is_applicable(ActionId a, std::span<const std::int32_t> state) const {
  for (const Fact& f : preconditions(a)) {
    if (state[f.var.index()] != f.value) return false;
  }
  return true;
}

void CompiledTask::applicable_actions(std::span<const std::int32_t> state,
                                      std::vector<ActionId>& out) const {
  out.clear();
  for (std::size_t v = 0; v < domain_sizes_.size(); ++v) {
    const std::size_t fact = fact_offsets_[v] + static_cast<std::size_t>(state[v]);
    for (std::uint32_t i = by_fact_begin_[fact]; i < by_fact_begin_[fact + 1]; ++i) {
      if (is_applicable(by_fact_[i], state)) out.push_back(by_fact_[i]);
    }
  }
  out.insert(out.end(), unconditional_.begin(), unconditional_.end());
  std::sort(out.begin(), out.end());
}

void CompiledTask::apply(ActionId a, std::span<std::int32_t> state) const {
  for (const Fact& f : effects(a)) state[f.var.index()] = f.value;
}

bool CompiledTask::is_goal(std::span<const std::int32_t> state) const {
  return std::all_of(goal_.begin(), goal_.end(),
                     [&](const Fact& f) { return state[f.var.index()] == f.value; });
}

VarId CompiledTask::Builder::add_variable(std::int32_t domain_size, std::string name) {
  SEWER_CHECK(domain_size >= 1, "a variable needs at least one value");
  task_.domain_sizes_.push_back(domain_size);
  task_.variable_names_.push_back(std::move(name));
  return VarId{static_cast<std::uint32_t>(task_.domain_sizes_.size() - 1)};
}

ActionId CompiledTask::Builder::add_action(std::span<const Fact> preconditions,
                                           std::span<const Fact> effects, Cost cost,
                                           std::string name) {
  SEWER_CHECK(cost >= 0, "action costs are not negative");
  if (task_.pre_begin_.empty()) task_.pre_begin_.push_back(0);
  // One by one: most actions have a fact or two, and a range insert costs more (issue 16).
  for (const Fact& f : preconditions) task_.facts_.push_back(f);
  task_.eff_begin_.push_back(static_cast<std::uint32_t>(task_.facts_.size()));
  for (const Fact& f : effects) task_.facts_.push_back(f);
  task_.pre_begin_.push_back(static_cast<std::uint32_t>(task_.facts_.size()));
  task_.costs_.push_back(cost);
  task_.names_.push_back(std::move(name));
  return ActionId{static_cast<std::uint32_t>(task_.costs_.size() - 1)};
}

void CompiledTask::Builder::reserve(std::size_t actions, std::size_t facts) {
  const std::size_t n = task_.costs_.size() + actions;
  task_.facts_.reserve(task_.facts_.size() + facts);
  task_.pre_begin_.reserve(n + 1);
  task_.eff_begin_.reserve(n);
  task_.costs_.reserve(n);
  task_.names_.reserve(n);
}

void CompiledTask::Builder::set_initial(std::vector<std::int32_t> values) {
  task_.initial_ = std::move(values);
}

void CompiledTask::Builder::add_goal(Fact fact) { task_.goal_.push_back(fact); }

void CompiledTask::Builder::set_cost_bound(Cost bound) { task_.cost_bound_ = bound; }

void CompiledTask::Builder::set_reserve(ActionId a, Cost reserve) {
  if (task_.reserve_.size() < task_.costs_.size()) task_.reserve_.resize(task_.costs_.size(), 0);
  const Cost cap = task_.cost_bound_ >= kInfiniteCost ? kInfiniteCost / 4 : task_.cost_bound_ + 1;
  task_.reserve_[a.index()] = std::clamp<Cost>(reserve, 0, cap);
}

bool CompiledTask::solves(std::span<const ActionId> plan, Cost* cost) const {
  std::vector<std::int32_t> state(initial_.begin(), initial_.end());
  Cost g = 0;
  for (ActionId a : plan) {
    if (!is_applicable(a, state) || exceeds_bound_before(g, a)) return false;
    apply(a, state);
    g += costs_[a.index()];
  }
  if (cost != nullptr) *cost = g;
  return is_goal(state) && !exceeds_bound(g);
}

void CompiledTask::Builder::set_penalty_unit(Cost unit) { task_.penalty_unit_ = unit; }

CompiledTask CompiledTask::Builder::build() && {
  CompiledTask& t = task_;
  if (t.pre_begin_.empty()) t.pre_begin_.push_back(0);
  if (!t.reserve_.empty()) t.reserve_.resize(t.costs_.size(), 0);
  SEWER_CHECK(t.initial_.size() == t.domain_sizes_.size(), "one initial value per variable");
  SEWER_CHECK(t.penalty_unit_ == 0 || t.penalty_unit_ / 2 > t.cost_bound_,
              "the penalty unit must exceed twice the cost bound");
  auto valid = [&](const Fact& f) {
    return f.var.index() < t.domain_sizes_.size() && f.value >= 0 &&
           f.value < t.domain_sizes_[f.var.index()];
  };
  for (std::size_t v = 0; v < t.initial_.size(); ++v) {
    SEWER_CHECK(valid(Fact{VarId{static_cast<std::uint32_t>(v)}, t.initial_[v]}),
                "initial value outside its domain");
  }
  SEWER_CHECK(std::all_of(t.facts_.begin(), t.facts_.end(), valid),
              "action fact outside its domain");
  SEWER_CHECK(std::all_of(t.goal_.begin(), t.goal_.end(), valid), "goal fact outside its domain");
  t.fact_offsets_.assign(t.domain_sizes_.size() + 1, 0);
  for (std::size_t v = 0; v < t.domain_sizes_.size(); ++v) {
    t.fact_offsets_[v + 1] = t.fact_offsets_[v] + static_cast<std::size_t>(t.domain_sizes_[v]);
  }
  // Counting sort of the actions by their first precondition.
  std::vector<std::uint32_t> count(t.fact_count() + 1, 0);
  for (ActionId a : t.action_ids()) {
    auto pre = t.preconditions(a);
    if (pre.empty()) {
      t.unconditional_.push_back(a);
    } else {
      ++count[t.fact_index(pre[0]) + 1];
    }
  }
  for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
  t.by_fact_begin_ = count;
  t.by_fact_.assign(t.action_count() - t.unconditional_.size(), ActionId{0});
  for (ActionId a : t.action_ids()) {
    auto pre = t.preconditions(a);
    if (!pre.empty()) t.by_fact_[count[t.fact_index(pre[0])]++] = a;
  }
  return std::move(task_);
}

}  // namespace sewerplan::domain
