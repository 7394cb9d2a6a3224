// SPDX-License-Identifier: MIT
// CompiledTask: a planning task in finite-domain form, what the search engines work on.
//
// Variables with small finite domains, an initial value for each, a goal (a set of facts
// var = value), and ground actions with preconditions and effects (facts) and an integer cost in
// milliseconds, after Helmert's SAS+ representation as used by Fast Downward (Helmert 2006,
// "The Fast Downward planning system", JAIR 26). A plan must cost at most cost_bound(): the
// battery, for the sewer domain. The sewer compiler (compile.h) builds one from a map and a
// mission; the engines in search/ know nothing of sewers, only this class.
//
// IDs (VarId, ActionId) are dense from 0 and belong to one task: do not mix them across tasks.
//
//   CompiledTask::Builder b;
//   VarId pos = b.add_variable(3, "position");
//   ActionId go = b.add_action({{pos, 0}}, {{pos, 2}}, 1500, "go 0->2");
//   b.set_initial({0});
//   b.add_goal({pos, 2});
//   CompiledTask task = std::move(b).build();
//   std::vector<ActionId> applicable;
//   task.applicable_actions(task.initial_state(), applicable);  // {go}
//
// Thread-safety: a CompiledTask is immutable once built, and its const methods are safe from any
// number of threads; a Builder belongs to one thread.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "sewerplan/core/strong_id.h"

namespace sewerplan::domain {

using VarId = StrongId<struct VarTag>;
using ActionId = StrongId<struct ActionTag>;

// Costs are integer milliseconds: sums are exact and the same on every machine.
using Cost = std::int64_t;
inline constexpr Cost kInfiniteCost = std::numeric_limits<Cost>::max() / 4;

// Seconds to milliseconds, rounded to the nearest.
Cost to_cost(double seconds);
double to_seconds(Cost cost);

struct Fact {
  VarId var{0};
  std::int32_t value = 0;
  friend bool operator==(const Fact&, const Fact&) = default;
};

class CompiledTask {
 public:
  class Builder;

  std::size_t variable_count() const { return domain_sizes_.size(); }
  std::int32_t domain_size(VarId var) const { return domain_sizes_[var.index()]; }
  const std::string& variable_name(VarId var) const { return variable_names_[var.index()]; }
  std::span<const std::int32_t> initial_state() const { return initial_; }
  std::span<const Fact> goal() const { return goal_; }

  std::size_t action_count() const { return costs_.size(); }
  IdRange<ActionId> action_ids() const { return id_range<ActionId>(costs_.size()); }
  std::span<const Fact> preconditions(ActionId a) const;
  std::span<const Fact> effects(ActionId a) const;
  Cost cost(ActionId a) const { return costs_[a.index()]; }
  const std::string& action_name(ActionId a) const { return names_[a.index()]; }

  // Plans costing more than this are not plans (kInfiniteCost: no bound).
  Cost cost_bound() const { return cost_bound_; }
  // Goal selection (compile.h) makes goals optional: forgoing one costs a penalty of
  // penalty_unit() (0: no optional goals), more than any plan within the bound can cost. A cost
  // is then (goals forgone) x penalty_unit() + the real cost, optimal plans forgo as few goals as
  // possible, and the bound applies to the real cost only. The unit is more than twice the bound,
  // so that one action past the bound cannot wrap into the next multiple.
  Cost penalty_unit() const { return penalty_unit_; }
  Cost real_cost(Cost cost) const { return penalty_unit_ > 0 ? cost % penalty_unit_ : cost; }
  bool exceeds_bound(Cost cost) const { return real_cost(cost) > cost_bound_; }
  // Battery an action needs left beyond its own cost when it starts (0 for most): a contingency
  // the plan must be able to pay for, such as backing out of a pipe that turns out blocked and
  // driving to an exit another way (compile.h, contingency-aware battery planning). An action
  // with `g` spent before it may be applied only if g + cost + reserve stays within the bound.
  Cost reserve(ActionId a) const { return reserve_.empty() ? 0 : reserve_[a.index()]; }
  bool exceeds_bound_before(Cost g_before, ActionId a) const {
    const Cost after = g_before + cost(a);
    return exceeds_bound(after) || real_cost(after) + reserve(a) > cost_bound_;
  }
  // Whether `plan` is applicable from the initial state, reaches the goal and stays within the
  // bound at every action, its reserve included; its cost in `cost` (if given).
  bool solves(std::span<const ActionId> plan, Cost* cost = nullptr) const;

  // Total number of facts, and a dense index of each (for heuristics' per-fact arrays).
  std::size_t fact_count() const { return fact_offsets_.back(); }
  std::size_t fact_index(Fact f) const {
    return fact_offsets_[f.var.index()] + static_cast<std::size_t>(f.value);
  }

  // Replaces `out` with the actions applicable in `state`, in increasing ID order.
  // Runtime: O(variables + candidate actions), no allocation once `out` has grown.
  void applicable_actions(std::span<const std::int32_t> state, std::vector<ActionId>& out) const;
  bool is_applicable(ActionId a, std::span<const std::int32_t> state) const;
  // Applies `a`'s effects to `state` in place. Precondition: a is applicable.
  void apply(ActionId a, std::span<std::int32_t> state) const;
  bool is_goal(std::span<const std::int32_t> state) const;

 private:
  std::vector<std::int32_t> domain_sizes_;
  std::vector<std::string> variable_names_;
  std::vector<std::int32_t> initial_;
  std::vector<Fact> goal_;
  // Actions: preconditions and effects flattened (CSR), costs, names.
  std::vector<std::uint32_t> pre_begin_;
  std::vector<std::uint32_t> eff_begin_;
  std::vector<Fact> facts_;
  std::vector<Cost> costs_;
  std::vector<Cost> reserve_;  // empty: none
  std::vector<std::string> names_;
  Cost cost_bound_ = kInfiniteCost;
  Cost penalty_unit_ = 0;
  // Successor index: actions by their first precondition's fact (CSR over fact_index), and the
  // actions without preconditions.
  std::vector<std::size_t> fact_offsets_;
  std::vector<std::uint32_t> by_fact_begin_;
  std::vector<ActionId> by_fact_;
  std::vector<ActionId> unconditional_;
};

class CompiledTask::Builder {
 public:
  VarId add_variable(std::int32_t domain_size, std::string name);
  ActionId add_action(std::span<const Fact> preconditions, std::span<const Fact> effects, Cost cost,
                      std::string name);
  ActionId add_action(std::initializer_list<Fact> preconditions,
                      std::initializer_list<Fact> effects, Cost cost, std::string name) {
    return add_action(std::span<const Fact>(preconditions.begin(), preconditions.size()),
                      std::span<const Fact>(effects.begin(), effects.size()), cost,
                      std::move(name));
  }
  // Room for `actions` more actions with `facts` facts in all (conditions and effects), so that
  // adding them does not grow the arrays step by step.
  void reserve(std::size_t actions, std::size_t facts);
  void set_initial(std::vector<std::int32_t> values);
  void add_goal(Fact fact);
  void set_cost_bound(Cost bound);
  // CompiledTask::reserve(a); at most the bound plus one (more could wrap a penalty unit).
  void set_reserve(ActionId a, Cost reserve);
  // Precondition: more than twice the cost bound (see penalty_unit()).
  void set_penalty_unit(Cost unit);
  // Checks every fact against its variable's domain (SEWER_CHECK: a compiler bug otherwise).
  CompiledTask build() &&;

 private:
  CompiledTask task_;
};

}  // namespace sewerplan::domain
