// SPDX-License-Identifier: MIT
// Building a contraction hierarchy (contraction_hierarchy.h): node order, witness searches,
// shortcuts, and the upward edges by rank.
#include "contraction_hierarchy.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <string>

namespace sewerplan::domain::detail {

namespace {
constexpr std::uint32_t kNone = 0xffffffffU;
constexpr Cost kMaxEdgeCost = 0xfffffffeLL;  // fits Edge::cost
}  // namespace

// The graph while it is contracted: each uncontracted node's moves in and out, to uncontracted
// nodes only (a node's moves leave its neighbours' lists when it is contracted), parallel moves
// merged to the cheapest.
class ChBuilder {
 public:
  struct Arc {
    std::uint32_t other;
    std::uint32_t middle;  // by node; kNone: a move of the graph
    Cost cost;
    std::uint32_t ways;  // shortest ways between its ends it stands for: 1, or 2 (more)
  };

  ChBuilder(std::span<const std::uint32_t> begin, std::span<const Node> to,
            std::span<const Cost> cost, const ChOptions& options)
      : options_(options), n_(static_cast<std::uint32_t>(begin.size() - 1)) {
    out_.resize(n_);
    in_.resize(n_);
    for (std::uint32_t u = 0; u < n_; ++u) {
      for (std::uint32_t e = begin[u]; e < begin[u + 1]; ++e) {
        if (to[e] >= n_) {
          error_ =
              "move " + std::to_string(u) + " -> " + std::to_string(to[e]) + " leaves the graph";
          return;
        }
        if (cost[e] < 0) {
          error_ =
              "move " + std::to_string(u) + " -> " + std::to_string(to[e]) + " has a negative cost";
          return;
        }
        if (to[e] != u) add_arc(u, to[e], cost[e], kNone, 1);
      }
    }
    for (const auto& arcs : out_) moves_ += arcs.size();
    dist_.assign(n_, kInfiniteCost);
    target_.assign(n_, false);
    contracted_.assign(n_, false);
    neighbours_contracted_.assign(n_, 0);
    level_.assign(n_, 0);
    priority_.assign(n_, 0);
  }

  Result<ContractionHierarchy> run() {
    if (!error_.empty()) return Error{ErrorCode::kInvalidArgument, error_};
    using Entry = std::pair<std::int64_t, std::uint32_t>;
    std::vector<Entry> heap;
    heap.reserve(n_);
    for (std::uint32_t v = 0; v < n_; ++v) {
      if (options_.stop != nullptr && v % 1024 == 0 && options_.stop->interrupted()) {
        return Error{ErrorCode::kCancelled, "the routing index's build was stopped while its " +
                                                std::string("nodes were ordered")};
      }
      priority_[v] = estimate(v);
      heap.emplace_back(priority_[v], v);
    }
    const auto later = std::greater<Entry>();
    std::make_heap(heap.begin(), heap.end(), later);
    std::vector<std::uint32_t> order;
    order.reserve(n_);
    final_up_.resize(n_);
    final_down_.resize(n_);
    while (!heap.empty()) {
      std::pop_heap(heap.begin(), heap.end(), later);
      const auto [p, v] = heap.back();
      heap.pop_back();
      if (contracted_[v] || p != priority_[v]) continue;
      // Not re-estimated here (lazy updates): the neighbours' estimates are renewed as each
      // node is contracted (below), and re-estimating at every pop too cost 10 % more time for
      // the same shortcuts (10k scrambled manholes, 2026-12-07).
      if (options_.stop != nullptr && order.size() % 1024 == 0 && options_.stop->interrupted()) {
        return Error{ErrorCode::kCancelled, "the routing index's build was stopped after " +
                                                std::to_string(order.size()) + " of " +
                                                std::to_string(n_) + " nodes"};
      }
      contract(v);
      order.push_back(v);
      for (std::uint32_t x : touched_neighbours_) {
        priority_[x] = estimate(x);
        heap.emplace_back(priority_[x], x);
        std::push_heap(heap.begin(), heap.end(), later);
      }
    }
    if (!error_.empty()) return Error{ErrorCode::kInvalidArgument, error_};
    return finish(order);
  }

 private:
  // A move or shortcut u -> w standing for `ways` ways; merged with one already there (the
  // cheaper stays; with keep_ties, equal costs add their ways).
  void add_arc(std::uint32_t u, std::uint32_t w, Cost c, std::uint32_t middle, std::uint32_t ways) {
    for (Arc& a : out_[u]) {
      if (a.other != w) continue;
      Arc merged = a;
      if (c < a.cost) {
        merged = {w, middle, c, ways};
      } else if (c == a.cost && options_.keep_ties) {
        merged.ways = std::min(2U, a.ways + ways);
      } else {
        return;
      }
      a = merged;
      for (Arc& b : in_[w]) {
        if (b.other == u) b = {u, merged.middle, merged.cost, merged.ways};
      }
      return;
    }
    out_[u].push_back({w, middle, c, ways});
    in_[w].push_back({u, middle, c, ways});
  }

  static void remove_arc(std::vector<Arc>& arcs, std::uint32_t other) {
    for (std::size_t i = 0; i < arcs.size(); ++i) {
      if (arcs[i].other == other) {
        arcs[i] = arcs.back();
        arcs.pop_back();
        return;
      }
    }
  }

  // A Dijkstra from u in the uncontracted graph without `skip`, up to `bound` or `limit` settled
  // nodes, or until every target is settled; dist_ holds what it found until the next reset.
  void witness_search(std::uint32_t u, std::uint32_t skip, Cost bound, std::size_t limit,
                      std::size_t targets) {
    reset();
    dist_[u] = 0;
    touched_.push_back(u);
    heap_.emplace_back(0, u);
    const auto later = std::greater<std::pair<Cost, std::uint32_t>>();
    std::size_t settled = 0;
    while (!heap_.empty() && settled < limit && targets > 0) {
      std::pop_heap(heap_.begin(), heap_.end(), later);
      const auto [d, x] = heap_.back();
      heap_.pop_back();
      if (d != dist_[x]) continue;
      if (d > bound) break;
      ++settled;
      if (target_[x]) --targets;
      for (const Arc& a : out_[x]) {
        if (a.other == skip) continue;
        const Cost nd = d + a.cost;
        if (nd < dist_[a.other]) {
          if (dist_[a.other] == kInfiniteCost) touched_.push_back(a.other);
          dist_[a.other] = nd;
          heap_.emplace_back(nd, a.other);
          std::push_heap(heap_.begin(), heap_.end(), later);
        }
      }
    }
  }

  void reset() {
    for (std::uint32_t x : touched_) dist_[x] = kInfiniteCost;
    touched_.clear();
    heap_.clear();
  }

  // Calls shortcut(u, w, cost, ways) for each shortcut contracting v needs, searching witnesses
  // with at most `limit` settled nodes each. With keep_ties, a witness must be strictly shorter.
  template <class F>
  void for_each_shortcut(std::uint32_t v, std::size_t limit, F&& shortcut) {
    if (in_[v].empty() || out_[v].empty()) return;
    Cost max_out = 0;
    for (const Arc& b : out_[v]) {
      max_out = std::max(max_out, b.cost);
      target_[b.other] = true;
    }
    for (const Arc& a : in_[v]) {
      const std::size_t targets = out_[v].size() - (target_[a.other] ? 1 : 0);
      if (targets == 0) continue;
      witness_search(a.other, v, a.cost + max_out, limit, targets);
      for (const Arc& b : out_[v]) {
        if (b.other == a.other) continue;
        const Cost via = a.cost + b.cost;
        if (dist_[b.other] > via || (options_.keep_ties && dist_[b.other] == via)) {
          shortcut(a.other, b.other, via, std::min(2U, a.ways * b.ways));
        }
      }
    }
    for (const Arc& b : out_[v]) target_[b.other] = false;
  }

  // Edge difference (shortcuts added less moves removed), contracted neighbours and level, after
  // Geisberger et al. (2008), section 3. The weights: 4, 1, 1 built 10k scrambled manholes in
  // 200 ms with 108k shortcuts, against 260 ms and 120k with 2, 1, 1 and 350 ms and 138k with
  // 1, 1, 0 (bench/domain/contraction_hierarchy_bench.cc, 2026-12-07).
  std::int64_t estimate(std::uint32_t v) {
    std::int64_t added = 0;
    for_each_shortcut(v, options_.estimate_settled,
                      [&](std::uint32_t, std::uint32_t, Cost, std::uint32_t) { ++added; });
    const auto removed = static_cast<std::int64_t>(in_[v].size() + out_[v].size());
    return 4 * (added - removed) + neighbours_contracted_[v] + level_[v];
  }

  void contract(std::uint32_t v) {
    contracted_[v] = true;
    // The moves v keeps are its upward edges: every other end is contracted later.
    final_up_[v] = out_[v];
    final_down_[v] = in_[v];
    shortcuts_.clear();
    for_each_shortcut(v, options_.contract_settled,
                      [&](std::uint32_t u, std::uint32_t w, Cost c, std::uint32_t ways) {
                        shortcuts_.push_back({u, w, c, ways});
                      });
    touched_neighbours_.clear();
    for (const Arc& a : in_[v]) {
      remove_arc(out_[a.other], v);
      touched_neighbours_.push_back(a.other);
    }
    for (const Arc& b : out_[v]) {
      remove_arc(in_[b.other], v);
      touched_neighbours_.push_back(b.other);
    }
    for (const auto& [u, w, c, ways] : shortcuts_) {
      if (c > kMaxEdgeCost) {
        error_ = "a shortcut " + std::to_string(u) + " -> " + std::to_string(w) + " costs " +
                 std::to_string(c) + " ms, more than a 32-bit edge holds";
      }
      add_arc(u, w, c, v, ways);
    }
    out_[v].clear();
    out_[v].shrink_to_fit();
    in_[v].clear();
    in_[v].shrink_to_fit();
    std::sort(touched_neighbours_.begin(), touched_neighbours_.end());
    touched_neighbours_.erase(std::unique(touched_neighbours_.begin(), touched_neighbours_.end()),
                              touched_neighbours_.end());
    for (std::uint32_t x : touched_neighbours_) {
      ++neighbours_contracted_[x];
      level_[x] = std::max(level_[x], level_[v] + 1);
    }
  }

  Result<ContractionHierarchy> finish(const std::vector<std::uint32_t>& order) {
    ContractionHierarchy ch;
    ch.node_ = order;
    ch.rank_.assign(n_, 0);
    for (std::uint32_t r = 0; r < n_; ++r) ch.rank_[order[r]] = r;
    auto fill = [&](const std::vector<std::vector<Arc>>& lists, std::vector<std::uint32_t>& begin,
                    std::vector<ContractionHierarchy::Edge>& edges) -> Result<void> {
      begin.reserve(n_ + 1);
      for (std::uint32_t r = 0; r < n_; ++r) {
        begin.push_back(static_cast<std::uint32_t>(edges.size()));
        for (const Arc& a : lists[order[r]]) {
          if (a.cost > kMaxEdgeCost) {
            return Error{ErrorCode::kInvalidArgument, "a move of node " + std::to_string(order[r]) +
                                                          " costs " + std::to_string(a.cost) +
                                                          " ms, more than a 32-bit edge holds"};
          }
          const std::uint32_t middle =
              a.middle == kNone ? ContractionHierarchy::kNoMiddle : ch.rank_[a.middle];
          if (middle != ContractionHierarchy::kNoMiddle) ++ch.statistics_.shortcuts;
          const std::uint32_t tied = a.ways > 1 ? 0x80000000U : 0U;
          edges.push_back({ch.rank_[a.other], static_cast<std::uint32_t>(a.cost), middle | tied});
        }
        // By head, so that unpacking finds a shortcut's halves by binary search (find_up).
        std::sort(edges.begin() + begin.back(), edges.end(),
                  [](const auto& x, const auto& y) { return x.head < y.head; });
      }
      begin.push_back(static_cast<std::uint32_t>(edges.size()));
      return Result<void>{};
    };
    if (auto r = fill(final_up_, ch.up_begin_, ch.up_); !r.has_value()) return r.error();
    if (auto r = fill(final_down_, ch.down_begin_, ch.down_); !r.has_value()) return r.error();
    ChStatistics& s = ch.statistics_;
    s.nodes = n_;
    s.moves = moves_;
    s.up_edges = ch.up_.size();
    s.down_edges = ch.down_.size();
    s.bytes = (ch.rank_.size() + ch.node_.size() + ch.up_begin_.size() + ch.down_begin_.size()) *
                  sizeof(std::uint32_t) +
              (ch.up_.size() + ch.down_.size()) * sizeof(ContractionHierarchy::Edge);
    return ch;
  }

  struct Shortcut {
    std::uint32_t from;
    std::uint32_t to;
    Cost cost;
    std::uint32_t ways;
  };

  ChOptions options_;
  std::uint32_t n_;
  std::string error_;
  std::size_t moves_ = 0;
  std::vector<std::vector<Arc>> out_;
  std::vector<std::vector<Arc>> in_;
  std::vector<std::vector<Arc>> final_up_;
  std::vector<std::vector<Arc>> final_down_;
  std::vector<Cost> dist_;
  std::vector<bool> target_;
  std::vector<bool> contracted_;
  std::vector<std::int64_t> neighbours_contracted_;
  std::vector<std::int64_t> level_;
  std::vector<std::int64_t> priority_;
  std::vector<std::uint32_t> touched_;
  std::vector<std::pair<Cost, std::uint32_t>> heap_;
  std::vector<std::uint32_t> touched_neighbours_;
  std::vector<Shortcut> shortcuts_;
};

Result<ContractionHierarchy> ContractionHierarchy::build(std::span<const std::uint32_t> begin,
                                                         std::span<const Node> to,
                                                         std::span<const Cost> cost,
                                                         const ChOptions& options) {
  if (begin.empty() || to.size() != cost.size() || begin.back() != to.size()) {
    return Error{ErrorCode::kInvalidArgument, "the graph's rows do not match its moves"};
  }
  if (begin.size() > kNoMiddle) {
    return Error{ErrorCode::kInvalidArgument, "too many nodes for a contraction hierarchy"};
  }
  return ChBuilder(begin, to, cost, options).run();
}

}  // namespace sewerplan::domain::detail
