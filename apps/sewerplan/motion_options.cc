// SPDX-License-Identifier: MIT
#include "motion_options.h"

#include <filesystem>
#include <memory>

#include <CLI/CLI.hpp>

#include "sewerplan/core/passage_motion.h"

#include "command.h"

namespace sewerplan::cli {

void add_motion_options(CLI::App& cmd, MotionOptions& options) {
  cmd.add_option("--motion", options.path,
                 "Planned manhole passages to use (default: MAP.motion.json beside the map, if "
                 "it exists; see 'sewerplan motion precompute')");
  cmd.add_flag("--no-motion", options.none,
               "Ignore planned manhole passages: use the angle and step rules");
}

Result<std::string> attach_motion_table(const MotionOptions& options, const std::string& map_path,
                                        const SewerMap& map, Mission& mission, std::ostream& err) {
  if (options.none) return std::string();
  std::filesystem::path path = options.path;
  if (path.empty()) {
    path = default_motion_path(map_path);
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return std::string();
  }
  Result<PassageMotionTable> table = load_passage_motion(path, map, mission.profile);
  if (!table.has_value()) {
    Error error = table.error();
    // A table for another map or profile is invalid input (exit code 1), not a usage error.
    if (error.code == ErrorCode::kInvalidArgument) error.code = ErrorCode::kInvalidMap;
    error.message += "\n(use --no-motion to plan with the angle and step rules)";
    return error;
  }
  std::size_t infeasible = 0;
  for (const PassageMotion& p : table->entries()) infeasible += p.feasible ? 0U : 1U;
  err << "motion: using " << table->size() << " planned manhole passages from " << path.string()
      << " (" << infeasible << " infeasible)\n";
  mission.passage_motion = std::make_shared<const PassageMotionTable>(std::move(*table));
  return path.string();
}

int attach_motion(const MotionOptions& options, const std::string& map_path, const SewerMap& map,
                  Mission& mission, std::ostream& err, std::string* used_path) {
  if (used_path != nullptr) used_path->clear();
  Result<std::string> used = attach_motion_table(options, map_path, map, mission, err);
  if (!used.has_value()) {
    err << used.error().message << '\n';
    return used.error().code == ErrorCode::kIo ? kExitIo : kExitInvalidInput;
  }
  if (used_path != nullptr) *used_path = *used;
  return kExitOk;
}

}  // namespace sewerplan::cli
