// SPDX-License-Identifier: MIT
// RelaxedTask and RelaxedExploration: the delete relaxation behind h_max, h_add and FF.
//
// Private to search. RelaxedTask flattens a CompiledTask once into unary operators (one per
// action effect, preconditions as fact indices in one array, CSR), as Fast Downward's
// relaxation_heuristic.h does. RelaxedExploration computes every fact's relaxed cost from a state
// with a Dijkstra-like generalisation (Knuth 1977's grammar problem; Bonet and Geffner's h_add and
// h_max), recording each fact's best supporter, and stops once every goal fact is settled. Its
// buffers are kept between evaluations: no allocation per call.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "sewerplan/core/stop_condition.h"
#include "sewerplan/domain/compiled_task.h"

namespace sewerplan::search::detail {

using domain::ActionId;
using domain::Cost;

struct UnaryOperator {
  std::uint32_t pre_begin;  // into RelaxedTask::preconditions_
  std::uint32_t pre_count;
  std::uint32_t effect;  // fact index
  ActionId action;
  Cost cost;
};

class RelaxedTask {
 public:
  // Nothing is built yet: see build().
  explicit RelaxedTask(const domain::CompiledTask& task) : task_(task) {}
  // Flattens the task, asking `stop` (if not null) every 1,024 actions; returns false if it fired
  // (the next call goes on where this one stopped). True once built; the rest needs it built.
  bool build(const StopCondition* stop);
  const domain::CompiledTask& task() const { return task_; }
  std::size_t fact_count() const { return task_.fact_count(); }
  const std::vector<UnaryOperator>& operators() const { return operators_; }
  std::span<const std::uint32_t> preconditions(const UnaryOperator& op) const {
    return std::span<const std::uint32_t>(preconditions_).subspan(op.pre_begin, op.pre_count);
  }
  // Operators having fact f as a precondition (CSR).
  std::span<const std::uint32_t> consumers(std::uint32_t f) const {
    return std::span<const std::uint32_t>(consumers_)
        .subspan(consumer_begin_[f], consumer_begin_[f + 1] - consumer_begin_[f]);
  }
  const std::vector<std::uint32_t>& goal_facts() const { return goal_facts_; }

 private:
  const domain::CompiledTask& task_;
  std::vector<UnaryOperator> operators_;
  std::vector<std::uint32_t> preconditions_;
  std::vector<std::uint32_t> consumer_begin_;
  std::vector<std::uint32_t> consumers_;
  std::vector<std::uint32_t> goal_facts_;
  std::uint32_t next_action_ = 0;  // the flattening's progress
  bool built_ = false;

  void index_consumers();
};

class RelaxedExploration {
 public:
  enum class Combine { kSum, kMax };
  static constexpr std::uint32_t kNoSupporter = 0xffffffffU;

  explicit RelaxedExploration(const RelaxedTask& relaxed) : relaxed_(relaxed) {}

  enum class Outcome { kGoalsReached, kDeadEnd, kInterrupted };
  // Fills fact costs from `state` (the relaxed task must be built); kDeadEnd if some goal fact is
  // unreachable, kInterrupted if `stop` (if not null) fired first.
  Outcome explore(std::span<const std::int32_t> state, Combine combine,
                  const StopCondition* stop = nullptr);
  Cost fact_cost(std::uint32_t f) const { return fact_cost_[f]; }
  std::uint32_t supporter(std::uint32_t f) const { return supporter_[f]; }

 private:
  const RelaxedTask& relaxed_;
  std::vector<Cost> fact_cost_;
  std::vector<std::uint32_t> supporter_;
  std::vector<bool> settled_;
  std::vector<Cost> op_cost_;
  std::vector<std::uint32_t> unsatisfied_;
  std::vector<std::pair<Cost, std::uint32_t>> heap_;
};

}  // namespace sewerplan::search::detail
