// SPDX-License-Identifier: MIT
#include "sewerplan/search/search_engine.h"

#include <algorithm>

namespace sewerplan::search {

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

SearchResult SearchEngine::search(const StopCondition& stop, const Clock& clock) {
  const double start_s = clock.now_s();
  watch(&stop);
  // A result the initial state decides (a goal, a dead end) stands even if the stop fires as it
  // is found (issue 14); otherwise the first evaluation may have been interrupted (the expansion
  // limit is for step()s).
  std::optional<SearchStatus> stopped;
  if (!initialize()) {
    stopped = stop.interrupted();
    while (!stopped && !step()) stopped = stop.check(statistics().expanded);
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
