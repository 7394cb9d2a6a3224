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
      then.exits != now.exits || then.hazards != now.hazards) {
    return std::nullopt;
  }
  const SewerMap& map = graph.map();
  Change change;
  auto pipe = [&](PipeId p) {
    if (change.pipe.empty()) change.pipe.assign(map.pipe_count(), false);
    change.pipe[p.index()] = true;
    change.any = true;
  };
  auto manhole = [&](ManholeId m) {
    if (change.manhole.empty()) change.manhole.assign(map.manhole_count(), false);
    change.manhole[m.index()] = true;
    change.any = true;
  };
  if (!added(then.closed_pipes, now.closed_pipes, std::less<>(), pipe) ||
      !added(then.closed_passages, now.closed_passages, passage_less,
             [&](const ClosedPassage& c) { manhole(c.manhole); }) ||
      !added(then.blockages, now.blockages, blockage_less,
             [&](const Blockage& b) { pipe(b.pipe); })) {
    return std::nullopt;
  }
  return change;
}

bool RouteMemo::Change::touches(const PositionGraph& graph, std::span<const Node> route) const {
  if (!any) return false;
  for (Node n : route) {
    if (const std::optional<PipeId> p = graph.pipe_of(n)) {
      if (!pipe.empty() && pipe[p->index()]) return true;
    } else if (const std::optional<ManholeId> m = graph.manhole_at(n)) {
      if (!manhole.empty() && manhole[m->index()]) return true;
    }
  }
  return false;
}

}  // namespace sewerplan::domain::detail
