// SPDX-License-Identifier: MIT
// PDDL interoperability: a map and mission written as a PDDL domain and problem in the MAKRO
// paper's action vocabulary, and the plans FF and Fast Downward find for them read back.
//
// The export lets the planners the field trusts solve the same problem as sewerplan's own search
// (MAKRO called FF 2.3 on such files; Adria, Streich and Hertzberg 2004, sections 4.4 and 5).
// It is typed STRIPS, so FF 2.3 reads it; with `action_costs` it adds :action-costs (Fast
// Downward, Metric-FF) with each action's cost in milliseconds. PDDL cannot carry everything the
// native domain knows; what it leaves out is written as comments at the top of both files and in
// docs/pddl.md:
//   - positions inside a pipe: the robot is "in pipe P", not at an offset, so action costs are
//     those of driving whole pipes (an upper bound for a drive out of a pipe);
//   - the battery and its reserve (numbers): a plan the planners find may exceed it; the
//     validator says so;
//   - the mission's end at "any exit" and a final task's "done last" need two bookkeeping actions
//     that the robot never executes, REACH_EXIT and ALL_OTHER_TASKS_DONE; import drops them.
// The robot's limits (pipe diameters, turns, steps) and the mission's closures are compiled into
// static facts, so a plan that the planners find drives only where the native domain allows.
//
// Object names must be PDDL names (a letter, then letters, digits, '-' or '_'), unique ignoring
// case across manholes, pipes and tasks. Names that are not keep their spelling with a prefix
// ("p-" for pipes, "m-" manholes, "t-" tasks) and, if still taken, a number; the problem file
// lists each renamed object in a comment, and import maps the names back (PddlNames).
//
//   Result<PddlFiles> files = export_pddl(map, mission, {.action_costs = true});
//   // ... fast-downward.py --alias lama-first domain.pddl problem.pddl -> sas_plan
//   Result<Plan> plan = import_pddl_plan(sas_plan_text, "sas_plan", PddlPlanFormat::kFastDownward,
//                                        map, mission, diagnostics);
//
// Thread-safety: free functions over values they only read; reentrant.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/domain/robot_state.h"

namespace sewerplan::domain {

struct PddlOptions {
  // Adds :action-costs and (total-cost) with each action's cost in milliseconds. FF 2.3 does not
  // read it; Fast Downward and Metric-FF do.
  bool action_costs = false;
};

struct PddlFiles {
  std::string domain;
  std::string problem;
};

// The PDDL name of every manhole, pipe and task, and the way back (see the file comment).
class PddlNames {
 public:
  PddlNames(const SewerMap& map, const Mission& mission);

  const std::string& manhole(ManholeId id) const { return manholes_[id.index()]; }
  const std::string& pipe(PipeId id) const { return pipes_[id.index()]; }
  const std::string& task(TaskId id) const { return tasks_[id.index()]; }

  // The original name of the object a PDDL name denotes (any case), if any.
  std::optional<std::string> original(std::string_view pddl_name) const;
  // Objects whose PDDL name differs from their own, for the problem file's comment.
  std::size_t renamed_count() const { return renamed_; }

 private:
  std::string claim(const std::string& name, std::string_view prefix);

  std::vector<std::string> manholes_;
  std::vector<std::string> pipes_;
  std::vector<std::string> tasks_;
  // lower-case PDDL name -> original name
  std::unordered_map<std::string, std::string> back_;
  std::size_t renamed_ = 0;
};

// The domain and problem for `mission` on `map`, from `progress` (default: the mission's start,
// nothing done): done tasks are not goals, and the robot starts where `progress` says. The energy
// already used is not expressible (see above). Fails only for a progress that does not belong to
// the mission (kInvalidArgument).
Result<PddlFiles> export_pddl(const SewerMap& map, const Mission& mission,
                              const PddlOptions& options = {},
                              const std::optional<MissionProgress>& progress = std::nullopt);

enum class PddlPlanFormat {
  kFf,            // FF's standard output: "step    0: DRIVE_PIPE_TO_MANHOLE P12 M2", "1: ..."
  kFastDownward,  // sas_plan: "(drive_pipe_to_manhole p12 m2)" lines, "; cost = ..." comment
};

// "ff" or "fd".
std::optional<PddlPlanFormat> pddl_plan_format_from_name(std::string_view name);

// Reads a plan FF or Fast Downward found for export_pddl(map, mission): object names are mapped
// back, the bookkeeping actions dropped, and the rest read as parse_plan reads plan text. In FF's
// output only the step lines count (everything else is FF's log); if FF reports that no plan
// exists, that is the error. In a sas_plan file every line must be an action in parentheses or a
// ';' comment. Unknown action or object names are reported in `diagnostics` with their line
// ("sas_plan:3: unknown object 'p99' ..."), and then the result is a kParse error.
Result<Plan> import_pddl_plan(std::string_view text, const std::string& file_name,
                              PddlPlanFormat format, const SewerMap& map, const Mission& mission,
                              Diagnostics& diagnostics);

}  // namespace sewerplan::domain
