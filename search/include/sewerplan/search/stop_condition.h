// SPDX-License-Identifier: MIT
// StopCondition: when a search must give up: a time limit, an expansion limit, or a cancel.
//
// After OMPL's PlannerTerminationCondition: the caller composes the limits, and the engine asks
// at every expansion. Time comes from an injected Clock (clock.h); the cancel flag may be set from
// any thread.
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

namespace sewerplan::search {

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
  static StopCondition after_seconds(const Clock& clock, double seconds);

  StopCondition& with_max_expansions(std::uint64_t expansions);
  // `cancel` must outlive the search.
  StopCondition& with_cancel(const std::atomic<bool>& cancel);

  // The reason to stop now, if any.
  std::optional<SearchStatus> check(std::uint64_t expansions) const;
  // The cancel flag or the time limit, without the expansion limit: for work inside one
  // expansion (a heuristic evaluation per successor), so that a cancel is honoured within one
  // evaluation rather than one expansion.
  std::optional<SearchStatus> interrupted() const;

 private:
  const Clock* clock_ = nullptr;
  double deadline_s_ = std::numeric_limits<double>::infinity();
  std::uint64_t max_expansions_ = std::numeric_limits<std::uint64_t>::max();
  const std::atomic<bool>* cancel_ = nullptr;
};

}  // namespace sewerplan::search
