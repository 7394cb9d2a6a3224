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
  if (scratch.settled.size() >= nodes) return true;
  // Distances and parents grow without being written (zeroed_array.h); the bits in slices.
  scratch.dist_left.grow_clean(nodes);
  scratch.parent_plus_one.grow_clean(nodes);
  while (scratch.settled.size() < nodes) {
    if (stop != nullptr && stop->interrupted()) return false;
    const std::size_t size = std::min(nodes, scratch.settled.size() + kSlice);
    scratch.settled.resize(size, false);
    scratch.is_target.resize(size, false);
    scratch.tied.resize(size, false);
  }
  return true;
}

GraphSearch::GraphSearch(const PositionGraph& graph, SearchScratch* scratch)
    : graph_(graph),
      scratch_(scratch != nullptr ? *scratch : own_),
      dist_left_(scratch_.dist_left),
      parent_plus_one_(scratch_.parent_plus_one),
      settled_(scratch_.settled),
      is_target_(scratch_.is_target),
      tied_(scratch_.tied),
      touched_(scratch_.touched),
      heap_(scratch_.heap) {
  if (settled_.size() < graph.size()) {
    dist_left_.grow_clean(graph.size());
    parent_plus_one_.grow_clean(graph.size());
    settled_.resize(graph.size(), false);
    is_target_.resize(graph.size(), false);
    tied_.resize(graph.size(), false);
  }
}

GraphSearch::~GraphSearch() { reset(); }

void GraphSearch::reset() {
  joined_ = std::nullopt;
  for (Node n : touched_) {
    set_distance(n, kInfiniteCost);
    set_parent(n, kNoParent);
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
    const Cost d = distance(from) + cost;
    const Cost old = distance(to);
    if (d < old && d <= bound) {
      if (old == kInfiniteCost) touched_.push_back(to);
      set_distance(to, d);
      set_parent(to, from);
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
    if (settled_[n] || d != distance(n)) continue;
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
  forget_unsettled();
  return stopped_at;
}

void GraphSearch::forget_unsettled() {
  // Nodes reached but not settled may have a distance that is not yet the shortest.
  for (Node n : touched_) {
    if (!settled_[n]) set_distance(n, kInfiniteCost);
  }
}

GraphSearch::Toward GraphSearch::run_toward(Node source, Node target, Cost bound,
                                            std::size_t settle_limit,
                                            const std::function<Cost(Node)>& to_target,
                                            const std::function<bool(Node)>* rest_known) {
  reset();
  direction_ = Direction::kForward;
  const Cost guide = to_target(source);
  if (guide == kInfiniteCost || guide > bound) return Toward::kUnreached;
  set_distance(source, 0);
  touched_.push_back(source);
  // Ordered by distance plus guide; a node's guide does not change, so the first entry of a node
  // that leaves the heap is its best.
  const auto later = std::greater<std::pair<Cost, Node>>();
  heap_.emplace_back(guide, source);
  Cost found = kInfiniteCost;
  std::size_t settled = 0;
  std::size_t next_ask = 1;
  while (!heap_.empty() && !interrupted_) {
    std::pop_heap(heap_.begin(), heap_.end(), later);
    const Cost f = heap_.back().first;
    const Node n = heap_.back().second;
    heap_.pop_back();
    // Every node that could lie on a shortest way to the target has an estimate no greater than
    // its distance (the guide is a lower bound): all are settled once the estimates pass it.
    if (f > found) break;
    if (settled_[n]) continue;
    settled_[n] = true;
    ++settled_total_;
    if ((settled_total_ & 255U) == 0 && interrupt_ && interrupt_()) {
      interrupted_ = true;
      break;
    }
    if (++settled > settle_limit) {
      heap_.clear();
      for (Node t : touched_) {
        set_distance(t, kInfiniteCost);
        tied_[t] = false;
      }
      return Toward::kGaveUp;
    }
    if (n == target) found = distance(n);
    // The rest known: while the target is not settled, every way to it not through n leaves the
    // settled nodes at a node in the heap, whose estimate is a lower bound of it, so costs more
    // than f; the way here is the only shortest one (no later node can tie a settled node of it:
    // it would have an estimate of at most f); and the rest is the only shortest way from n in
    // the graph without closures and a way of this one, at the guide's cost: the way through n
    // is the only shortest. (Once the target is settled, its own way lies among the settled
    // nodes, and a node at its estimate may tie it: a review found a slot reached at once from a
    // passage and, at no cost, from its pipe's end.)
    if (rest_known != nullptr && found == kInfiniteCost && n != target && settled == next_ask) {
      next_ask *= 2;  // a refusal costs up to the rest's length: asked at 1, 2, 4, ... settled
      if ((heap_.empty() || heap_.front().first > f) && only_shortest_way(n) && (*rest_known)(n)) {
        joined_ = n;
        heap_.clear();
        forget_unsettled();
        for (Node t : touched_) tied_[t] = false;
        return Toward::kUnique;
      }
    }
    graph_.for_each_successor(n, [&](Node to, Cost c) {
      const Cost d = distance(n) + c;
      if (d > bound || d > distance(to)) return;
      if (d == distance(to)) {
        tied_[to] = true;  // a second settled node reaches it at its distance
        return;
      }
      const Cost rest = to_target(to);
      if (rest == kInfiniteCost || d + rest > bound) return;
      if (distance(to) == kInfiniteCost) touched_.push_back(to);
      set_distance(to, d);
      set_parent(to, n);
      tied_[to] = false;
      heap_.emplace_back(d + rest, to);
      std::push_heap(heap_.begin(), heap_.end(), later);
    });
  }
  heap_.clear();
  forget_unsettled();
  const bool unique = found != kInfiniteCost && only_shortest_way(target);
  for (Node t : touched_) tied_[t] = false;
  if (interrupted_) return Toward::kGaveUp;
  if (found == kInfiniteCost) return Toward::kUnreached;
  return unique ? Toward::kUnique : Toward::kTied;
}

bool GraphSearch::only_shortest_way(Node target) const {
  for (Node v = target; parent(v) != kNoParent; v = parent(v)) {
    if (tied_[v]) return false;
  }
  return true;
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
    if (distance(s) == 0) continue;
    set_distance(s, 0);
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
  set_distance(source, 0);
  touched_.push_back(source);
  heap_.emplace_back(0, source);
  return settle(bound, Direction::kForward, [&](Node n) { return goal[n]; });
}

void GraphSearch::path(Node n, std::vector<Node>& out) const {
  out.clear();
  append_path(n, out);
}

void GraphSearch::append_path(Node n, std::vector<Node>& out) const {
  if (distance(n) == kInfiniteCost) return;
  const std::size_t begin = out.size();
  for (Node at = n; at != kNoParent; at = parent(at)) out.push_back(at);
  if (direction_ == Direction::kForward) {
    std::reverse(out.begin() + static_cast<std::ptrdiff_t>(begin), out.end());
  }
}

}  // namespace sewerplan::domain::detail
