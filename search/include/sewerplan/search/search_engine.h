// SPDX-License-Identifier: MIT
// SearchEngine: the common face of sewerplan's heuristic search algorithms.
//
// An engine searches a domain::CompiledTask for a plan: initialize(), then (unless the initial
// state decided it) step() (one expansion) until it returns a final status, then result(). search()
// runs that loop under a StopCondition (core/stop_condition.h), checked at every step, so a time
// limit or a cancel from another thread is honoured within one expansion (and, inside an expansion,
// between heuristic evaluations). Engines: BestFirstSearch (A*, weighted A*, greedy best-first, by
// configuration) and EnforcedHillClimbing (FF's). Modelled on Fast Downward's SearchAlgorithm
// (Helmert 2006).
//
//   BestFirstSearch astar(task, heuristic, BestFirstSearch::astar());
//   SearchResult r = astar.search(StopCondition::after_seconds(clock, 1.0));
//   if (r.status == SearchStatus::kSolved) use(r.plan);
//
// Thread-safety: an engine belongs to one thread; search() may be stopped from another through
// the StopCondition's cancel flag. SearchResult and SearchStatistics are plain values.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string_view>
#include <vector>

#include "sewerplan/core/stop_condition.h"
#include "sewerplan/domain/compiled_task.h"

namespace sewerplan::search {

using domain::ActionId;
using domain::Cost;
// The stop condition is core's (core/stop_condition.h), shared with the compile and the motion
// planner; these keep search::StopCondition and search::SearchStatus working.
using sewerplan::SearchStatus;
using sewerplan::StopCondition;

struct SearchStatistics {
  std::uint64_t expanded = 0;
  std::uint64_t generated = 0;
  std::uint64_t evaluated = 0;  // heuristic evaluations
  std::uint64_t reopened = 0;
  std::uint64_t dead_ends = 0;  // states the heuristic proved unsolvable, or over the cost bound
  std::uint64_t stored = 0;     // distinct states held in the state registry
  double time_s = 0;
  std::size_t peak_memory_bytes = 0;  // states, search data and open list at their largest
  friend bool operator==(const SearchStatistics&, const SearchStatistics&) = default;
};

std::ostream& operator<<(std::ostream& os, const SearchStatistics& s);

// Adds `more` to `total` (counts and times summed, peak memory the larger), for searches that run
// several engines one after another.
void accumulate(SearchStatistics& total, const SearchStatistics& more);

struct SearchResult {
  SearchStatus status = SearchStatus::kUnsolvable;
  std::vector<ActionId> plan;
  Cost cost = 0;
  SearchStatistics statistics;
  friend bool operator==(const SearchResult&, const SearchResult&) = default;
};

class SearchEngine {
 public:
  virtual ~SearchEngine() = default;

  // Runs initialize() and step() until a final status or until `stop` fires; the statistics'
  // time is measured on `clock`.
  SearchResult search(const StopCondition& stop, const Clock& clock);
  SearchResult search(const StopCondition& stop);  // on a SteadyClock

  // Stores and evaluates the initial state. Returns the final status when the initial state
  // decides the search (kSolved: it is a goal, the plan is empty; kUnsolvable: a dead end), which
  // result() then holds and search() reports even if the stop fires at that moment; nullopt while
  // the search goes on, or if the evaluation was interrupted.
  virtual std::optional<SearchStatus> initialize() = 0;
  // One expansion. Returns nullopt while the search goes on, else its final status.
  virtual std::optional<SearchStatus> step() = 0;
  virtual SearchResult result() const = 0;
  virtual const SearchStatistics& statistics() const = 0;
  virtual std::string_view name() const = 0;

  // The stop condition that step() also checks between heuristic evaluations, and the heuristic
  // inside them (search() sets it for its run; nullptr: none). An interrupted initialize() or
  // step() returns as it is, and search() then reports the stop: an engine interrupted so is not
  // stepped again.
  virtual void watch(const StopCondition* stop) { watched_ = stop; }

 protected:
  bool interrupted() const { return watched_ != nullptr && watched_->interrupted().has_value(); }
  const StopCondition* watched() const { return watched_; }

 private:
  const StopCondition* watched_ = nullptr;
};

}  // namespace sewerplan::search
