// SPDX-License-Identifier: MIT
#include "sewerplan/search/best_first_search.h"

#include <algorithm>
#include <cmath>

namespace sewerplan::search {

using domain::StateId;

namespace {
// Entries compare so that the heap's top is the smallest (f, h, order).
bool later(const auto& a, const auto& b) {
  if (a.f != b.f) return a.f > b.f;
  if (a.h != b.h) return a.h > b.h;
  return a.order > b.order;
}
}  // namespace

BestFirstSearch::BestFirstSearch(const domain::CompiledTask& task, Heuristic& heuristic,
                                 Ordering ordering, Cost cost_bound)
    : task_(task),
      heuristic_(heuristic),
      ordering_(ordering),
      bound_(task.penalty_unit() > 0 ? cost_bound : std::min(cost_bound, task.cost_bound())),
      registry_(task) {}

std::string_view BestFirstSearch::name() const {
  if (ordering_.g_weight == 0) return "greedy best-first search";
  return ordering_.h_weight == 1 ? "A*" : "weighted A*";
}

Cost BestFirstSearch::f_value(Cost g, Cost h) const {
  return static_cast<Cost>(std::llround(ordering_.g_weight * static_cast<double>(g) +
                                        ordering_.h_weight * static_cast<double>(h)));
}

void BestFirstSearch::open(StateId id, const NodeInfo& info) {
  info_[id.index()] = info;
  info_[id.index()].status = Status::kOpen;
  heap_.push_back({f_value(info.g, info.h), info.h, order_++, info.g, id});
  std::push_heap(heap_.begin(), heap_.end(),
                 [](const Entry& a, const Entry& b) { return later(a, b); });
}

void BestFirstSearch::watch(const StopCondition* stop) {
  SearchEngine::watch(stop);
  heuristic_.watch(stop);
}

std::optional<SearchStatus> BestFirstSearch::initialize() {
  result_ = SearchResult{};
  const auto [id, added] = registry_.insert(task_.initial_state());
  info_.resize(registry_.size());
  if (task_.is_goal(task_.initial_state())) {
    // The empty plan, with nothing to evaluate (a step() would expand it and find the same).
    ++result_.statistics.generated;
    open(id, {0, 0, id, ActionId{0}, Status::kNew});
    update_memory();
    result_.status = SearchStatus::kSolved;
    return result_.status;
  }
  const Cost h = heuristic_.evaluate(task_.initial_state(), nullptr);
  if (h == Heuristic::kInterrupted) return std::nullopt;  // search() reports the stop
  ++result_.statistics.evaluated;
  ++result_.statistics.generated;
  if (h == Heuristic::kDeadEnd) {
    info_[id.index()].status = Status::kDeadEnd;
    ++result_.statistics.dead_ends;
    update_memory();
    result_.status = SearchStatus::kUnsolvable;
    return result_.status;
  }
  open(id, {0, h, id, ActionId{0}, Status::kNew});
  update_memory();
  return std::nullopt;
}

std::optional<SearchStatus> BestFirstSearch::step() {
  const auto cmp = [](const Entry& a, const Entry& b) { return later(a, b); };
  if (heap_.empty()) {
    result_.status = SearchStatus::kUnsolvable;
    return result_.status;
  }
  std::pop_heap(heap_.begin(), heap_.end(), cmp);
  const Entry entry = heap_.back();
  heap_.pop_back();
  NodeInfo& node = info_[entry.state.index()];
  if (node.status != Status::kOpen || entry.g != node.g) return std::nullopt;  // stale entry
  node.status = Status::kClosed;
  ++result_.statistics.expanded;
  registry_.unpack(entry.state, values_);
  if (task_.is_goal(values_)) {
    trace_plan(entry.state);
    result_.status = SearchStatus::kSolved;
    return result_.status;
  }
  const Cost g = node.g;
  const bool admissible = heuristic_.admissible();
  task_.applicable_actions(values_, applicable_);
  for (ActionId a : applicable_) {
    if (interrupted()) return std::nullopt;  // search() reports the stop
    const Cost succ_g = g + task_.cost(a);
    if (succ_g > bound_ || task_.exceeds_bound_before(g, a)) {
      ++result_.statistics.dead_ends;
      continue;
    }
    successor_ = values_;
    task_.apply(a, successor_);
    const auto [id, added] = registry_.insert(successor_);
    ++result_.statistics.generated;
    if (added) {
      info_.resize(registry_.size());
      const Cost h = heuristic_.evaluate(successor_, nullptr);
      if (h == Heuristic::kInterrupted) return std::nullopt;  // search() reports the stop
      ++result_.statistics.evaluated;
      if (h == Heuristic::kDeadEnd) {
        info_[id.index()].status = Status::kDeadEnd;
        ++result_.statistics.dead_ends;
        continue;
      }
      info_[id.index()] = {succ_g, h, entry.state, a, Status::kNew};
      if (admissible && succ_g + h > bound_) continue;
      open(id, info_[id.index()]);
      continue;
    }
    NodeInfo& succ = info_[id.index()];
    if (succ.status == Status::kDeadEnd || succ_g >= succ.g) continue;
    if (succ.status == Status::kClosed) ++result_.statistics.reopened;
    if (admissible && succ_g + succ.h > bound_) continue;
    open(id, {succ_g, succ.h, entry.state, a, Status::kNew});
  }
  update_memory();
  return std::nullopt;
}

void BestFirstSearch::trace_plan(StateId goal) {
  result_.plan.clear();
  result_.cost = info_[goal.index()].g;
  for (StateId s = goal; info_[s.index()].parent != s; s = info_[s.index()].parent) {
    result_.plan.push_back(info_[s.index()].action);
  }
  std::reverse(result_.plan.begin(), result_.plan.end());
}

void BestFirstSearch::update_memory() {
  const std::size_t bytes = registry_.memory_bytes() + info_.capacity() * sizeof(NodeInfo) +
                            heap_.capacity() * sizeof(Entry);
  result_.statistics.peak_memory_bytes = std::max(result_.statistics.peak_memory_bytes, bytes);
  result_.statistics.stored = registry_.size();
}

}  // namespace sewerplan::search
