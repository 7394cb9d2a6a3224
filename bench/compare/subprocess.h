// SPDX-License-Identifier: MIT
// Running an external planner as a child process under a time limit and a memory cap, and
// measuring its wall time and peak memory.
//
// The child gets its own process group, so that a planner that starts helpers (Fast Downward's
// driver runs the translator and the search as processes) is stopped as a whole at the time
// limit. The memory cap is RLIMIT_AS, inherited by every process the child starts; peak memory is
// the largest resident set of the child and of its descendants that it waited for (wait4).
//
//   RunResult r = run_process({"/opt/ff/ff", "-o", "domain.pddl", "-f", "problem.pddl"},
//                             {.time_limit_s = 60, .memory_limit_mb = 8192,
//                              .stdout_path = "ff.out", .directory = "work/"});
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace sewerplan::compare {

struct RunLimits {
  double time_limit_s = 60;
  std::size_t memory_limit_mb = 8192;  // 0: none
  std::string stdout_path;             // empty: /dev/null
  std::string stderr_path;             // empty: /dev/null
  std::string directory;               // working directory; empty: the caller's
};

struct RunResult {
  bool started = false;    // false: the program could not be run (see `error`)
  bool timed_out = false;  // killed at the time limit
  int exit_code = -1;      // when it exited normally
  int signal = 0;          // when a signal ended it (also SIGKILL at the time limit)
  double wall_s = 0;
  double peak_mb = 0;
  std::string error;
};

RunResult run_process(const std::vector<std::string>& argv, const RunLimits& limits);

}  // namespace sewerplan::compare
