// SPDX-License-Identifier: MIT
// JoinedSearch: a guided search toward a target that stops where the rest of its way is the
// routing index's own, as the compile runs it (GraphSearch::run_toward with rest_known,
// ChQuery::way_to_aim), and the whole way and cost it then found, for tests to compare with the
// plain search's.
//
//   JoinedSearch joined(graph, index);
//   index.aim_at(t);
//   const JoinedSearch::Way way = joined.run(search, source, t, bound, guide);
//   if (way.result == GraphSearch::Toward::kUnique) EXPECT_EQ(way.path, want_path);
#pragma once

#include <functional>
#include <vector>

#include "contraction_hierarchy.h"
#include "graph_search.h"
#include "position_graph.h"

namespace sewerplan::domain::detail {

class JoinedSearch {
 public:
  // Both must outlive this object, which refers to itself (not to be copied or moved).
  JoinedSearch(const PositionGraph& graph, ChQuery& index)
      : graph_(graph),
        reads_([this](Node from, Node to) { return graph_.reads_move(from, to); }),
        rest_known_([this, &index](Node n) {
          return !graph_.is_extra_spot(n) && index.way_to_aim(n, rest_, &reads_, &rest_cost_);
        }) {}
  JoinedSearch(const JoinedSearch&) = delete;
  JoinedSearch& operator=(const JoinedSearch&) = delete;

  struct Way {
    GraphSearch::Toward result = GraphSearch::Toward::kUnreached;
    bool joined = false;        // the search stopped where the index's way is the rest
    std::vector<Node> path;     // when joined or kUnique
    Cost cost = kInfiniteCost;  // likewise
  };

  // The index aimed at `target` beforehand (ChQuery::aim_at). Not on profiles with free passages
  // (GraphCore::free_passages): there the search runs without the rest, as the compile does.
  template <class Guide>
  Way run(GraphSearch& search, Node source, Node target, Cost bound, const Guide& guide) {
    Way way;
    way.result = search.run_toward(source, target, bound, graph_.size(), guide,
                                   graph_.core().free_passages ? nullptr : &rest_known_);
    if (const std::optional<Node> at = search.joined()) {
      way.joined = true;
      search.path(*at, way.path);
      way.path.insert(way.path.end(), rest_.begin() + 1, rest_.end());
      way.cost = search.distance(*at) + rest_cost_;
    } else if (way.result == GraphSearch::Toward::kUnique) {
      search.path(target, way.path);
      way.cost = search.distance(target);
    }
    return way;
  }

 private:
  const PositionGraph& graph_;
  std::vector<Node> rest_;
  Cost rest_cost_ = 0;
  const std::function<bool(Node, Node)> reads_;
  const std::function<bool(Node)> rest_known_;
};

}  // namespace sewerplan::domain::detail
