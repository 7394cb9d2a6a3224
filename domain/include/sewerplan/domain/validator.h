// SPDX-License-Identifier: MIT
// The plan validator: replays a plan on the map and the mission, step by step, as docs/domain.md
// defines the sewer domain, and says whether it is executable, reaches the goal, and what it costs.
//
// It is written from the specification alone, independently of the planner (its compiled task and
// search), so that each checks the other: every plan the planner returns must validate, with the
// cost the planner claims. PlanReplay is the step-by-step form, for the executor (which replays
// what it has done) and for the brute-force oracle of the tests (tests/support/brute_force.h);
// validate_plan replays a whole plan into a ValidationReport. Plans come from the planner or from
// text (plan_text.h).
//
//   ValidationReport report = validate_plan(plan, map, mission);
//   if (!report.valid) std::cerr << report.error << '\n';  // "step 11 (INSPECT_PIPE P4): ..."
//
//   PlanReplay replay(map, mission, initial_progress(mission, map));
//   Result<double> cost_s = replay.apply(DrivePipeToManhole{p12, m2});
//
// Numbers: costs in seconds, energy in Wh. Turns and steps are compared with a 1e-9 tolerance, the
// battery with 1e-9 Wh; nothing else is rounded, so the same plan always gives the same cost bits.
//
// Thread-safety: free functions over values they only read; reentrant.
#pragma once

#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/domain/robot_state.h"

namespace sewerplan::domain {

// What is wrong with a start, if anything: IDs outside the map, an offset outside its pipe, a
// `done` list that does not match the mission's tasks, negative or non-finite energy. A start in a
// pipe the robot cannot drive is not wrong here: every action in that pipe then fails.
std::optional<std::string> start_problem(const SewerMap& map, const Mission& mission,
                                         const MissionProgress& start);

// A plan being replayed: the robot's position, the tasks done, the time and energy so far.
// Copyable and cheap to copy (the map and the mission are referenced, and must outlive it).
class PlanReplay {
 public:
  // Precondition: start_problem(map, mission, start) is empty (checked).
  PlanReplay(const SewerMap& map, const Mission& mission, MissionProgress start);

  // Checks `step` against the current state; if it is executable, applies it and returns its
  // cost in seconds. Otherwise a kInvalidArgument Error says what is wrong, naming the objects and
  // the limit ("pipe P7 is closed"), and the state is unchanged. Runtime: O(tasks) for a task
  // action or a closed-passage check, else O(1) plus O(closed pipes).
  Result<double> apply(const PlanStep& step);

  const RobotPosition& position() const { return progress_.position; }
  const std::vector<bool>& done() const { return progress_.done; }
  // Precondition: `task` is the mission's (checked).
  bool done(TaskId task) const;
  // Time and energy of the steps applied, not counting the start's energy already used.
  double elapsed_s() const { return elapsed_s_; }
  double energy_wh() const;
  // True once the mission's final task has been done by an action: no step may follow.
  bool finished() const { return finished_; }
  // Empty when the goal of docs/domain.md holds; else the first thing missing, e.g.
  // "task 'inspect' (inspect_pipe) is not done" or "the robot is not at an exit (exits: M1, M10)".
  std::optional<std::string> unmet_goal() const;
  // The state as a start for another plan: energy used is the start's plus energy_wh().
  MissionProgress progress() const;

 private:
  struct Transition {
    double cost_s = 0;
    RobotPosition next;
    std::optional<TaskId> task_done;
  };
  Result<Transition> transition(const PlanStep& step) const;
  Result<Transition> drive_pipe_to_manhole(const DrivePipeToManhole& s) const;
  Result<Transition> drive_manhole(const DriveManhole& s) const;
  Result<Transition> enter_pipe(const EnterPipe& s) const;
  Result<Transition> take_water_sample(const TakeWaterSample& s) const;
  Result<Transition> inspect_pipe(const InspectPipe& s) const;
  Result<Transition> go_to_point(const GoToPoint& s) const;
  Result<Transition> go_to_manhole(const GoToManhole& s) const;
  // The robot's offset in `pipe`, if it is in it and may drive there.
  Result<double> offset_in(PipeId pipe) const;
  // "pipe P5 is blocked at 12.30 m" if a blockage lies between the two offsets.
  std::optional<Error> blocked_between(PipeId pipe, double from, double to) const;
  // `task`, if it is a pending task of `kind` that may be done now; `place` names the action's
  // pipe or manhole, and `at_place` says whether the task is there.
  Result<const Task*> pending_task(TaskId task, TaskKind kind, bool at_place,
                                   const std::string& place) const;
  std::optional<std::string> passage_problem(ManholeId m, SlotIndex from, SlotIndex to) const;
  // Why the robot cannot be in `pipe` at all (its diameter), or cannot enter it (also closed).
  std::optional<std::string> does_not_fit(PipeId pipe) const;
  std::optional<std::string> undrivable(PipeId pipe) const;
  Error invalid(std::string message) const;

  const SewerMap* map_;
  const Mission* mission_;
  MissionProgress progress_;  // energy_used_wh stays the start's
  double elapsed_s_ = 0;
  bool finished_ = false;
};

struct ValidationReport {
  bool valid = false;
  // The first step that cannot be executed (from 0); empty when the steps are fine and the goal is
  // not reached, or when the start is wrong.
  std::optional<std::size_t> failed_step;
  // Why the plan is invalid: "step 11 (INSPECT_PIPE P4): the robot is at M5 slot 4 (P4), not in
  // pipe P4", "goal not reached: task 'inspect' (inspect_pipe) is not done", or "invalid start:
  // ...". Empty when valid.
  std::string error;
  std::vector<double> step_costs_s;  // of the steps executed
  double total_cost_s = 0;           // their sum, in plan order
  double energy_wh = 0;              // of the steps executed
  MissionProgress end;               // after the steps executed
};

// "valid: 14 steps, 585.4 s, 19.5 Wh" or "invalid: " and the error.
std::ostream& operator<<(std::ostream& os, const ValidationReport& report);

// Replays `plan` from `start`, stopping at the first step that cannot be executed, then checks the
// goal. Runtime: O(steps x tasks).
ValidationReport validate_plan(const Plan& plan, const SewerMap& map, const Mission& mission,
                               const MissionProgress& start);
// From the mission's start: initial_progress(mission, map).
ValidationReport validate_plan(const Plan& plan, const SewerMap& map, const Mission& mission);

}  // namespace sewerplan::domain
