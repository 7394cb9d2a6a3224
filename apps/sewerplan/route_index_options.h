// SPDX-License-Identifier: MIT
// The routing-index options of `plan` and `simulate`: --route-index FILE and --no-route-index.
//
// By default a command uses the index kept beside the map (MAP.route-index.bin, written by
// `sewerplan index build`) when there is one, and says so on standard error. The plans are the
// same with or without it, so one beside the map that is stale (of another map, robot, motion
// table or --condition) is said so on standard error, with the command that remakes it, and
// the command plans without it; a broken file, or a stale one named by --route-index, is an
// error (docs/formats/route-index.md). A stale motion table is always an error: it changes plans.
#pragma once

#include <optional>
#include <ostream>
#include <string>

#include "sewerplan/core/result.h"
#include "sewerplan/domain/route_index.h"

namespace CLI {
class App;
}

namespace sewerplan::cli {

struct RouteIndexOptions {
  std::string path;  // empty: the default beside the map, if it exists
  bool none = false;
};

void add_route_index_options(CLI::App& cmd, RouteIndexOptions& options);

// The index to use (saying so on `err`), none when there is none; or the error, not printed (a
// broken file: kParse, kUnsupportedFormat or kIo). `use` hands it to the planner (a
// CompileCache's or a Replanner's use_route_index): its error (a stale index) comes back as
// invalid input (kInvalidMap), with how to do without it.
template <class Use>
Result<void> attach_route_index(const RouteIndexOptions& options, const std::string& map_path,
                                std::ostream& err, Use&& use);

// The loading half of attach_route_index.
Result<std::optional<domain::RouteIndex>> load_route_index(const RouteIndexOptions& options,
                                                           const std::string& map_path);

template <class Use>
Result<void> attach_route_index(const RouteIndexOptions& options, const std::string& map_path,
                                std::ostream& err, Use&& use) {
  Result<std::optional<domain::RouteIndex>> index = load_route_index(options, map_path);
  if (!index.has_value()) return index.error();
  if (!*index) return Result<void>{};
  if (Result<void> used = use(**index); !used.has_value()) {
    Error error = used.error();
    if (error.code == ErrorCode::kInvalidArgument && options.path.empty()) {
      err << "index: " << error.message << "; planning without it\n";
      return Result<void>{};
    }
    // An index of another map or profile is invalid input (exit code 1), not a usage error.
    if (error.code == ErrorCode::kInvalidArgument) error.code = ErrorCode::kInvalidMap;
    error.message += "\n(use --no-route-index to plan without it)";
    return error;
  }
  err << "index: using the routing index " << (*index)->source() << " ("
      << (*index)->statistics().nodes << " positions)\n";
  return Result<void>{};
}

}  // namespace sewerplan::cli
