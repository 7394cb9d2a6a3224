// SPDX-License-Identifier: MIT
#include "tour_costs.h"

#include <algorithm>

namespace sewerplan::search::detail {

std::int32_t OrderCosts::place(std::size_t goal, std::size_t option) const {
  if (goal == kStart) return s_.start;
  const Option& o = s_.goals[goal].options[option];
  return o.to == kStays ? o.at : o.to;
}

OrderCosts::Front OrderCosts::advance(const Front& from, std::size_t goal) const {
  const std::vector<Option>& options = s_.goals[goal].options;
  Front to{goal, std::vector<Cost>(options.size(), kInfiniteCost)};
  for (std::size_t a = 0; a < from.cost.size(); ++a) {
    if (from.cost[a] >= kInfiniteCost) continue;
    const std::int32_t at = place(from.goal, a);
    for (std::size_t b = 0; b < options.size(); ++b) {
      const Cost d = s_.move_cost(at, options[b].at);
      if (d >= kInfiniteCost) continue;
      to.cost[b] = std::min(to.cost[b], from.cost[a] + d + options[b].cost);
    }
  }
  return to;
}

Cost OrderCosts::rest(std::int32_t at, const Back& back) const {
  if (back.goal == kStart) return s_.end ? s_.move_cost(at, *s_.end) : 0;
  const std::vector<Option>& options = s_.goals[back.goal].options;
  Cost best = kInfiniteCost;
  for (std::size_t c = 0; c < options.size(); ++c) {
    if (back.cost[c] >= kInfiniteCost) continue;
    const Cost d = s_.move_cost(at, options[c].at);
    if (d >= kInfiniteCost) continue;
    best = std::min(best, d + options[c].cost + back.cost[c]);
  }
  return best;
}

OrderCosts::Back OrderCosts::prepend(std::size_t goal, const Back& back) const {
  const std::size_t n = s_.goals[goal].options.size();
  Back to{goal, std::vector<Cost>(n)};
  for (std::size_t d = 0; d < n; ++d) to.cost[d] = rest(place(goal, d), back);
  return to;
}

Cost OrderCosts::join(const Front& front, const Back& back) const {
  Cost best = kInfiniteCost;
  for (std::size_t a = 0; a < front.cost.size(); ++a) {
    if (front.cost[a] >= kInfiniteCost) continue;
    const Cost r = rest(place(front.goal, a), back);
    if (r < kInfiniteCost) best = std::min(best, front.cost[a] + r);
  }
  return best;
}

OrderCosts::Back OrderCosts::back_at(std::size_t k) const {
  if (k == order_.size()) return {};
  return {order_[k], tails_[k]};
}

void OrderCosts::prepare(const std::vector<std::size_t>& full) {
  order_ = full;
  const std::size_t m = order_.size();
  heads_.resize(m + 1);
  heads_[0] = Front{kStart, {0}};
  for (std::size_t k = 0; k < m; ++k) heads_[k + 1] = advance(heads_[k], order_[k]);
  tails_.resize(m);
  for (std::size_t k = m; k > 0; --k) tails_[k - 1] = prepend(order_[k - 1], back_at(k)).cost;
}

Cost OrderCosts::inserted(std::size_t at, std::size_t g) const {
  return join(advance(heads_[at], g), back_at(at));
}

void OrderCosts::moved(std::size_t i, std::size_t places, std::vector<Cost>& out) const {
  out.assign(places, kInfiniteCost);
  const std::size_t g = order_[i];
  // After i: the goals between slide forward, g follows them.
  Front front = heads_[i];
  for (std::size_t j = i + 1; j < places; ++j) {
    front = advance(front, order_[j]);
    out[j] = join(advance(front, g), back_at(j + 1));
  }
  // Before i: g goes first, the goals between slide back.
  Back back = back_at(i + 1);
  for (std::size_t j = i; j > 0; --j) {
    back = prepend(order_[j - 1], back);
    out[j - 1] = join(advance(heads_[j - 1], g), back);
  }
}

Cost OrderCosts::reversed(std::size_t i, std::size_t j) const {
  Front front = heads_[i];
  for (std::size_t t = j; t > i; --t) front = advance(front, order_[t - 1]);
  return join(front, back_at(j));
}

}  // namespace sewerplan::search::detail
