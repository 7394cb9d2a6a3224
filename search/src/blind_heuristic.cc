// SPDX-License-Identifier: MIT
// The blind heuristic: 0 at every state (heuristic.h).
#include "heuristics.h"

namespace sewerplan::search::detail {
namespace {

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

}  // namespace

std::unique_ptr<Heuristic> make_blind_heuristic() { return std::make_unique<BlindHeuristic>(); }

}  // namespace sewerplan::search::detail
