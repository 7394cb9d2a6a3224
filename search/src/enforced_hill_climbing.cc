// SPDX-License-Identifier: MIT
#include "sewerplan/search/enforced_hill_climbing.h"

#include <algorithm>

namespace sewerplan::search {

using domain::StateId;

EnforcedHillClimbing::EnforcedHillClimbing(const domain::CompiledTask& task, Heuristic& heuristic)
    : task_(task), heuristic_(heuristic), registry_(task) {}

EnforcedHillClimbing::Visit& EnforcedHillClimbing::visit(StateId id) {
  visits_.grow_to(registry_.size());
  return visits_[id.index()];
}

void EnforcedHillClimbing::watch(const StopCondition* stop) {
  SearchEngine::watch(stop);
  heuristic_.watch(stop);
  if (fallback_) fallback_->watch(stop);
}

std::optional<SearchStatus> EnforcedHillClimbing::initialize() {
  result_ = SearchResult{};
  fallback_.reset();
  plan_.clear();
  const auto [id, added] = registry_.insert(task_.initial_state());
  current_g_ = 0;
  if (task_.is_goal(task_.initial_state())) {
    // The empty plan, with nothing to evaluate (a step() would find the same).
    ++result_.statistics.generated;
    restart_from(id, 0, {});
    result_.status = SearchStatus::kSolved;
    result_.statistics.stored = registry_.size();
    return result_.status;
  }
  std::vector<ActionId> helpful;
  const Cost h = heuristic_.evaluate(task_.initial_state(), &helpful);
  if (h == Heuristic::kInterrupted) return std::nullopt;  // search() reports the stop
  ++result_.statistics.evaluated;
  ++result_.statistics.generated;
  if (h == Heuristic::kDeadEnd) {
    ++result_.statistics.dead_ends;
    result_.status = SearchStatus::kUnsolvable;
    result_.statistics.stored = registry_.size();
    queue_.clear();
    current_ = id;
    current_h_ = h;
    return result_.status;
  }
  restart_from(id, h, std::move(helpful));
  return std::nullopt;
}

void EnforcedHillClimbing::restart_from(StateId state, Cost h, std::vector<ActionId> helpful) {
  current_ = state;
  current_h_ = h;
  ++iteration_;
  queue_.clear();
  Visit& v = visit(state);
  v = {iteration_, state, ActionId{0}, 0, std::move(helpful)};
  queue_.push_back(state);
}

void EnforcedHillClimbing::commit(StateId reached) {
  std::vector<ActionId> path;
  for (StateId s = reached; s != current_; s = visits_[s.index()].parent) {
    path.push_back(visits_[s.index()].action);
  }
  plan_.insert(plan_.end(), path.rbegin(), path.rend());
  current_g_ += visits_[reached.index()].g;
}

std::optional<SearchStatus> EnforcedHillClimbing::step() {
  if (fallback_) return fallback_->step();
  if (current_h_ == Heuristic::kDeadEnd) return SearchStatus::kUnsolvable;
  registry_.unpack(current_, values_);
  if (task_.is_goal(values_)) {
    result_.status = SearchStatus::kSolved;
    result_.plan = plan_;
    result_.cost = current_g_;
    return result_.status;
  }
  if (queue_.empty()) {  // enforced hill-climbing failed: FF falls back to best-first search
    fallback_ = std::make_unique<BestFirstSearch>(task_, heuristic_, BestFirstSearch::greedy());
    fallback_->watch(watched());
    return fallback_->initialize();
  }
  const StateId s = queue_.front();
  queue_.pop_front();
  ++result_.statistics.expanded;
  result_.statistics.stored = registry_.size();
  result_.statistics.peak_memory_bytes =
      std::max(result_.statistics.peak_memory_bytes, registry_.memory_bytes() +
                                                         visits_.capacity() * sizeof(Visit) +
                                                         queue_.size() * sizeof(StateId));
  registry_.unpack(s, values_);
  std::vector<ActionId> candidates = visits_[s.index()].helpful;
  if (candidates.empty()) task_.applicable_actions(values_, candidates);
  const Cost g = visits_[s.index()].g;
  for (ActionId a : candidates) {
    if (interrupted()) return std::nullopt;  // search() reports the stop
    const Cost succ_g = g + task_.cost(a);
    if (task_.exceeds_bound_before(current_g_ + g, a)) {
      ++result_.statistics.dead_ends;
      continue;
    }
    successor_ = values_;
    task_.apply(a, successor_);
    const StateId id = registry_.insert(successor_).first;
    ++result_.statistics.generated;
    if (visit(id).iteration == iteration_) continue;
    std::vector<ActionId> helpful;
    const Cost h = heuristic_.evaluate(successor_, &helpful);
    if (h == Heuristic::kInterrupted) return std::nullopt;  // search() reports the stop
    ++result_.statistics.evaluated;
    Visit& v = visit(id);
    v = {iteration_, s, a, succ_g, {}};
    if (h == Heuristic::kDeadEnd) {
      ++result_.statistics.dead_ends;
      continue;
    }
    if (h < current_h_ || task_.is_goal(successor_)) {
      commit(id);
      restart_from(id, h, std::move(helpful));
      return std::nullopt;
    }
    v.helpful = std::move(helpful);
    queue_.push_back(id);
  }
  return std::nullopt;
}

SearchResult EnforcedHillClimbing::result() const {
  SearchResult r = fallback_ ? fallback_->result() : result_;
  r.statistics = statistics();
  return r;
}

const SearchStatistics& EnforcedHillClimbing::statistics() const {
  combined_ = result_.statistics;
  if (fallback_) {
    // The fallback's time is counted by search() around the whole run, not here.
    SearchStatistics fallback = fallback_->statistics();
    fallback.time_s = 0;
    accumulate(combined_, fallback);
  }
  return combined_;
}

}  // namespace sewerplan::search
