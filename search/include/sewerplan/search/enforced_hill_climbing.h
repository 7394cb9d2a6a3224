// SPDX-License-Identifier: MIT
// EnforcedHillClimbing: FF's search (Hoffmann and Nebel 2001, section 4).
//
// From the current state, a breadth-first search over the heuristic's helpful actions looks for
// the nearest state with a strictly better heuristic value (or a goal); the path to it is
// committed and the search goes on from there. If a breadth-first search runs dry, enforced
// hill-climbing has failed, and, as FF does, the engine starts a complete greedy best-first search
// from the initial state with the same heuristic. Plans are found fast but are not optimal. Paths
// costing more than the task's cost bound are pruned.
//
//   auto h = make_heuristic(HeuristicKind::kFf, task);
//   EnforcedHillClimbing ehc(task, *h);
//   SearchResult r = ehc.search(StopCondition::after_seconds(clock, 1.0));
//
// Thread-safety: as BestFirstSearch: one thread per engine, cancelled through the StopCondition.
#pragma once

#include <deque>
#include <memory>
#include <vector>

#include "sewerplan/domain/segmented_vector.h"
#include "sewerplan/domain/state_registry.h"
#include "sewerplan/search/best_first_search.h"
#include "sewerplan/search/heuristic.h"
#include "sewerplan/search/search_engine.h"

namespace sewerplan::search {

class EnforcedHillClimbing final : public SearchEngine {
 public:
  // `task` and `heuristic` must outlive the search; the heuristic should offer preferred actions
  // (FF does); without them every applicable action is tried.
  EnforcedHillClimbing(const domain::CompiledTask& task, Heuristic& heuristic);

  std::optional<SearchStatus> initialize() override;
  std::optional<SearchStatus> step() override;
  void watch(const StopCondition* stop) override;
  SearchResult result() const override;
  const SearchStatistics& statistics() const override;
  std::string_view name() const override { return "enforced hill-climbing"; }
  // Whether enforced hill-climbing failed and the greedy best-first fallback took over.
  bool fell_back() const { return fallback_ != nullptr; }

 private:
  struct Visit {
    std::uint64_t iteration = 0;
    domain::StateId parent{0};
    ActionId action{0};
    Cost g = 0;  // from the current state
    std::vector<ActionId> helpful;
  };

  void restart_from(domain::StateId state, Cost h, std::vector<ActionId> helpful);
  void commit(domain::StateId reached);
  Visit& visit(domain::StateId id);

  const domain::CompiledTask& task_;
  Heuristic& heuristic_;
  domain::StateRegistry registry_;
  domain::SegmentedVector<Visit> visits_;  // grows without moving (issue 14)
  std::deque<domain::StateId> queue_;
  std::uint64_t iteration_ = 0;
  domain::StateId current_{0};
  Cost current_h_ = 0;
  Cost current_g_ = 0;
  std::vector<ActionId> plan_;
  std::vector<std::int32_t> values_;
  std::vector<std::int32_t> successor_;
  std::vector<ActionId> applicable_;
  SearchResult result_;
  std::unique_ptr<BestFirstSearch> fallback_;
  mutable SearchStatistics combined_;
};

}  // namespace sewerplan::search
