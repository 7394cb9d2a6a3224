// SPDX-License-Identifier: MIT
// The motion-table options of `plan` and `simulate`: --motion FILE and --no-motion.
//
// By default a command uses the table kept beside the map (MAP.motion.json, written by
// `sewerplan motion precompute`) when there is one, and says so on standard error; a stale or
// broken table is an error rather than silently ignored (docs/motion.md).
#pragma once

#include <ostream>
#include <string>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace CLI {
class App;
}

namespace sewerplan::cli {

struct MotionOptions {
  std::string path;  // empty: the default beside the map, if it exists
  bool none = false;
};

void add_motion_options(CLI::App& cmd, MotionOptions& options);

// Attaches the table to the mission (saying so on `err`): the path used, empty when none is; or
// the error, not printed (a stale or broken table: kInvalidMap and the like, or kIo).
Result<std::string> attach_motion_table(const MotionOptions& options, const std::string& map_path,
                                        const SewerMap& map, Mission& mission, std::ostream& err);

// Attaches the table to the mission. Returns kExitOk, or the exit code after printing the error.
// `used_path`, when given, receives the table's path (empty when none is used).
int attach_motion(const MotionOptions& options, const std::string& map_path, const SewerMap& map,
                  Mission& mission, std::ostream& err, std::string* used_path = nullptr);

}  // namespace sewerplan::cli
