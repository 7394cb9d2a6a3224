// SPDX-License-Identifier: MIT
// BestFirstSearch: eager best-first search; A*, weighted A* and greedy search are its orderings.
//
// States are ordered by f = g_weight x g + h_weight x h, ties broken by lower h and then by the
// order of generation (so runs are deterministic). A* (1, 1) with an admissible heuristic returns
// an optimal plan (Hart, Nilsson and Raphael 1968); weighted A* (1, w) one within a factor w of
// optimal (Pohl 1970); greedy best-first (0, 1) the first plan its heuristic leads to. A state
// reached again more cheaply is reopened. States costing more than the task's cost bound (with an
// admissible heuristic: whose g + h does) are pruned, so "unsolvable" means no plan within the
// bound. As in Fast Downward, A* is a configuration of this engine, not a class.
//
//   auto h = make_heuristic(HeuristicKind::kMax, task);
//   BestFirstSearch astar(task, *h, BestFirstSearch::astar());
//   SearchResult r = astar.search(StopCondition());
//
// Thread-safety: a BestFirstSearch (and the Heuristic it uses) belongs to one thread; cancel it
// from another through the StopCondition's atomic flag. Distinct engines over one task may run
// concurrently (the task is only read).
#pragma once

#include <cstdint>
#include <vector>

#include "sewerplan/domain/state_registry.h"
#include "sewerplan/search/heuristic.h"
#include "sewerplan/search/search_engine.h"

namespace sewerplan::search {

class BestFirstSearch final : public SearchEngine {
 public:
  struct Ordering {
    double g_weight = 1;
    double h_weight = 1;
  };
  static Ordering astar() { return {1, 1}; }
  static Ordering weighted_astar(double weight) { return {1, weight}; }
  static Ordering greedy() { return {0, 1}; }

  // `task` and `heuristic` must outlive the search. `cost_bound` tightens the task's own bound
  // (plans must cost at most the smaller), for anytime search that only wants cheaper plans.
  BestFirstSearch(const domain::CompiledTask& task, Heuristic& heuristic, Ordering ordering,
                  Cost cost_bound = domain::kInfiniteCost);

  std::optional<SearchStatus> initialize() override;
  std::optional<SearchStatus> step() override;
  void watch(const StopCondition* stop) override;
  SearchResult result() const override { return result_; }
  const SearchStatistics& statistics() const override { return result_.statistics; }
  std::string_view name() const override;

 private:
  enum class Status : std::uint8_t { kNew, kOpen, kClosed, kDeadEnd };
  struct NodeInfo {
    Cost g = 0;
    Cost h = 0;
    domain::StateId parent{0};
    ActionId action{0};
    Status status = Status::kNew;
  };
  struct Entry {
    Cost f;
    Cost h;
    std::uint64_t order;
    Cost g;
    domain::StateId state;
  };

  void open(domain::StateId id, const NodeInfo& info);
  Cost f_value(Cost g, Cost h) const;
  void trace_plan(domain::StateId goal);
  void update_memory();

  const domain::CompiledTask& task_;
  Heuristic& heuristic_;
  Ordering ordering_;
  Cost bound_;
  domain::StateRegistry registry_;
  std::vector<NodeInfo> info_;
  std::vector<Entry> heap_;
  std::uint64_t order_ = 0;
  std::vector<std::int32_t> values_;
  std::vector<std::int32_t> successor_;
  std::vector<ActionId> applicable_;
  SearchResult result_;
};

}  // namespace sewerplan::search
