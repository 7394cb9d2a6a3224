// SPDX-License-Identifier: MIT
// The costs of one order of goals, kept per option of each goal, so that the tour search prices a
// trial order that differs from it in one goal or one stretch without rerunning the dynamic
// programme over the whole order (issue 16: cheapest insertion and local search over 50 goals
// reran it for every trial, 16 times the time of the shortest paths they need on 1,000 manholes).
//
// For an order F of m goals, head(k) holds, per option of F[k-1], the cheapest cost of doing
// F[0..k) ending with that option (head(0): at the start), and tail(k), per option of F[k], the
// cheapest cost of doing the rest of the order (and reaching the end position) after that option.
// A trial order joins a head and a tail with the few goals it changes in between: inserting a goal
// costs O(options^2), moving goal i to every other place costs O(m x options^2) in all (forward
// from the heads for the places after i, backward from the tails for those before), reversing a
// stretch costs its length. Every figure is exactly what Evaluator::cost in tour_search.cc gives
// for the trial order: the same sums and minima, taken in another order.
#pragma once

#include <cstddef>
#include <vector>

#include "tour_shape.h"

namespace sewerplan::search::detail {

class OrderCosts {
 public:
  explicit OrderCosts(const Shape& shape) : s_(shape) {}

  // Reads the order `full` (goal indices, the last-goal included where there is one).
  void prepare(const std::vector<std::size_t>& full);
  // The cost of the prepared order (kInfiniteCost: impossible).
  Cost total() const { return join(heads_.back(), {}); }
  // The cost of the prepared order with goal g inserted before position `at` (0..m).
  Cost inserted(std::size_t at, std::size_t g);
  // For each j in [0, places) but i, the cost of the prepared order with its goal i taken out and
  // put back at position j of the order without it: out[j] (out[i] is kInfiniteCost).
  void moved(std::size_t i, std::size_t places, std::vector<Cost>& out);
  // The cost of the prepared order with the stretch [i, j) reversed.
  Cost reversed(std::size_t i, std::size_t j);

 private:
  static constexpr std::size_t kStart = static_cast<std::size_t>(-1);

  // Costs per option of `goal` after doing it (goal kStart: one entry, at the start).
  struct Front {
    std::size_t goal = kStart;
    std::vector<Cost> cost;
  };
  // Costs per option of `goal` of all that follows it (goal kStart: nothing follows but the end).
  struct Rest {
    std::size_t goal = kStart;
    const Cost* cost = nullptr;
  };

  std::int32_t place(std::size_t goal, std::size_t option) const;
  // Buffers are reused: the searches call these some K^3 times and allocated on every call.
  void advance(const Front& from, std::size_t goal, Front& to) const;
  // The cheapest cost from `at` to do what `rest` holds, and end.
  Cost rest(std::int32_t at, Rest rest) const;
  void prepend(std::size_t goal, Rest rest, std::vector<Cost>& to) const;
  Cost join(const Front& front, Rest rest) const;
  Rest rest_at(std::size_t k) const;  // order[k..], tail(k)

  const Shape& s_;
  std::vector<std::size_t> order_;
  std::vector<Front> heads_;              // heads_[k]: after order_[0..k)
  std::vector<std::vector<Cost>> tails_;  // tails_[k]: per option of order_[k]
  Front front_, next_, trial_;            // scratch
  std::vector<Cost> back_[2];             // scratch
};

}  // namespace sewerplan::search::detail
