// SPDX-License-Identifier: MIT
#include "route_store.h"

#include <algorithm>

namespace sewerplan::domain::detail {

void RouteStore::reserve_rows(std::size_t keys) {
  const std::size_t wanted = nodes_.size() * (keys + keys / 2) + 4096;
  nodes_.reserve(std::min(wanted, std::max(kMaxReservedNodes, nodes_.size())));
}

RouteRef RouteStore::keep(const GraphSearch& search, Node n) {
  const std::size_t begin = nodes_.size();
  search.append_path(n, nodes_);
  return {begin, nodes_.size() - begin};
}

RouteRef RouteStore::keep(std::span<const Node> route) {
  const std::size_t begin = nodes_.size();
  nodes_.insert(nodes_.end(), route.begin(), route.end());
  return {begin, route.size()};
}

RouteRef RouteStore::keep(Node first, std::span<const Node> rest) {
  const std::size_t begin = nodes_.size();
  nodes_.push_back(first);
  nodes_.insert(nodes_.end(), rest.begin(), rest.end());
  return {begin, rest.size() + 1};
}

}  // namespace sewerplan::domain::detail
