// SPDX-License-Identifier: MIT
// h_max, h_add, FF and blind: the heuristics of heuristic.h.
#include <algorithm>

#include "sewerplan/core/enum_names.h"
#include "sewerplan/search/heuristic.h"

#include "relaxed_task.h"

namespace sewerplan::search {
namespace {

using detail::RelaxedExploration;
using detail::RelaxedTask;

class BlindHeuristic final : public Heuristic {
 public:
  BlindHeuristic() = default;
  Cost evaluate(std::span<const std::int32_t>, std::vector<ActionId>* preferred) override {
    if (preferred != nullptr) preferred->clear();
    return 0;
  }
  bool admissible() const override { return true; }
  std::string_view name() const override { return "blind"; }
};

// h_max and h_add: the cost of the goal facts, combined by max or by sum.
class CombiningHeuristic final : public Heuristic {
 public:
  CombiningHeuristic(const domain::CompiledTask& task, RelaxedExploration::Combine combine)
      : relaxed_(task), exploration_(relaxed_), combine_(combine) {}

  Cost evaluate(std::span<const std::int32_t> state, std::vector<ActionId>* preferred) override {
    if (preferred != nullptr) preferred->clear();
    if (!relaxed_.build(watched())) return kInterrupted;
    if (auto outcome = exploration_.explore(state, combine_, watched());
        outcome != RelaxedExploration::Outcome::kGoalsReached) {
      return outcome == RelaxedExploration::Outcome::kDeadEnd ? kDeadEnd : kInterrupted;
    }
    Cost h = 0;
    for (std::uint32_t g : relaxed_.goal_facts()) {
      h = combine_ == RelaxedExploration::Combine::kSum ? h + exploration_.fact_cost(g)
                                                        : std::max(h, exploration_.fact_cost(g));
    }
    return h;
  }
  bool admissible() const override { return combine_ == RelaxedExploration::Combine::kMax; }
  std::string_view name() const override {
    return combine_ == RelaxedExploration::Combine::kMax ? "max" : "add";
  }

 private:
  RelaxedTask relaxed_;
  RelaxedExploration exploration_;
  RelaxedExploration::Combine combine_;
};

// FF's heuristic: the cost of a relaxed plan made of h_add's best supporters, each action counted
// once; its actions applicable in the state are the helpful ones (Hoffmann and Nebel 2001). Every
// action counts 1 ms more than its cost, so that zero-cost actions still make progress visible.
class FfHeuristic final : public Heuristic {
 public:
  explicit FfHeuristic(const domain::CompiledTask& task)
      : relaxed_(task), exploration_(relaxed_), in_plan_(task.action_count(), false) {}

  Cost evaluate(std::span<const std::int32_t> state, std::vector<ActionId>* preferred) override {
    if (preferred != nullptr) preferred->clear();
    if (!relaxed_.build(watched())) return kInterrupted;
    if (auto outcome = exploration_.explore(state, RelaxedExploration::Combine::kSum, watched());
        outcome != RelaxedExploration::Outcome::kGoalsReached) {
      return outcome == RelaxedExploration::Outcome::kDeadEnd ? kDeadEnd : kInterrupted;
    }
    Cost h = 0;
    relaxed_plan_.clear();
    stack_.assign(relaxed_.goal_facts().begin(), relaxed_.goal_facts().end());
    while (!stack_.empty()) {
      const std::uint32_t f = stack_.back();
      stack_.pop_back();
      const std::uint32_t op = exploration_.supporter(f);
      if (op == RelaxedExploration::kNoSupporter) continue;  // true in the state
      const detail::UnaryOperator& u = relaxed_.operators()[op];
      if (in_plan_[u.action.index()]) continue;
      in_plan_[u.action.index()] = true;
      relaxed_plan_.push_back(u.action);
      h += u.cost + 1;
      for (std::uint32_t p : relaxed_.preconditions(u)) stack_.push_back(p);
    }
    for (ActionId a : relaxed_plan_) {
      in_plan_[a.index()] = false;
      if (preferred != nullptr && relaxed_.task().is_applicable(a, state)) preferred->push_back(a);
    }
    if (preferred != nullptr) std::sort(preferred->begin(), preferred->end());
    return h;
  }
  bool admissible() const override { return false; }
  std::string_view name() const override { return "ff"; }

 private:
  RelaxedTask relaxed_;
  RelaxedExploration exploration_;
  std::vector<bool> in_plan_;
  std::vector<ActionId> relaxed_plan_;
  std::vector<std::uint32_t> stack_;
};

// sewerplan::detail in full: search::detail (relaxed_task.h) hides it here.
constexpr sewerplan::detail::EnumNames<HeuristicKind, 4> kHeuristicKinds{{
    {HeuristicKind::kFf, "ff"},
    {HeuristicKind::kAdd, "add"},
    {HeuristicKind::kMax, "max"},
    {HeuristicKind::kBlind, "blind"},
}};
static_assert(sewerplan::detail::distinct(kHeuristicKinds));

}  // namespace

std::string_view to_string(HeuristicKind kind) {
  return sewerplan::detail::name_of(kHeuristicKinds, kind);
}

std::optional<HeuristicKind> heuristic_from_string(std::string_view name) {
  return sewerplan::detail::value_of(kHeuristicKinds, name);
}

std::unique_ptr<Heuristic> make_heuristic(HeuristicKind kind, const domain::CompiledTask& task) {
  switch (kind) {
    case HeuristicKind::kFf:
      return std::make_unique<FfHeuristic>(task);
    case HeuristicKind::kAdd:
      return std::make_unique<CombiningHeuristic>(task, RelaxedExploration::Combine::kSum);
    case HeuristicKind::kMax:
      return std::make_unique<CombiningHeuristic>(task, RelaxedExploration::Combine::kMax);
    case HeuristicKind::kBlind:
      return std::make_unique<BlindHeuristic>();
  }
  return nullptr;
}

}  // namespace sewerplan::search
