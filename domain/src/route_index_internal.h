// SPDX-License-Identifier: MIT
// What a RouteIndex holds (route_index.h), and the fingerprint of the graph it is built over:
// private to domain, shared by route_index.cc and the compile that adopts an index (compile.cc).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "sewerplan/domain/route_index.h"

#include "contraction_hierarchy.h"
#include "position_graph.h"

namespace sewerplan::domain {

struct RouteIndex::Impl {
  std::shared_ptr<const detail::ContractionHierarchy> hierarchy;
  RouteIndexStatistics statistics;
  std::string source;
};

namespace detail {

// FNV-1a 64 over the core's adjacency (GraphCore::adjacency_begin, _to, _cost), each value as its
// little-endian bytes (docs/formats/route-index.md, "Fingerprint"). Precondition: the core has
// its adjacency (PositionGraph::build_adjacency). Runtime: O(nodes + moves).
std::uint64_t adjacency_fingerprint(const GraphCore& core);

}  // namespace detail
}  // namespace sewerplan::domain
