// SPDX-License-Identifier: MIT
// StopCondition: when a long computation must give up: a time limit, an expansion limit, or a
// cancel.
//
// One stop condition for every algorithm of sewerplan (issue 14): the heuristic search engines, the
// tour search and the exact tour search (search/), the compile's route searches and goal selection
// (domain/compile.h), and the motion planner through a manhole and its precompute
// (fusion/manhole_turn_planner.h, passage_precompute.h: OMPL's own PlannerTerminationCondition is
// built from it). After OMPL's PlannerTerminationCondition: the caller composes the limits, and the
// algorithm asks at every unit of its work (an expansion, a slice of a heuristic's exploration, an
// order evaluated, 256 nodes settled, an RRT iteration). Time comes from an injected Clock
// (clock.h); the cancel flag may be set from any thread. SearchStatus, the outcome of a search,
// names the reasons to stop among its values.
//
// Thread-safety: a StopCondition is an immutable value once composed; check() may be called from
// any number of threads at once (it reads the atomic cancel flag and the clock).
//
//   std::atomic<bool> cancel{false};
//   StopCondition stop = StopCondition::after_seconds(clock, 0.5)
//                            .with_max_expansions(1'000'000).with_cancel(cancel);
//   ... from another thread: cancel = true;
#pragma once

#include <atomic>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/result.h"

namespace sewerplan {

enum class SearchStatus {
  kSolved,          // a plan was found
  kUnsolvable,      // the reachable state space holds no plan within the cost bound
  kTimeLimit,       // stopped at the time limit
  kExpansionLimit,  // stopped at the expansion limit
  kCancelled,       // cancelled from outside
};

std::string_view to_string(SearchStatus status);

class StopCondition {
 public:
  // Never stops.
  StopCondition() = default;
  // Stops `seconds` from now on `clock` (which must outlive the condition).
  static StopCondition after_seconds(const Clock& clock, double seconds);
  // Stops once `clock` reads `deadline_s` (as Clock::now_s(); infinite: never).
  static StopCondition at_deadline(const Clock& clock, double deadline_s);

  StopCondition& with_max_expansions(std::uint64_t expansions);
  // `cancel` must outlive the search.
  StopCondition& with_cancel(const std::atomic<bool>& cancel);

  // The reason to stop now, if any.
  std::optional<SearchStatus> check(std::uint64_t expansions) const;
  // The cancel flag or the time limit, without the expansion limit: for work inside one
  // expansion (a heuristic evaluation per successor), so that a cancel is honoured within one
  // evaluation rather than one expansion, and for algorithms that count no expansions.
  std::optional<SearchStatus> interrupted() const;

  // Whether the condition can ever fire without an expansion limit (a clock or a cancel flag).
  bool can_interrupt() const { return clock_ != nullptr || cancel_ != nullptr; }

 private:
  const Clock* clock_ = nullptr;
  double deadline_s_ = std::numeric_limits<double>::infinity();
  std::uint64_t max_expansions_ = std::numeric_limits<std::uint64_t>::max();
  const std::atomic<bool>* cancel_ = nullptr;
};

// The error of a computation that `stopped`: kCancelled for a cancel, kSearchLimit for a limit;
// `what` names the computation ("the compile", "the motion planner"). `stopped` is one of the
// reasons to stop (kTimeLimit, kExpansionLimit, kCancelled); any other value reads as a limit.
Error stopped_error(SearchStatus stopped, std::string_view what);

}  // namespace sewerplan
