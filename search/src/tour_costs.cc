// SPDX-License-Identifier: MIT
#include "tour_costs.h"

#include <algorithm>
#include <utility>

namespace sewerplan::search::detail {

std::int32_t OrderCosts::place(std::size_t goal, std::size_t option) const {
  if (goal == kStart) return s_.start;
  const Option& o = s_.goals[goal].options[option];
  return o.to == kStays ? o.at : o.to;
}

void OrderCosts::advance(const Front& from, std::size_t goal, Front& to) const {
  const std::vector<Option>& options = s_.goals[goal].options;
  to.goal = goal;
  to.cost.assign(options.size(), kInfiniteCost);
  for (std::size_t a = 0; a < from.cost.size(); ++a) {
    if (from.cost[a] >= kInfiniteCost) continue;
    const std::int32_t at = place(from.goal, a);
    for (std::size_t b = 0; b < options.size(); ++b) {
      const Cost d = s_.move_cost(at, options[b].at);
      if (d >= kInfiniteCost) continue;
      to.cost[b] = std::min(to.cost[b], from.cost[a] + d + options[b].cost);
    }
  }
}

Cost OrderCosts::rest(std::int32_t at, Rest rest) const {
  if (rest.goal == kStart) return s_.end ? s_.move_cost(at, *s_.end) : 0;
  const std::vector<Option>& options = s_.goals[rest.goal].options;
  Cost best = kInfiniteCost;
  for (std::size_t c = 0; c < options.size(); ++c) {
    if (rest.cost[c] >= kInfiniteCost) continue;
    const Cost d = s_.move_cost(at, options[c].at);
    if (d >= kInfiniteCost) continue;
    best = std::min(best, d + options[c].cost + rest.cost[c]);
  }
  return best;
}

void OrderCosts::prepend(std::size_t goal, Rest rest, std::vector<Cost>& to) const {
  const std::size_t n = s_.goals[goal].options.size();
  to.resize(n);
  for (std::size_t d = 0; d < n; ++d) to[d] = this->rest(place(goal, d), rest);
}

Cost OrderCosts::join(const Front& front, Rest rest) const {
  Cost best = kInfiniteCost;
  for (std::size_t a = 0; a < front.cost.size(); ++a) {
    if (front.cost[a] >= kInfiniteCost) continue;
    const Cost r = this->rest(place(front.goal, a), rest);
    if (r < kInfiniteCost) best = std::min(best, front.cost[a] + r);
  }
  return best;
}

OrderCosts::Rest OrderCosts::rest_at(std::size_t k) const {
  if (k == order_.size()) return {};
  return {order_[k], tails_[k].data()};
}

void OrderCosts::prepare(const std::vector<std::size_t>& full) {
  order_ = full;
  const std::size_t m = order_.size();
  heads_.resize(m + 1);
  heads_[0].goal = kStart;
  heads_[0].cost.assign(1, 0);
  for (std::size_t k = 0; k < m; ++k) advance(heads_[k], order_[k], heads_[k + 1]);
  tails_.resize(m);
  for (std::size_t k = m; k > 0; --k) prepend(order_[k - 1], rest_at(k), tails_[k - 1]);
}

Cost OrderCosts::inserted(std::size_t at, std::size_t g) {
  advance(heads_[at], g, trial_);
  return join(trial_, rest_at(at));
}

void OrderCosts::moved(std::size_t i, std::size_t places, std::vector<Cost>& out) {
  out.assign(places, kInfiniteCost);
  const std::size_t g = order_[i];
  // After i: the goals between slide forward, g follows them.
  front_ = heads_[i];
  for (std::size_t j = i + 1; j < places; ++j) {
    advance(front_, order_[j], next_);
    std::swap(front_, next_);
    advance(front_, g, trial_);
    out[j] = join(trial_, rest_at(j + 1));
  }
  // Before i: g goes first, the goals between slide back.
  Rest back = rest_at(i + 1);
  for (std::size_t j = i, k = 0; j > 0; --j, k ^= 1U) {
    prepend(order_[j - 1], back, back_[k]);
    back = {order_[j - 1], back_[k].data()};
    advance(heads_[j - 1], g, trial_);
    out[j - 1] = join(trial_, back);
  }
}

Cost OrderCosts::reversed(std::size_t i, std::size_t j) {
  front_ = heads_[i];
  for (std::size_t t = j; t > i; --t) {
    advance(front_, order_[t - 1], next_);
    std::swap(front_, next_);
  }
  return join(front_, rest_at(j));
}

}  // namespace sewerplan::search::detail
