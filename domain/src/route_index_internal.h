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
};

namespace detail {

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
