// SPDX-License-Identifier: MIT
// FF's relaxed-plan heuristic and its helpful actions (Hoffmann and Nebel 2001).
#include <algorithm>

#include "heuristics.h"

namespace sewerplan::search::detail {
namespace {

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
      const UnaryOperator& u = relaxed_.operators()[op];
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

}  // namespace

std::unique_ptr<Heuristic> make_ff_heuristic(const domain::CompiledTask& task) {
  return std::make_unique<FfHeuristic>(task);
}

}  // namespace sewerplan::search::detail
