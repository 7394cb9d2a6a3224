// SPDX-License-Identifier: MIT
// Queries on a contraction hierarchy (contraction_hierarchy.h): point to point, many to many
// (buckets), and unpacking a way into the graph's moves.
#include <algorithm>
#include <cassert>
#include <functional>

#include "sewerplan/core/check.h"

#include "contraction_hierarchy.h"

namespace sewerplan::domain::detail {

namespace {
constexpr std::uint32_t kNone = 0xffffffffU;
// distance_to_aim()'s marks in forward_.dist (no way costs that much: a cost is at most 2^32 ms
// per edge): waiting for its upward neighbours, known to have no way.
constexpr Cost kAimOpen = kInfiniteCost - 1;
constexpr Cost kAimNoWay = kInfiniteCost - 2;

// The edge to `head` among edges[begin[tail], begin[tail + 1]), sorted by head: a binary search.
// (Finding a shortcut's halves was two thirds of a first plan's time at 100,000 scrambled
// manholes, but as a cache miss per half, not the scan: the lists are short. ChTable::segment
// unpacks each tree edge once instead.)
template <class Edge>
const Edge& find_edge(const std::vector<std::uint32_t>& begin, const std::vector<Edge>& edges,
                      std::uint32_t tail, std::uint32_t head) {
  const auto first = edges.begin() + begin[tail];
  const auto last = edges.begin() + begin[tail + 1];
  const auto it = std::lower_bound(first, last, head,
                                   [](const Edge& e, std::uint32_t h) { return e.head < h; });
  SEWER_CHECK(it != last && it->head == head,
              "a contraction hierarchy's way uses an edge it does not have");
  return it != last ? *it : edges.front();
}
}  // namespace

const ContractionHierarchy::Edge& ContractionHierarchy::find_up(std::uint32_t low,
                                                                std::uint32_t high) const {
  return find_edge(up_begin_, up_, low, high);
}

const ContractionHierarchy::Edge& ContractionHierarchy::find_down(std::uint32_t low,
                                                                  std::uint32_t high) const {
  return find_edge(down_begin_, down_, low, high);
}

ChQuery::ChQuery(const ContractionHierarchy& ch) : ch_(ch) {
  for (Side* side : {&forward_, &backward_}) {
    side->dist.assign(ch.size(), kInfiniteCost);
    side->parent.assign(ch.size(), kNone);
    side->ways.assign(ch.size(), 0);
  }
  bucket_begin_.assign(ch.size(), 0);
}

void ChQuery::clear(Side& side) {
  for (std::uint32_t x : side.touched) {
    side.dist[x] = kInfiniteCost;
    side.parent[x] = kNone;
    side.ways[x] = 0;
  }
  side.touched.clear();
  side.heap.clear();
}

void ChQuery::start(Side& side, std::uint32_t source) {
  aimed_ = false;
  clear(side);
  side.dist[source] = 0;
  side.ways[source] = 1;
  side.touched.push_back(source);
  side.heap.emplace_back(0, source);
}

template <bool kForward>
std::uint32_t ChQuery::settle_next(Side& side, Cost* d, bool* stalled) {
  const auto later = std::greater<std::pair<Cost, std::uint32_t>>();
  const auto& relax_begin = kForward ? ch_.up_begin_ : ch_.down_begin_;
  const auto& relax_edges = kForward ? ch_.up_ : ch_.down_;
  const auto& stall_begin = kForward ? ch_.down_begin_ : ch_.up_begin_;
  const auto& stall_edges = kForward ? ch_.down_ : ch_.up_;
  while (!side.heap.empty()) {
    std::pop_heap(side.heap.begin(), side.heap.end(), later);
    const auto [du, u] = side.heap.back();
    side.heap.pop_back();
    if (du != side.dist[u]) continue;
    ++settled_total_;
    *d = du;
    // Stall on demand: a higher node this side reached already leads to u more cheaply.
    *stalled = false;
    for (std::uint32_t e = stall_begin[u]; e < stall_begin[u + 1]; ++e) {
      const auto& edge = stall_edges[e];
      if (side.dist[edge.head] + edge.cost < du) {
        *stalled = true;
        return u;
      }
    }
    for (std::uint32_t e = relax_begin[u]; e < relax_begin[u + 1]; ++e) {
      const auto& edge = relax_edges[e];
      const Cost nd = du + edge.cost;
      Cost& old = side.dist[edge.head];
      const auto ways = static_cast<std::uint8_t>(std::min(2U, side.ways[u] * edge.ways()));
      if (nd < old) {
        if (old == kInfiniteCost) side.touched.push_back(edge.head);
        old = nd;
        side.parent[edge.head] = u;
        side.ways[edge.head] = ways;
        side.heap.emplace_back(nd, edge.head);
        std::push_heap(side.heap.begin(), side.heap.end(), later);
      } else if (nd == old) {
        side.ways[edge.head] = static_cast<std::uint8_t>(std::min(2, side.ways[edge.head] + ways));
      }
    }
    return u;
  }
  return kNone;
}

Cost ChQuery::meet(Node s, Node t, std::uint32_t* middle, std::uint32_t* ways) {
  assert(s < ch_.size() && t < ch_.size());
  start(forward_, ch_.rank_[s]);
  start(backward_, ch_.rank_[t]);
  Cost best = kInfiniteCost;
  *middle = kNone;
  for (;;) {
    const Cost f = forward_.heap.empty() ? kInfiniteCost : forward_.heap.front().first;
    const Cost b = backward_.heap.empty() ? kInfiniteCost : backward_.heap.front().first;
    // Neither side can reach a meeting point cheaper than the best found (counting ways: as
    // cheap, so that every node at the best distance or less is settled on both sides).
    if (forward_.heap.empty() && backward_.heap.empty()) break;
    if (ways == nullptr ? std::min(f, b) >= best : std::min(f, b) > best) break;
    Cost d = 0;
    bool stalled = false;
    const std::uint32_t u = f <= b ? settle_next<true>(forward_, &d, &stalled)
                                   : settle_next<false>(backward_, &d, &stalled);
    if (u == kNone) continue;
    const Cost via = forward_.dist[u] == kInfiniteCost || backward_.dist[u] == kInfiniteCost
                         ? kInfiniteCost
                         : forward_.dist[u] + backward_.dist[u];
    if (via < best) {
      best = via;
      *middle = u;
    }
  }
  if (ways != nullptr) {
    // Every shortest way has one up-down form (keep_ties), whose highest node is where the two
    // sides meet at the best distance.
    *ways = 0;
    for (std::uint32_t x : forward_.touched) {
      if (best != kInfiniteCost && backward_.dist[x] != kInfiniteCost &&
          forward_.dist[x] + backward_.dist[x] == best) {
        *ways = std::min(2U, *ways + std::uint32_t{forward_.ways[x]} * backward_.ways[x]);
      }
    }
  }
  return best;
}

Cost ChQuery::distance(Node s, Node t, bool* unique) {
  std::uint32_t middle = kNone;
  std::uint32_t ways = 0;
  const Cost d = meet(s, t, &middle, unique != nullptr ? &ways : nullptr);
  if (unique != nullptr) *unique = ways == 1;
  return d;
}

bool ContractionHierarchy::unpack(std::uint32_t tail, std::uint32_t head, std::uint32_t middle,
                                  std::vector<Node>& out,
                                  const std::function<bool(Node from, Node to)>* check) const {
  if (middle == kNoMiddle) {
    if (check != nullptr && !(*check)(node_[tail], node_[head])) return false;
    out.push_back(node_[head]);
    return true;
  }
  // The middle is contracted before both ends: tail -> middle is a down edge at it, middle ->
  // head an up edge.
  return unpack(tail, middle, find_down(middle, tail).middle(), out, check) &&
         unpack(middle, head, find_up(middle, head).middle(), out, check);
}

Cost ChQuery::path(Node s, Node t, std::vector<Node>& out, bool* unique) {
  out.clear();
  std::uint32_t middle = kNone;
  std::uint32_t ways = 0;
  const Cost best = meet(s, t, &middle, unique != nullptr ? &ways : nullptr);
  if (unique != nullptr) *unique = ways == 1;
  if (best == kInfiniteCost) return best;
  // The upward way s ... middle, then middle ... t downward.
  std::vector<std::uint32_t> up;
  for (std::uint32_t x = middle; x != kNone; x = forward_.parent[x]) up.push_back(x);
  std::reverse(up.begin(), up.end());
  out.push_back(s);
  for (std::size_t i = 1; i < up.size(); ++i) {
    ch_.unpack(up[i - 1], up[i], ch_.find_up(up[i - 1], up[i]).middle(), out);
  }
  for (std::uint32_t x = middle; backward_.parent[x] != kNone; x = backward_.parent[x]) {
    const std::uint32_t next = backward_.parent[x];
    ch_.unpack(x, next, ch_.find_down(next, x).middle(), out);
  }
  return best;
}

void ChQuery::table(std::span<const Node> sources, std::span<const Node> targets,
                    std::vector<Cost>& out, std::vector<bool>* unique) {
  fill_table(sources, targets, out, unique, nullptr);
}

void ChQuery::table_with_ways(std::span<const Node> sources, std::span<const Node> targets,
                              ChTable& out) {
  out = ChTable{};
  out.ch_ = &ch_;
  out.targets_ = targets.size();
  fill_table(sources, targets, out.dist_, nullptr, &out);
}

void ChQuery::fill_table(std::span<const Node> sources, std::span<const Node> targets,
                         std::vector<Cost>& out, std::vector<bool>* unique, ChTable* kept) {
  out.assign(sources.size() * targets.size(), kInfiniteCost);
  row_ways_.assign(targets.size(), 0);
  row_middle_.assign(targets.size(), kNone);
  buckets_.clear();
  for (std::uint32_t j = 0; j < targets.size(); ++j) {
    assert(targets[j] < ch_.size());
    start(backward_, ch_.rank_[targets[j]]);
    Cost d = 0;
    bool stalled = false;
    for (std::uint32_t u; (u = settle_next<false>(backward_, &d, &stalled)) != kNone;) {
      if (!stalled) buckets_.push_back({u, j, d, backward_.ways[u], backward_.parent[u]});
    }
  }
  std::sort(buckets_.begin(), buckets_.end(), [](const BucketEntry& a, const BucketEntry& b) {
    return a.node != b.node ? a.node < b.node : a.target < b.target;
  });
  for (std::uint32_t i = 0; i < buckets_.size(); ++i) {
    if (i == 0 || buckets_[i].node != buckets_[i - 1].node) {
      bucket_begin_[buckets_[i].node] = i + 1;
      bucket_nodes_.push_back(buckets_[i].node);
    }
  }
  if (kept != nullptr) {
    kept->down_.reserve(buckets_.size());
    for (const BucketEntry& b : buckets_) kept->down_.push_back({b.node, b.target, b.parent});
    kept->ways_.assign(out.size(), 0);
    kept->middle_.assign(out.size(), kNone);
    kept->tree_begin_.push_back(0);
  }
  for (std::size_t i = 0; i < sources.size(); ++i) {
    assert(sources[i] < ch_.size());
    start(forward_, ch_.rank_[sources[i]]);
    Cost* row = out.data() + i * targets.size();
    std::fill(row_ways_.begin(), row_ways_.end(), 0);
    Cost d = 0;
    bool stalled = false;
    for (std::uint32_t u; (u = settle_next<true>(forward_, &d, &stalled)) != kNone;) {
      if (stalled) continue;
      if (kept != nullptr) kept->up_.push_back({u, 0, forward_.parent[u]});
      if (bucket_begin_[u] == 0) continue;
      for (std::uint32_t e = bucket_begin_[u] - 1; e < buckets_.size() && buckets_[e].node == u;
           ++e) {
        const BucketEntry& entry = buckets_[e];
        const Cost via = d + entry.dist;
        const std::uint32_t ways = std::min(2U, forward_.ways[u] * entry.ways);
        if (via < row[entry.target]) {
          row[entry.target] = via;
          row_ways_[entry.target] = ways;
          row_middle_[entry.target] = u;
        } else if (via == row[entry.target]) {
          row_ways_[entry.target] = std::min(2U, row_ways_[entry.target] + ways);
        }
      }
    }
    if (unique != nullptr) {
      unique->resize(out.size());
      for (std::size_t j = 0; j < targets.size(); ++j) {
        (*unique)[i * targets.size() + j] = row_ways_[j] == 1;
      }
    }
    if (kept != nullptr) {
      for (std::size_t j = 0; j < targets.size(); ++j) {
        kept->ways_[i * targets.size() + j] = static_cast<std::uint8_t>(row_ways_[j]);
        kept->middle_[i * targets.size() + j] = row_middle_[j];
      }
      const auto begin = kept->up_.begin() + static_cast<std::ptrdiff_t>(kept->tree_begin_.back());
      std::sort(begin, kept->up_.end(),
                [](const ChTable::Parent& a, const ChTable::Parent& b) { return a.node < b.node; });
      kept->tree_begin_.push_back(kept->up_.size());
    }
  }
  for (std::uint32_t x : bucket_nodes_) bucket_begin_[x] = 0;
  bucket_nodes_.clear();
}

std::size_t ChTable::up_entry(std::size_t i, std::uint32_t node) const {
  const auto begin = up_.begin() + static_cast<std::ptrdiff_t>(tree_begin_[i]);
  const auto end = up_.begin() + static_cast<std::ptrdiff_t>(tree_begin_[i + 1]);
  const auto it = std::lower_bound(begin, end, node,
                                   [](const Parent& p, std::uint32_t n) { return p.node < n; });
  SEWER_CHECK(it != end && it->node == node, "a table's way leaves its source's search tree");
  return static_cast<std::size_t>(it - up_.begin());
}

std::size_t ChTable::down_entry(std::size_t j, std::uint32_t node) const {
  const auto it =
      std::lower_bound(down_.begin(), down_.end(), std::pair{node, j},
                       [](const Parent& p, const std::pair<std::uint32_t, std::size_t>& k) {
                         return p.node != k.first ? p.node < k.first : p.target < k.second;
                       });
  SEWER_CHECK(it != down_.end() && it->node == node && it->target == j,
              "a table's way leaves its target's search tree");
  return static_cast<std::size_t>(it - down_.begin());
}

std::uint32_t ChTable::up_parent(std::size_t i, std::uint32_t node) const {
  return up_[up_entry(i, node)].parent;
}

std::uint32_t ChTable::down_parent(std::size_t j, std::uint32_t node) const {
  return down_[down_entry(j, node)].parent;
}

std::span<const Node> ChTable::segment(bool up, std::size_t entry) const {
  std::vector<Segment>& segments = up ? up_segments_ : down_segments_;
  if (segments.empty()) segments.assign(up ? up_.size() : down_.size(), Segment{});
  Segment& seg = segments[entry];
  if (seg.size == Segment::kUnknown) {
    const Parent& p = up ? up_[entry] : down_[entry];
    const auto begin = segment_nodes_.size();
    // An up entry: the edge parent -> node; a down entry: node -> parent, toward the target.
    if (up) {
      ch_->unpack(p.parent, p.node, ch_->find_up(p.parent, p.node).middle(), segment_nodes_);
    } else {
      ch_->unpack(p.node, p.parent, ch_->find_down(p.parent, p.node).middle(), segment_nodes_);
    }
    seg.begin = begin;
    seg.size = static_cast<std::uint32_t>(segment_nodes_.size() - begin);
  }
  return {segment_nodes_.data() + seg.begin, seg.size};
}

bool ChTable::way(std::size_t i, std::size_t j, std::vector<Node>& out,
                  const std::function<bool(Node from, Node to)>* check) const {
  out.clear();
  if (distance(i, j) == kInfiniteCost) return true;
  const std::uint32_t middle = middle_[i * targets_ + j];
  // The tree edges from the source up to the meeting node, then down to the target, each
  // unpacked once per table (segment()): a source's ways to every target share its tree's
  // edges, a target's from every source its own (issue 35: unpacking every way whole was two
  // thirds of a first plan at 100,000 scrambled manholes, a cache miss per shortcut's half).
  std::vector<std::size_t>& up = way_entries_;
  up.clear();
  std::uint32_t root = middle;
  for (std::size_t e = up_entry(i, middle); up_[e].parent != kNone;
       e = up_entry(i, up_[e].parent)) {
    up.push_back(e);
    root = up_[e].parent;
  }
  out.push_back(ch_->node_[root]);
  const auto append = [&](std::span<const Node> nodes) {
    for (Node n : nodes) {
      if (check != nullptr && !(*check)(out.back(), n)) return false;
      out.push_back(n);
    }
    return true;
  };
  for (auto it = up.rbegin(); it != up.rend(); ++it) {
    if (!append(segment(true, *it))) return false;
  }
  for (std::size_t e = down_entry(j, middle); down_[e].parent != kNone;
       e = down_entry(j, down_[e].parent)) {
    if (!append(segment(false, e))) return false;
  }
  return true;
}

void ChQuery::aim_at(Node target) {
  assert(target < ch_.size());
  start(backward_, ch_.rank_[target]);
  clear(forward_);
  // The whole backward search space, unstalled: every node's distance down to the target.
  const auto later = std::greater<std::pair<Cost, std::uint32_t>>();
  while (!backward_.heap.empty()) {
    std::pop_heap(backward_.heap.begin(), backward_.heap.end(), later);
    const auto [du, u] = backward_.heap.back();
    backward_.heap.pop_back();
    if (du != backward_.dist[u]) continue;
    ++settled_total_;
    // Parents and ways as settle_next() keeps them, for way_to_aim(): at one distance the nodes
    // settle by rank and every edge climbs, so a node's ways are all counted before it is
    // expanded.
    for (std::uint32_t e = ch_.down_begin_[u]; e < ch_.down_begin_[u + 1]; ++e) {
      const auto& edge = ch_.down_[e];
      Cost& old = backward_.dist[edge.head];
      const auto ways = static_cast<std::uint8_t>(std::min(2U, backward_.ways[u] * edge.ways()));
      if (du + edge.cost < old) {
        if (old == kInfiniteCost) backward_.touched.push_back(edge.head);
        old = du + edge.cost;
        backward_.parent[edge.head] = u;
        backward_.ways[edge.head] = ways;
        backward_.heap.emplace_back(old, edge.head);
        std::push_heap(backward_.heap.begin(), backward_.heap.end(), later);
      } else if (du + edge.cost == old) {
        backward_.ways[edge.head] =
            static_cast<std::uint8_t>(std::min(2, backward_.ways[edge.head] + ways));
      }
    }
  }
  aimed_ = true;
}

Cost ChQuery::distance_to_aim(Node n) {
  SEWER_CHECK(aimed_, "a contraction hierarchy's guide asked without a target");
  assert(n < ch_.size());
  // forward_.dist by rank, one read per node (the nodes lie all over the map: each read is a
  // cache miss): kInfiniteCost not seen, kAimOpen, kAimNoWay, else known.
  constexpr Cost kOpen = kAimOpen;
  constexpr Cost kNoWay = kAimNoWay;
  const auto known = [&](std::uint32_t x) { return forward_.dist[x] < kOpen; };
  const std::uint32_t r = ch_.rank_[n];
  if (!known(r)) {
    // Depth first up the hierarchy: a node's distance is the best of its own down to the target
    // and, over its upward edges, the edge and the head's (every head is higher: no cycle, and no
    // head is open while a node above it on the stack is).
    aim_stack_.assign(1, r);
    while (!aim_stack_.empty()) {
      const std::uint32_t x = aim_stack_.back();
      Cost& d = forward_.dist[x];
      if (d < kOpen) {
        aim_stack_.pop_back();
        continue;
      }
      if (d == kInfiniteCost) {
        d = kOpen;
        forward_.touched.push_back(x);
        bool waits = false;
        for (std::uint32_t e = ch_.up_begin_[x]; e < ch_.up_begin_[x + 1]; ++e) {
          if (forward_.dist[ch_.up_[e].head] == kInfiniteCost) {
            aim_stack_.push_back(ch_.up_[e].head);
            waits = true;
          }
        }
        if (waits) continue;
      }
      Cost best = backward_.dist[x];
      for (std::uint32_t e = ch_.up_begin_[x]; e < ch_.up_begin_[x + 1]; ++e) {
        const auto& edge = ch_.up_[e];
        const Cost above = forward_.dist[edge.head];
        if (above != kNoWay) best = std::min(best, above + edge.cost);
      }
      d = best == kInfiniteCost ? kNoWay : best;
      aim_stack_.pop_back();
      ++settled_total_;
    }
  }
  return forward_.dist[r] == kNoWay ? kInfiniteCost : forward_.dist[r];
}

bool ChQuery::way_to_aim(Node n, std::vector<Node>& out,
                         const std::function<bool(Node from, Node to)>* check, Cost* cost) {
  SEWER_CHECK(aimed_, "a contraction hierarchy's way asked without a target");
  const Cost total = distance_to_aim(n);
  out.assign(1, n);
  if (total == kInfiniteCost) return false;
  *cost = total;
  // distance_to_aim(x) is the best over x's upward space of the way up to a node and down from
  // it to the target; every upward neighbour's is known once x's is. Up from n, at each node
  // exactly one choice must give its distance: to turn down here (the backward search's tree),
  // or one upward edge. Two would be two shortest ways (each has one up-down form, keep_ties).
  std::uint32_t r = ch_.rank_[n];
  for (;;) {
    const Cost here = forward_.dist[r];
    const bool down = backward_.dist[r] == here;
    std::size_t choices = down ? 1 : 0;
    std::uint32_t chosen = kNone;
    for (std::uint32_t e = ch_.up_begin_[r]; e < ch_.up_begin_[r + 1]; ++e) {
      const auto& edge = ch_.up_[e];
      const Cost above = forward_.dist[edge.head];
      if (above < kAimNoWay && above + edge.cost == here) {
        ++choices;
        chosen = e;
      }
    }
    if (choices != 1) return false;
    if (down) {
      if (backward_.ways[r] != 1) return false;
      break;
    }
    const auto& edge = ch_.up_[chosen];
    if (edge.ways() != 1 || !ch_.unpack(r, edge.head, edge.middle(), out, check)) return false;
    r = edge.head;
  }
  for (std::uint32_t x = r; backward_.parent[x] != kNone; x = backward_.parent[x]) {
    const std::uint32_t next = backward_.parent[x];
    if (!ch_.unpack(x, next, ch_.find_down(next, x).middle(), out, check)) return false;
  }
  return true;
}

}  // namespace sewerplan::domain::detail
