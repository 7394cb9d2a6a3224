// SPDX-License-Identifier: MIT
#include "sewerplan/search/search_engine.h"

#include <algorithm>

namespace sewerplan::search {

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

std::ostream& operator<<(std::ostream& os, const SearchStatistics& s) {
  return os << s.expanded << " expanded, " << s.generated << " generated, " << s.evaluated
            << " evaluated, " << s.reopened << " reopened, " << s.dead_ends << " dead ends, "
            << s.time_s << " s, peak " << s.peak_memory_bytes << " bytes";
}

void accumulate(SearchStatistics& total, const SearchStatistics& more) {
  total.expanded += more.expanded;
  total.generated += more.generated;
  total.evaluated += more.evaluated;
  total.reopened += more.reopened;
  total.dead_ends += more.dead_ends;
  total.stored += more.stored;
  total.time_s += more.time_s;
  total.peak_memory_bytes = std::max(total.peak_memory_bytes, more.peak_memory_bytes);
}

StopCondition StopCondition::after_seconds(const Clock& clock, double seconds) {
  StopCondition stop;
  stop.clock_ = &clock;
  stop.deadline_s_ = clock.now_s() + seconds;
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
  if (cancel_ != nullptr && cancel_->load(std::memory_order_relaxed))
    return SearchStatus::kCancelled;
  if (expansions >= max_expansions_) return SearchStatus::kExpansionLimit;
  if (clock_ != nullptr && clock_->now_s() >= deadline_s_) return SearchStatus::kTimeLimit;
  return std::nullopt;
}

std::optional<SearchStatus> StopCondition::interrupted() const {
  if (cancel_ != nullptr && cancel_->load(std::memory_order_relaxed))
    return SearchStatus::kCancelled;
  if (clock_ != nullptr && clock_->now_s() >= deadline_s_) return SearchStatus::kTimeLimit;
  return std::nullopt;
}

SearchResult SearchEngine::search(const StopCondition& stop, const Clock& clock) {
  const double start_s = clock.now_s();
  watch(&stop);
  initialize();
  std::optional<SearchStatus> stopped;
  while (!step()) {
    stopped = stop.check(statistics().expanded);
    if (stopped) break;
  }
  watch(nullptr);
  SearchResult r = result();
  if (stopped) {
    r.status = *stopped;
    r.plan.clear();
  }
  r.statistics.time_s = clock.now_s() - start_s;
  return r;
}

SearchResult SearchEngine::search(const StopCondition& stop) {
  const SteadyClock clock;
  return search(stop, clock);
}

}  // namespace sewerplan::search
