// SPDX-License-Identifier: MIT
#include "route_index_options.h"

#include <filesystem>

#include <CLI/CLI.hpp>

namespace sewerplan::cli {

void add_route_index_options(CLI::App& cmd, RouteIndexOptions& options) {
  cmd.add_option("--route-index", options.path,
                 "Routing index to take the routes from (default: MAP.route-index.bin beside the "
                 "map, if it exists; see 'sewerplan index build')");
  cmd.add_flag("--no-route-index", options.none, "Ignore the routing index kept beside the map");
}

Result<std::optional<domain::RouteIndex>> load_route_index(const RouteIndexOptions& options,
                                                           const std::string& map_path) {
  if (options.none) return std::optional<domain::RouteIndex>();
  std::filesystem::path path = options.path;
  if (path.empty()) {
    path = domain::default_route_index_path(map_path);
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return std::optional<domain::RouteIndex>();
  }
  Result<domain::RouteIndex> index = domain::RouteIndex::load(path);
  if (!index.has_value()) {
    Error error = index.error();
    if (error.code != ErrorCode::kIo)
      error.message += "\n(use --no-route-index to plan without it)";
    return error;
  }
  return std::optional<domain::RouteIndex>(std::move(*index));
}

}  // namespace sewerplan::cli
