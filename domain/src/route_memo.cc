// SPDX-License-Identifier: MIT
#include "route_memo.h"

#include <algorithm>
#include <tuple>
#include <utility>

namespace sewerplan::domain::detail {
namespace {

template <class T, class Less>
std::vector<T> sorted(std::vector<T> v, Less less) {
  std::sort(v.begin(), v.end(), less);
  return v;
}

bool hazard_less(const Hazard& a, const Hazard& b) {
  return std::tie(a.pipe, a.offset_m, a.probability, a.reason) <
         std::tie(b.pipe, b.offset_m, b.probability, b.reason);
}

bool passage_less(const ClosedPassage& a, const ClosedPassage& b) {
  return std::tie(a.manhole, a.from, a.to) < std::tie(b.manhole, b.from, b.to);
}

bool blockage_less(const Blockage& a, const Blockage& b) {
  return std::tie(a.pipe, a.offset_m) < std::tie(b.pipe, b.offset_m);
}

// The entries of `now` that `then` lacks, through `f`; false if `then` has one `now` lacks.
// Both sorted by `less`.
template <class T, class Less, class F>
bool added(const std::vector<T>& then, const std::vector<T>& now, Less less, F&& f) {
  if (!std::includes(now.begin(), now.end(), then.begin(), then.end(), less)) return false;
  auto it = then.begin();
  for (const T& x : now) {
    while (it != then.end() && less(*it, x)) ++it;
    if (it == then.end() || less(x, *it)) f(x);
  }
  return true;
}

// Whether every drive's risk cost under `now`'s hazards is at least under `then`'s (both sorted
// by hazard_less): in each pipe, each hazard of `then` that weighs (probability above 0) has one
// of its own in `now` at the same offset, as likely or more; `now` may have more. f(pipe) for
// each pipe whose hazards differ. A drive's risk is 1 - prod(1 - p) over the hazards it passes,
// so it only grows: edges only dearer, as with closures (route_memo.h).
template <class F>
bool risen(const std::vector<Hazard>& then, const std::vector<Hazard>& now, F&& f) {
  auto probability = [](const Hazard& h) { return std::clamp(h.probability, 0.0, 1.0); };
  auto pipe_end = [](const std::vector<Hazard>& v, std::size_t i) {
    while (i + 1 < v.size() && v[i + 1].pipe == v[i].pipe) ++i;
    return i + 1;
  };
  std::size_t i = 0;
  std::size_t j = 0;
  while (i < then.size() || j < now.size()) {
    const PipeId pipe = j == now.size() || (i < then.size() && then[i].pipe < now[j].pipe)
                            ? then[i].pipe
                            : now[j].pipe;
    const std::size_t i_end = i < then.size() && then[i].pipe == pipe ? pipe_end(then, i) : i;
    const std::size_t j_end = j < now.size() && now[j].pipe == pipe ? pipe_end(now, j) : j;
    if (!std::equal(then.begin() + static_cast<std::ptrdiff_t>(i),
                    then.begin() + static_cast<std::ptrdiff_t>(i_end),
                    now.begin() + static_cast<std::ptrdiff_t>(j),
                    now.begin() + static_cast<std::ptrdiff_t>(j_end))) {
      // Sorted by offset, then probability: each of then's takes the least likely of now's at
      // its offset that is at least as likely, and not taken yet.
      std::vector<bool> taken(j_end - j, false);
      for (std::size_t a = i; a < i_end; ++a) {
        if (!(probability(then[a]) > 0)) continue;
        bool matched = false;
        for (std::size_t b = j; b < j_end && !matched; ++b) {
          if (!taken[b - j] && now[b].offset_m == then[a].offset_m &&
              probability(now[b]) >= probability(then[a])) {
            taken[b - j] = true;
            matched = true;
          }
        }
        if (!matched) return false;
      }
      f(pipe);
    }
    i = i_end;
    j = j_end;
  }
  return true;
}

}  // namespace

RouteMemo::Context RouteMemo::context_of(const Mission& mission, double blockage_weight_s,
                                         double return_weight_s, bool exit_goal) {
  Context c;
  c.blockage_weight_s = blockage_weight_s;
  c.return_weight_s = return_weight_s;
  c.exit_goal = exit_goal;
  c.exits = sorted(mission.exits, std::less<>());
  c.exits.erase(std::unique(c.exits.begin(), c.exits.end()), c.exits.end());
  if (blockage_weight_s > 0 || return_weight_s > 0)
    c.hazards = sorted(mission.hazards, hazard_less);
  c.closed_pipes = sorted(mission.closed_pipes, std::less<>());
  c.closed_pipes.erase(std::unique(c.closed_pipes.begin(), c.closed_pipes.end()),
                       c.closed_pipes.end());
  for (ClosedPassage p : mission.closed_passages) {
    if (p.to < p.from) std::swap(p.from, p.to);
    c.closed_passages.push_back(p);
  }
  c.closed_passages = sorted(std::move(c.closed_passages), passage_less);
  c.closed_passages.erase(std::unique(c.closed_passages.begin(), c.closed_passages.end()),
                          c.closed_passages.end());
  c.blockages = sorted(mission.blockages, blockage_less);
  c.blockages.erase(std::unique(c.blockages.begin(), c.blockages.end()), c.blockages.end());
  return c;
}

std::optional<RouteMemo::Change> RouteMemo::change_to(const Context& now,
                                                      const PositionGraph& graph) const {
  const Context& then = context;
  if (then.blockage_weight_s != now.blockage_weight_s ||
      then.return_weight_s != now.return_weight_s || then.exit_goal != now.exit_goal ||
      then.exits != now.exits) {
    return std::nullopt;
  }
  const SewerMap& map = graph.map();
  Change change;
  auto pipe = [&](PipeId p) {
    if (change.pipe.empty()) change.pipe.assign(map.pipe_count(), false);
    change.pipe[p.index()] = true;
    change.nodes.push_back(graph.pipe_end(p, 0));
    change.nodes.push_back(graph.pipe_end(p, 1));
    change.any = true;
  };
  auto manhole = [&](ManholeId m) {
    change.nodes.push_back(graph.in_manhole(m));
    for (std::uint16_t s = 0; s < map.manhole(m).slot_count; ++s) {
      change.nodes.push_back(graph.at_slot(m, SlotIndex{s}));
    }
    change.any = true;
  };
  if (!risen(then.hazards, now.hazards, pipe) ||
      !added(then.closed_pipes, now.closed_pipes, std::less<>(), pipe) ||
      !added(then.closed_passages, now.closed_passages, passage_less,
             [&](const ClosedPassage& c) { manhole(c.manhole); }) ||
      !added(then.blockages, now.blockages, blockage_less,
             [&](const Blockage& b) { pipe(b.pipe); })) {
    return std::nullopt;
  }
  std::sort(change.nodes.begin(), change.nodes.end());
  change.nodes.erase(std::unique(change.nodes.begin(), change.nodes.end()), change.nodes.end());
  for (Node n : change.nodes) change.maybe[(n >> 6) & 63] |= std::uint64_t{1} << (n & 63);
  return change;
}

bool RouteMemo::Change::touches(const PositionGraph& graph, std::span<const Node> route) const {
  if (!any) return false;
  // A search in a short sorted list per node: a slot's manhole would be a lookup in a table as
  // large as the map, a cache miss per node (a replan checks hundreds of thousands).
  for (Node n : route) {
    if (graph.is_extra_spot(n)) {
      if (!pipe.empty() && pipe[graph.pipe_of(n)->index()]) return true;
    } else if (((maybe[(n >> 6) & 63] >> (n & 63)) & 1) != 0 &&
               std::binary_search(nodes.begin(), nodes.end(), n)) {
      return true;
    }
  }
  return false;
}

}  // namespace sewerplan::domain::detail
