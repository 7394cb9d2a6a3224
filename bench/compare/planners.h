// SPDX-License-Identifier: MIT
// The planners the comparison runs on one instance: sewerplan itself (as a child process of this
// program, so that its memory is measured alone), FF on the STRIPS export and Fast Downward on the
// export with action costs. Every plan is read back and checked by sewerplan's validator.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"

#include "subprocess.h"

namespace sewerplan::compare {

// One instance on disk: map.json and mission.json in `directory`, and loaded.
struct Instance {
  std::string name;
  std::size_t manholes = 0;
  std::size_t tasks = 0;
  std::string seed;  // "-" for a dataset
  std::filesystem::path directory;
  SewerMap map;
  Mission mission;
};

struct Outcome {
  std::string planner;
  std::string status;  // solved, no plan, timeout, crashed, failed, invalid plan, ...
  double wall_s = 0;   // the whole process
  std::optional<double> load_and_plan_s;  // sewerplan's own figure, inside its process
  std::optional<double> cost_s;           // by sewerplan's validator
  std::optional<std::size_t> steps;
  double peak_mb = 0;
  std::string detail;  // why it failed, in a few words
  bool solved() const { return status == "solved"; }
};

struct PlannerPaths {
  std::string self;  // this program, for sewerplan's runs
  std::string ff;
  std::string fd;
  std::string fd_alias = "lama-first";
};

Outcome run_sewerplan(const Instance& instance, const PlannerPaths& paths, const RunLimits& limits);
Outcome run_ff(const Instance& instance, const PlannerPaths& paths, const RunLimits& limits);
Outcome run_fd(const Instance& instance, const PlannerPaths& paths, const RunLimits& limits);

// The child side of run_sewerplan: loads, plans and writes the plan; prints
// "load_and_plan_s cost_s" on success, the planner's error as plan --json does ({"error": {"code",
// "message"}}) on failure. Returns the sewerplan CLI's exit codes (0, 4 no plan, 5 search limit,
// 1 invalid input).
int native_child(const std::string& map, const std::string& mission, const std::string& plan_out,
                 double time_limit_s);

}  // namespace sewerplan::compare
