// SPDX-License-Identifier: MIT
#include "sewerplan/core/stop_condition.h"

#include <string>

namespace sewerplan {

std::string_view to_string(SearchStatus status) {
  switch (status) {
    case SearchStatus::kSolved:
      return "solved";
    case SearchStatus::kUnsolvable:
      return "unsolvable";
    case SearchStatus::kTimeLimit:
      return "time limit";
    case SearchStatus::kExpansionLimit:
      return "expansion limit";
    case SearchStatus::kCancelled:
      return "cancelled";
  }
  return "unknown";
}

StopCondition StopCondition::after_seconds(const Clock& clock, double seconds) {
  return at_deadline(clock, clock.now_s() + seconds);
}

StopCondition StopCondition::at_deadline(const Clock& clock, double deadline_s) {
  StopCondition stop;
  stop.clock_ = &clock;
  stop.deadline_s_ = deadline_s;
  return stop;
}

StopCondition& StopCondition::with_max_expansions(std::uint64_t expansions) {
  max_expansions_ = expansions;
  return *this;
}

StopCondition& StopCondition::with_cancel(const std::atomic<bool>& cancel) {
  cancel_ = &cancel;
  return *this;
}

std::optional<SearchStatus> StopCondition::check(std::uint64_t expansions) const {
  if (cancel_ != nullptr && cancel_->load(std::memory_order_relaxed)) {
    return SearchStatus::kCancelled;
  }
  if (expansions >= max_expansions_) return SearchStatus::kExpansionLimit;
  if (clock_ != nullptr && clock_->now_s() >= deadline_s_) return SearchStatus::kTimeLimit;
  return std::nullopt;
}

std::optional<SearchStatus> StopCondition::interrupted() const {
  if (cancel_ != nullptr && cancel_->load(std::memory_order_relaxed)) {
    return SearchStatus::kCancelled;
  }
  if (clock_ != nullptr && clock_->now_s() >= deadline_s_) return SearchStatus::kTimeLimit;
  return std::nullopt;
}

Error stopped_error(SearchStatus stopped, std::string_view what) {
  switch (stopped) {
    case SearchStatus::kCancelled:
      return Error{ErrorCode::kCancelled, std::string(what) + " was cancelled"};
    case SearchStatus::kTimeLimit:
      return Error{ErrorCode::kSearchLimit, std::string(what) + " reached its time limit"};
    case SearchStatus::kExpansionLimit:
      return Error{ErrorCode::kSearchLimit, std::string(what) + " reached its expansion limit"};
    case SearchStatus::kSolved:
    case SearchStatus::kUnsolvable:
      break;
  }
  return Error{ErrorCode::kSearchLimit, std::string(what) + " stopped"};
}

}  // namespace sewerplan
