// SPDX-License-Identifier: MIT
#include "relaxed_task.h"

#include <algorithm>
#include <functional>

namespace sewerplan::search::detail {

using domain::Fact;
using domain::kInfiniteCost;

namespace {
// Work between two checks of the stop condition: well under 0.1 ms each.
constexpr std::uint32_t kCheckEvery = 1024;

bool fired(const StopCondition* stop) { return stop != nullptr && stop->interrupted().has_value(); }
}  // namespace

bool RelaxedTask::build(const StopCondition* stop) {
  if (built_) return true;
  const auto actions = static_cast<std::uint32_t>(task_.action_count());
  while (next_action_ < actions) {
    if (next_action_ % kCheckEvery == 0 && fired(stop)) return false;
    const ActionId a{next_action_++};
    const auto pre = task_.preconditions(a);
    const auto begin = static_cast<std::uint32_t>(preconditions_.size());
    for (const Fact& f : pre)
      preconditions_.push_back(static_cast<std::uint32_t>(task_.fact_index(f)));
    for (const Fact& f : task_.effects(a)) {
      operators_.push_back({begin, static_cast<std::uint32_t>(pre.size()),
                            static_cast<std::uint32_t>(task_.fact_index(f)), a, task_.cost(a)});
    }
  }
  if (fired(stop)) return false;
  index_consumers();
  built_ = true;
  return true;
}

void RelaxedTask::index_consumers() {
  const domain::CompiledTask& task = task_;
  // Consumers: counting sort of (fact, operator) pairs by fact.
  consumer_begin_.assign(task.fact_count() + 1, 0);
  for (const UnaryOperator& op : operators_) {
    for (std::uint32_t f : preconditions(op)) ++consumer_begin_[f + 1];
  }
  for (std::size_t f = 1; f < consumer_begin_.size(); ++f)
    consumer_begin_[f] += consumer_begin_[f - 1];
  consumers_.resize(consumer_begin_.back());
  std::vector<std::uint32_t> next(consumer_begin_.begin(), consumer_begin_.end() - 1);
  for (std::uint32_t o = 0; o < operators_.size(); ++o) {
    for (std::uint32_t f : preconditions(operators_[o])) consumers_[next[f]++] = o;
  }
  for (const Fact& g : task.goal())
    goal_facts_.push_back(static_cast<std::uint32_t>(task.fact_index(g)));
}

RelaxedExploration::Outcome RelaxedExploration::explore(std::span<const std::int32_t> state,
                                                        Combine combine,
                                                        const StopCondition* stop) {
  const auto& ops = relaxed_.operators();
  const domain::CompiledTask& task = relaxed_.task();
  fact_cost_.assign(relaxed_.fact_count(), kInfiniteCost);
  supporter_.assign(relaxed_.fact_count(), kNoSupporter);
  settled_.assign(relaxed_.fact_count(), false);
  op_cost_.resize(ops.size());
  unsatisfied_.resize(ops.size());
  heap_.clear();
  const auto later = std::greater<std::pair<Cost, std::uint32_t>>();
  // At equal cost the later supporter wins while the fact is unsettled: its preconditions cost
  // more, so it extends a chain rather than starting afresh from the state. With macro actions
  // over exact shortest routes, a key on the way to another then supports it, and FF's relaxed
  // plan becomes a tree of routes instead of a star of them from the current position
  // (bench/search/planner_bench.cc: EHC's plans on 20 tasks got 25-40% cheaper).
  auto reach = [&](std::uint32_t f, Cost c, std::uint32_t op) {
    if (c < fact_cost_[f]) {
      fact_cost_[f] = c;
      supporter_[f] = op;
      heap_.emplace_back(c, f);
      std::push_heap(heap_.begin(), heap_.end(), later);
    } else if (c == fact_cost_[f] && !settled_[f] && op != kNoSupporter) {
      supporter_[f] = op;
    }
  };
  for (std::uint32_t o = 0; o < ops.size(); ++o) {
    if (o % kCheckEvery == 0 && fired(stop)) return Outcome::kInterrupted;
    op_cost_[o] = ops[o].cost;
    unsatisfied_[o] = ops[o].pre_count;
    if (ops[o].pre_count == 0) reach(ops[o].effect, ops[o].cost, o);
  }
  for (std::size_t v = 0; v < state.size(); ++v) {
    reach(static_cast<std::uint32_t>(
              task.fact_index({domain::VarId{static_cast<std::uint32_t>(v)}, state[v]})),
          0, kNoSupporter);
  }
  std::size_t goals_left = relaxed_.goal_facts().size();
  // Work since the last check: a fact settled counts its consumers and the goals scanned.
  std::size_t work = 0;
  const std::size_t work_per_fact = 1 + relaxed_.goal_facts().size();
  while (!heap_.empty() && goals_left > 0) {
    if (work >= kCheckEvery * 4) {
      if (fired(stop)) return Outcome::kInterrupted;
      work = 0;
    }
    work += work_per_fact;
    std::pop_heap(heap_.begin(), heap_.end(), later);
    const auto [c, f] = heap_.back();
    heap_.pop_back();
    if (c != fact_cost_[f] || settled_[f]) continue;
    settled_[f] = true;
    for (std::uint32_t g : relaxed_.goal_facts()) goals_left -= g == f ? 1 : 0;
    work += relaxed_.consumers(f).size();
    for (std::uint32_t o : relaxed_.consumers(f)) {
      op_cost_[o] =
          combine == Combine::kSum ? op_cost_[o] + c : std::max(op_cost_[o], ops[o].cost + c);
      if (--unsatisfied_[o] == 0) reach(ops[o].effect, op_cost_[o], o);
    }
  }
  const bool reached = std::all_of(relaxed_.goal_facts().begin(), relaxed_.goal_facts().end(),
                                   [&](std::uint32_t g) { return fact_cost_[g] != kInfiniteCost; });
  return reached ? Outcome::kGoalsReached : Outcome::kDeadEnd;
}

}  // namespace sewerplan::search::detail
