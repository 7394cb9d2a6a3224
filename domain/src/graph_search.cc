// SPDX-License-Identifier: MIT
#include "graph_search.h"

#include <algorithm>

namespace sewerplan::domain::detail {

namespace {
constexpr Node kNoParent = 0xffffffffU;
constexpr std::size_t kArity = 4;
}  // namespace

bool GraphSearch::grow(SearchScratch& scratch, std::size_t nodes, const StopCondition* stop) {
  if (stop != nullptr && stop->interrupted()) return false;
  scratch.nodes.grow_clean(nodes);
  return true;
}

GraphSearch::GraphSearch(const PositionGraph& graph, SearchScratch* scratch)
    : graph_(graph),
      scratch_(scratch != nullptr ? *scratch : own_),
      nodes_(scratch_.nodes),
      touched_(scratch_.touched),
      heap_(scratch_.heap) {
  nodes_.grow_clean(graph.size());
}

GraphSearch::~GraphSearch() { reset(); }

void GraphSearch::reset() {
  for (Node n : touched_) nodes_[n] = SearchEntry{};
  touched_.clear();
  heap_.clear();
}

// A 4-ary heap: half the levels of a binary one, and a node's children side by side in one cache
// line; the pops come in the order of (distance, node) as from any exact priority queue.
void GraphSearch::push(Cost d, Node n) {
  const std::pair<Cost, Node> entry(d, n);
  std::size_t i = heap_.size();
  heap_.push_back(entry);
  while (i > 0) {
    const std::size_t up = (i - 1) / kArity;
    if (!(entry < heap_[up])) break;
    heap_[i] = heap_[up];
    i = up;
  }
  heap_[i] = entry;
}

std::pair<Cost, Node> GraphSearch::pop() {
  const std::pair<Cost, Node> top = heap_.front();
  const std::pair<Cost, Node> last = heap_.back();
  heap_.pop_back();
  const std::size_t size = heap_.size();
  if (size == 0) return top;
  std::size_t i = 0;
  for (;;) {
    const std::size_t first = kArity * i + 1;
    if (first >= size) break;
    const std::size_t end = std::min(first + kArity, size);
    std::size_t least = first;
    for (std::size_t c = first + 1; c < end; ++c) {
      if (heap_[c] < heap_[least]) least = c;
    }
    if (!(heap_[least] < last)) break;
    heap_[i] = heap_[least];
    i = least;
  }
  heap_[i] = last;
  return top;
}

template <class Done>
std::optional<Node> GraphSearch::settle(Cost bound, Direction direction, Done&& done) {
  direction_ = direction;
  std::optional<Node> stopped_at;
  while (!heap_.empty() && !interrupted_) {
    // Not a structured binding: clang 14 cannot capture one in the lambdas below.
    const std::pair<Cost, Node> top = pop();
    const Cost d = top.first;
    const Node n = top.second;
    SearchEntry& entry = nodes_[n];
    if ((entry.flags & SearchEntry::kSettled) != 0 || d != kInfiniteCost - entry.dist_left) {
      continue;
    }
    entry.flags |= SearchEntry::kSettled;
    ++settled_total_;
    if ((settled_total_ & 255U) == 0 && interrupt_ && interrupt_()) {
      interrupted_ = true;
      break;
    }
    if (done(n)) {
      stopped_at = n;
      break;
    }
    // The first node settled at a node's distance stays its parent: only a shorter way replaces
    // it.
    auto relax = [&](Node to, Cost cost) {
      const Cost reached = d + cost;
      SearchEntry& next = nodes_[to];
      const Cost old = kInfiniteCost - next.dist_left;
      if (reached < old && reached <= bound) {
        if (old == kInfiniteCost) touched_.push_back(to);
        next.dist_left = kInfiniteCost - reached;
        next.parent_plus_one = n + 1U;
        push(reached, to);
      }
    };
    if (direction == Direction::kForward) {
      graph_.for_each_successor(n, relax);
    } else {
      graph_.for_each_predecessor(n, relax);
    }
  }
  // Nodes reached but not settled may have a distance that is not yet the shortest: distance()
  // gives them none (with no pass over the touched nodes to clear them).
  return stopped_at;
}

std::optional<Node> GraphSearch::run(std::span<const Node> sources, std::span<const Node> targets,
                                     Cost bound, Direction direction,
                                     const std::vector<bool>* goal) {
  reset();
  std::size_t targets_left = 0;
  for (Node t : targets) {
    if (!is_target(t)) ++targets_left;
    nodes_[t].flags |= SearchEntry::kTarget;
  }
  for (Node s : sources) {
    if (tentative(s) == 0) continue;
    set_distance(s, 0);
    touched_.push_back(s);
    push(0, s);
  }
  std::optional<Node> found;
  if (targets_left > 0 || goal != nullptr) {
    settle(bound, direction, [&](Node n) {
      if (is_target(n)) --targets_left;
      if (goal != nullptr && !found && (*goal)[n]) found = n;
      return targets_left == 0 && (goal == nullptr || found);
    });
  } else {
    // Nothing to settle beyond the sources themselves, at distance 0.
    heap_.clear();
    for (Node s : sources) nodes_[s].flags |= SearchEntry::kSettled;
  }
  for (Node t : targets) nodes_[t].flags &= ~SearchEntry::kTarget;
  return found;
}

std::optional<Node> GraphSearch::run_to_nearest(Node source, const std::vector<bool>& goal,
                                                Cost bound) {
  reset();
  set_distance(source, 0);
  touched_.push_back(source);
  push(0, source);
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
