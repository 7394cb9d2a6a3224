// SPDX-License-Identifier: MIT
#include "graph_search.h"

#include <algorithm>
#include <functional>

namespace sewerplan::domain::detail {

namespace {
constexpr Node kNoParent = 0xffffffffU;
}

bool GraphSearch::grow(SearchScratch& scratch, std::size_t nodes, const StopCondition* stop) {
  constexpr std::size_t kSlice = 16384;  // nodes between two checks: well under 0.1 ms
  if (scratch.dist.size() >= nodes) return true;
  scratch.dist.reserve(nodes);
  scratch.parent.reserve(nodes);
  while (scratch.dist.size() < nodes) {
    if (stop != nullptr && stop->interrupted()) return false;
    const std::size_t size = std::min(nodes, scratch.dist.size() + kSlice);
    scratch.dist.resize(size, kInfiniteCost);
    scratch.parent.resize(size, kNoParent);
    scratch.settled.resize(size, false);
    scratch.is_target.resize(size, false);
  }
  return true;
}

GraphSearch::GraphSearch(const PositionGraph& graph, SearchScratch* scratch)
    : graph_(graph),
      scratch_(scratch != nullptr ? *scratch : own_),
      dist_(scratch_.dist),
      parent_(scratch_.parent),
      settled_(scratch_.settled),
      is_target_(scratch_.is_target),
      touched_(scratch_.touched),
      heap_(scratch_.heap) {
  if (dist_.size() < graph.size()) {
    dist_.resize(graph.size(), kInfiniteCost);
    parent_.resize(graph.size(), kNoParent);
    settled_.resize(graph.size(), false);
    is_target_.resize(graph.size(), false);
  }
}

GraphSearch::~GraphSearch() { reset(); }

void GraphSearch::reset() {
  for (Node n : touched_) {
    dist_[n] = kInfiniteCost;
    parent_[n] = kNoParent;
    settled_[n] = false;
  }
  touched_.clear();
  heap_.clear();
}

template <class Done>
std::optional<Node> GraphSearch::settle(Cost bound, Direction direction, Done&& done) {
  direction_ = direction;
  const auto later = std::greater<std::pair<Cost, Node>>();
  std::make_heap(heap_.begin(), heap_.end(), later);
  auto relax = [&](Node from, Node to, Cost cost) {
    const Cost d = dist_[from] + cost;
    if (d < dist_[to] && d <= bound) {
      if (dist_[to] == kInfiniteCost) touched_.push_back(to);
      dist_[to] = d;
      parent_[to] = from;
      heap_.emplace_back(d, to);
      std::push_heap(heap_.begin(), heap_.end(), later);
    }
  };
  std::optional<Node> stopped_at;
  while (!heap_.empty() && !interrupted_) {
    std::pop_heap(heap_.begin(), heap_.end(), later);
    // Not a structured binding: clang 14 cannot capture one in the lambdas below.
    const Cost d = heap_.back().first;
    const Node n = heap_.back().second;
    heap_.pop_back();
    if (settled_[n] || d != dist_[n]) continue;
    settled_[n] = true;
    ++settled_total_;
    if ((settled_total_ & 255U) == 0 && interrupt_ && interrupt_()) {
      interrupted_ = true;
      break;
    }
    if (done(n)) {
      stopped_at = n;
      break;
    }
    if (direction == Direction::kForward) {
      graph_.for_each_successor(n, [&](Node to, Cost c) { relax(n, to, c); });
    } else {
      graph_.for_each_predecessor(n, [&](Node from, Cost c) { relax(n, from, c); });
    }
  }
  // Nodes reached but not settled may have a distance that is not yet the shortest.
  for (Node n : touched_) {
    if (!settled_[n]) dist_[n] = kInfiniteCost;
  }
  return stopped_at;
}

std::optional<Node> GraphSearch::run(std::span<const Node> sources, std::span<const Node> targets,
                                     Cost bound, Direction direction,
                                     const std::vector<bool>* goal) {
  reset();
  std::size_t targets_left = 0;
  for (Node t : targets) {
    if (!is_target_[t]) ++targets_left;
    is_target_[t] = true;
  }
  for (Node s : sources) {
    if (dist_[s] == 0) continue;
    dist_[s] = 0;
    touched_.push_back(s);
    heap_.emplace_back(0, s);
  }
  std::optional<Node> found;
  if (targets_left > 0 || goal != nullptr) {
    settle(bound, direction, [&](Node n) {
      if (is_target_[n]) --targets_left;
      if (goal != nullptr && !found && (*goal)[n]) found = n;
      return targets_left == 0 && (goal == nullptr || found);
    });
  } else {
    heap_.clear();
  }
  for (Node t : targets) is_target_[t] = false;
  return found;
}

std::optional<Node> GraphSearch::run_to_nearest(Node source, const std::vector<bool>& goal,
                                                Cost bound) {
  reset();
  dist_[source] = 0;
  touched_.push_back(source);
  heap_.emplace_back(0, source);
  return settle(bound, Direction::kForward, [&](Node n) { return goal[n]; });
}

void GraphSearch::path(Node n, std::vector<Node>& out) const {
  out.clear();
  append_path(n, out);
}

void GraphSearch::append_path(Node n, std::vector<Node>& out) const {
  if (dist_[n] == kInfiniteCost) return;
  const std::size_t begin = out.size();
  for (Node at = n; at != kNoParent; at = parent_[at]) out.push_back(at);
  if (direction_ == Direction::kForward) {
    std::reverse(out.begin() + static_cast<std::ptrdiff_t>(begin), out.end());
  }
}

}  // namespace sewerplan::domain::detail
