// SPDX-License-Identifier: MIT
#include "pipe_key_routes.h"

#include <algorithm>

namespace sewerplan::domain::detail {

PipeKeyRoutes::PipeKeyRoutes(const PositionGraph& graph, std::span<const Node> keys)
    : graph_(graph), keys_(keys) {}

void PipeKeyRoutes::reserve(std::size_t row_nodes) { store_.reserve(2 * row_nodes + 4096); }

PipeKeyRoutes::FirstMoves PipeKeyRoutes::first_moves(Node key) const {
  FirstMoves moves;
  graph_.for_each_successor(key, [&](Node to, Cost cost) { moves.emplace_back(to, cost); });
  return moves;
}

bool PipeKeyRoutes::usable(std::span<const Key> group, bool only_targets_entered) const {
  if (group.size() < 2 || !only_targets_entered) return false;
  const std::optional<PipeId> pipe = graph_.pipe_of(keys_[group.front().index]);
  if (!pipe || !graph_.pipe_drivable(*pipe)) return false;
  std::vector<Node> slots;
  for (const Key& key : group) {
    if (graph_.pipe_of(keys_[key.index]) != pipe) return false;
    for (const auto& [slot, cost] : first_moves(keys_[key.index])) {
      if (cost <= key.bound && std::find(slots.begin(), slots.end(), slot) == slots.end()) {
        slots.push_back(slot);
      }
    }
  }
  return slots.size() < group.size();
}

bool PipeKeyRoutes::search(GraphSearch& search, std::span<const Key> group,
                           std::span<const Node> targets, const std::vector<bool>* goal) {
  store_.clear();
  row_count_ = 0;
  // Each slot within the largest bound a key leaves for it.
  std::vector<std::pair<Node, Cost>> slots;
  for (const Key& key : group) {
    for (const auto& [slot, cost] : first_moves(keys_[key.index])) {
      if (cost > key.bound) continue;
      auto it =
          std::find_if(slots.begin(), slots.end(), [&](const auto& s) { return s.first == slot; });
      if (it == slots.end()) {
        slots.emplace_back(slot, key.bound - cost);
      } else {
        it->second = std::max(it->second, key.bound - cost);
      }
    }
  }
  if (rows_.size() < slots.size()) rows_.resize(slots.size());
  for (const auto& [slot, bound] : slots) {
    SlotRow& row = rows_[row_count_++];
    row.slot = slot;
    row.dist.assign(keys_.size(), kInfiniteCost);
    row.routes.assign(keys_.size(), {});
    row.goal.reset();
    // Without targets or goal a key's own search settles nothing but the key.
    if (targets.empty() && goal == nullptr) continue;
    row.goal = search.run(std::span<const Node>(&slot, 1), targets, bound,
                          GraphSearch::Direction::kForward, goal);
    ++searches_;
    if (search.interrupted()) return false;
    for (std::size_t b = 0; b < keys_.size(); ++b) {
      row.dist[b] = search.distance(keys_[b]);
      if (row.dist[b] != kInfiniteCost) row.routes[b] = store_.keep(search, keys_[b]);
    }
    if (row.goal) {
      row.goal_dist = search.distance(*row.goal);
      row.goal_route = store_.keep(search, *row.goal);
    }
  }
  return true;
}

const PipeKeyRoutes::SlotRow* PipeKeyRoutes::slot_row(Node slot) const {
  for (std::size_t i = 0; i < row_count_; ++i) {
    if (rows_[i].slot == slot) return &rows_[i];
  }
  return nullptr;
}

template <class Value>
std::pair<Cost, const PipeKeyRoutes::SlotRow*> PipeKeyRoutes::cheapest(const FirstMoves& moves,
                                                                       Cost bound, Value&& value,
                                                                       bool& tie) const {
  Cost best = kInfiniteCost;
  const SlotRow* at = nullptr;
  tie = false;
  for (const auto& [slot, cost] : moves) {
    const SlotRow* row = slot_row(slot);
    if (row == nullptr || cost > bound) continue;
    const Cost v = value(*row);
    if (v == kInfiniteCost || v > bound - cost) continue;
    if (cost + v < best) {
      best = cost + v;
      at = row;
      tie = false;
    } else if (cost + v == best) {
      tie = true;
    }
  }
  return {best, at};
}

bool PipeKeyRoutes::row(const Key& key, std::span<Cost> dist, std::span<RouteRef> routes,
                        RouteStore& store, Exit& exit) const {
  const FirstMoves moves = first_moves(keys_[key.index]);
  bool tie = false;
  // Where each entry comes from, all of them before anything is written.
  std::vector<const SlotRow*> from(keys_.size(), nullptr);
  std::vector<Cost> cost(keys_.size(), kInfiniteCost);
  for (std::size_t b = 0; b < keys_.size(); ++b) {
    if (b == key.index) continue;
    std::tie(cost[b], from[b]) = cheapest(
        moves, key.bound, [&](const SlotRow& r) { return r.dist[b]; }, tie);
    if (tie) return false;
  }
  const auto [exit_cost, exit_from] = cheapest(
      moves, key.bound, [](const SlotRow& r) { return r.goal ? r.goal_dist : kInfiniteCost; }, tie);
  if (tie) return false;
  const Node head = keys_[key.index];
  for (std::size_t b = 0; b < keys_.size(); ++b) {
    dist[b] = b == key.index ? 0 : cost[b];
    routes[b] =
        from[b] != nullptr ? store.keep_after(head, store_.route(from[b]->routes[b])) : RouteRef{};
  }
  exit.cost = exit_cost;
  exit.route = exit_from != nullptr ? store.keep_after(head, store_.route(exit_from->goal_route))
                                    : RouteRef{};
  return true;
}

}  // namespace sewerplan::domain::detail
