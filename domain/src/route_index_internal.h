// SPDX-License-Identifier: MIT
// What a RouteIndex holds (route_index.h), and the fingerprint of the graph it is built over:
// private to domain, shared by route_index.cc and the compile that adopts an index (compile.cc).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "sewerplan/domain/route_index.h"

#include "contraction_hierarchy.h"
#include "position_graph.h"

namespace sewerplan::domain {

struct RouteIndex::Impl {
  std::shared_ptr<const detail::ContractionHierarchy> hierarchy;
  RouteIndexStatistics statistics;
  std::string source;

  // Takes `ch` as the hierarchy, with its counts in `statistics` (the fingerprint aside).
  void hold(detail::ContractionHierarchy ch);
};

namespace detail {

// The moves of `map` for this robot and motion table as a compile's searches read them: a core
// with its adjacency built (PositionGraph::build_adjacency) from `core` if it serves them (else a
// new one), or null if `stop` fired first.
std::shared_ptr<GraphCore> core_with_adjacency(std::shared_ptr<GraphCore> core, const SewerMap& map,
                                               const RobotProfile& profile,
                                               std::shared_ptr<const PassageMotionTable> motion,
                                               const StopCondition& stop);

// FNV-1a 64 over the core's adjacency (GraphCore::adjacency_begin, _to, _cost), each value as its
// little-endian bytes (docs/formats/route-index.md, "Fingerprint"). Precondition: the core has
// its adjacency (PositionGraph::build_adjacency). Runtime: O(nodes + moves).
std::uint64_t adjacency_fingerprint(const GraphCore& core);

// The file's checksum (offset 56) over the bytes after its header: eight FNV-1a 64 hashes, lane
// k over the bytes k, k + 8, k + 16, ..., then FNV-1a 64 over the eight lanes' values (8 bytes
// each, little-endian). Runtime: O(bytes).
std::uint64_t file_checksum(std::string_view bytes);

}  // namespace detail
}  // namespace sewerplan::domain
