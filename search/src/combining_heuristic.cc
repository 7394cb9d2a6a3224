// SPDX-License-Identifier: MIT
// h_max and h_add (Bonet and Geffner 2001): one class, the combination a parameter.
#include <algorithm>

#include "heuristics.h"

namespace sewerplan::search::detail {
namespace {

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

}  // namespace

std::unique_ptr<Heuristic> make_combining_heuristic(const domain::CompiledTask& task,
                                                    RelaxedExploration::Combine combine) {
  return std::make_unique<CombiningHeuristic>(task, combine);
}

}  // namespace sewerplan::search::detail
