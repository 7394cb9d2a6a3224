// SPDX-License-Identifier: MIT
// Events: what happened during a mission, one plain value per kind, as the Executor delivers them.
//
// The Executor (executor.h) calls its observers with every event, in order, on run()'s thread:
// a plan or replan, each action and job, a robot's error, a recovery stage tried, a failure told
// to the Replanner, a task done or dropped, a way out on the battery reserve, a manhole arrival
// checked against the plan, a hazard's probability learnt, the beacon, and the mission's end. Each
// `Event` is the mission time `t_s` (the robot's clock) and one of these structs; switch on it with
// std::visit. Names (of tasks, pipes, manholes) are the map's and the mission's, so an event means
// the same without them: the JSON-lines log (event_json.h) and the readable live log (event_text.h)
// are consumers, and a JSON-lines log reads back into the same events.
//
//   executor.subscribe([&](const Event& e) {
//     if (const auto* done = std::get_if<TaskDoneEvent>(&e.what)) show(done->task, e.t_s);
//   });
//
// Thread safety: events are plain values; an observer runs on the thread that calls run().
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "sewerplan/executor/recovery.h"
#include "sewerplan/executor/replanner.h"
#include "sewerplan/hal/robot.h"

namespace sewerplan::executor {

// How a mission ended: "ended" (the plan was carried out: at an exit, or at the mission's end
// point), "beacon" (no way out: the beacon is on), "halted" (Executor::halt(): the robot was
// stopped where it is, the beacon is off).
enum class MissionOutcome { kEnded, kBeacon, kHalted };

// Why the beacon is on, for counting (campaigns show that no limit ever strands a robot).
enum class BeaconCause {
  kNone,         // "none": not on
  kNoExit,       // "no-exit": a search proved that no exit can be reached
  kStuck,        // "stuck": the robot cannot move (recovery left it stuck, a danger in a manhole)
  kMalfunction,  // "malfunction": a permanent malfunction, a reboot that failed
  kLink,         // "link": the link to the robot failed (CAN)
  kLimit,        // "limit": a bound of the executor (max_replans) or a plan that did not validate
};

// The stable names above, and back (empty for any other text).
std::string_view to_string(MissionOutcome outcome);
std::optional<MissionOutcome> parse_mission_outcome(std::string_view name);
std::string_view to_string(BeaconCause cause);
std::optional<BeaconCause> parse_beacon_cause(std::string_view name);

// "plan" (the first) or "replan": the Replanner's answer.
struct PlanEvent {
  bool replan = false;
  std::string
      reason;  // why it was made ("start", "blockage in P5 at 4.00 m"), or why there is none
  double planning_ms = 0;
  PlanResponse::Decision decision = PlanResponse::Decision::kFollowPlan;
  std::vector<std::string> goals;    // the tasks the plan does
  std::vector<std::string> dropped;  // tasks newly dropped
  std::string end;                   // "exit M4", "pipe P9 (final task 'end')"
  std::size_t steps = 0;
  double cost_s = 0;
  // Which answer of the anytime ladder it is (PlanResponse::Rung); written when not "search",
  // so logs of plans the search made read as before.
  PlanResponse::Rung rung = PlanResponse::Rung::kSearch;
  // PlanResponse::strand_probability; logged only when above 0 ("strand_probability").
  double strand_probability = 0;
  friend bool operator==(const PlanEvent&, const PlanEvent&) = default;
};

// "action": a fused action about to run.
struct ActionEvent {
  std::string step;  // the plan step, in the paper's text
  std::string kind;  // fusion::action_kind: "drive_to_manhole", "pass_manhole", ...
  double duration_s = 0;
  std::string parameters;  // the action with its parameters, as fusion prints it
  friend bool operator==(const ActionEvent&, const ActionEvent&) = default;
};

// "job": a job the robot ran, and how far it got.
struct JobEvent {
  std::string job;  // "DriveForward(0.30 m/s, 2.83 m)"
  double progress_m = 0;
  bool ok = true;
  friend bool operator==(const JobEvent&, const JobEvent&) = default;
};

// "error": the robot's error for the job before it.
struct ErrorEvent {
  hal::RobotErrorKind kind = hal::RobotErrorKind::kMalfunction;
  std::string reason;  // the robot's words
  std::string where;   // where the executor's dead reckoning puts the robot
  friend bool operator==(const ErrorEvent&, const ErrorEvent&) = default;
};

// "recovery": a stage of staged recovery tried, and whether it worked.
struct RecoveryEvent {
  RecoveryPhase phase = RecoveryPhase::kReboot;
  bool ok = false;
  friend bool operator==(const RecoveryEvent&, const RecoveryEvent&) = default;
};

// "failure": what the Replanner is told, by the map's names.
struct FailureEvent {
  struct InPipe {  // a blockage or a danger spot
    std::string pipe;
    double offset_m = 0;
    friend bool operator==(const InPipe&, const InPipe&) = default;
  };
  struct Passage {  // a dangerous passage, slots numbered from 1 as in the paper
    std::string manhole;
    int from_slot = 1;
    int to_slot = 1;
    friend bool operator==(const Passage&, const Passage&) = default;
  };
  Failure::Kind kind = Failure::Kind::kStuck;
  std::variant<std::monostate, InPipe, Passage> where;  // nothing for kStuck
  std::string detail;                                   // the robot's words
  friend bool operator==(const FailureEvent&, const FailureEvent&) = default;
};

// "task_done"
struct TaskDoneEvent {
  std::string task;
  friend bool operator==(const TaskDoneEvent&, const TaskDoneEvent&) = default;
};

// "task_dropped"
struct TaskDroppedEvent {
  std::string task;
  std::string reason;
  friend bool operator==(const TaskDroppedEvent&, const TaskDroppedEvent&) = default;
};

// "reserve": the Replanner sends the robot out on its battery reserve (kExitOnReserve): a
// search proved that no exit can be reached above the reserve, and `end` can be reached on the
// charge left. Right after the plan or replan event of that answer.
struct ReserveEvent {
  std::string end;        // the exit it heads for: "exit M4"
  double energy_wh = 0;   // what the way out needs
  double left_wh = 0;     // the charge the robot reports left
  double reserve_wh = 0;  // the operator's reserve (Mission::battery_reserve_fraction)
  friend bool operator==(const ReserveEvent&, const ReserveEvent&) = default;
};

// "arrival": the robot stopped at a manhole, or at what it took for one, and the controller
// checked its place against the plan's (manhole verification, docs/localisation.md). Logged for
// every arrival the robot observed (hal::JobReport::observation) and for every one that does not
// match; a robot that observes nothing (the exact simulated world) logs none.
struct ArrivalEvent {
  std::string expected;  // where the plan has the robot: "M6 slot 2"; empty: in a pipe
  // The check's outcome (localisation::Verification): "matches", "wrong-manhole",
  // "unmapped-junction", "missed-manhole", "false-detection", "signature-differs".
  std::string check;
  double probability = 0;  // that the robot is where the plan has it
  std::string believed;    // the most likely place: "at M7 slot 1 (P9)"; empty: lost
  std::string manhole;     // the manhole of that place ("M7"); empty: none on the map
  std::string observed;    // the signature seen: "4 slots at 0, 92, 181, 268°"; empty: none
  std::string reason;      // why it does not match; empty when it does
  friend bool operator==(const ArrivalEvent&, const ArrivalEvent&) = default;
};

// "hazard": what the robot observed of a hazard of the condition data changed its probability
// (Replanner::observe_pass, observe_stop, report_failure; docs/executor.md, "Probabilities that
// learn"). A pass: right after the job that drove past it (finished, or stopped further on); a
// blockage met: before the replan it causes.
struct HazardEvent {
  enum class Observed {
    kPassed,   // "passed": driven past safely, the probability lowered by a Bayesian update
    kBlocked,  // "blocked": met as a blockage, now certain
  };
  std::string pipe;
  double offset_m = 0;
  std::string reason;  // the finding: "BBA roots"
  Observed observed = Observed::kPassed;
  double probability_before = 0;
  double probability = 0;  // after
  std::size_t passes = 0;  // safe passes observed so far
  friend bool operator==(const HazardEvent&, const HazardEvent&) = default;
};

// "passed", "blocked", and back (empty for any other text).
std::string_view to_string(HazardEvent::Observed observed);
std::optional<HazardEvent::Observed> parse_hazard_observed(std::string_view name);

// "beacon": asked for, and whether the robot confirmed it (hal::BeaconState).
struct BeaconEvent {
  std::string reason;
  hal::BeaconState state = hal::BeaconState::kConfirmed;
  friend bool operator==(const BeaconEvent&, const BeaconEvent&) = default;
};

// "mission_end": always the last event of a run.
struct MissionEndEvent {
  MissionOutcome outcome = MissionOutcome::kEnded;
  std::string end;  // "exit M4", why the beacon is on, or where the robot was halted
  std::vector<std::string> tasks_done;
  double energy_wh = 0;
  std::size_t replans = 0;
  PlanResponse::Decision decision = PlanResponse::Decision::kFollowPlan;  // the Replanner's last
  BeaconCause beacon_cause = BeaconCause::kNone;
  hal::BeaconState beacon = hal::BeaconState::kNone;  // written when not kNone
  friend bool operator==(const MissionEndEvent&, const MissionEndEvent&) = default;
};

struct Event {
  double t_s = 0;  // mission time, the robot's clock
  std::variant<PlanEvent, ActionEvent, JobEvent, ErrorEvent, RecoveryEvent, FailureEvent,
               TaskDoneEvent, TaskDroppedEvent, ReserveEvent, ArrivalEvent, HazardEvent,
               BeaconEvent, MissionEndEvent>
      what;
  friend bool operator==(const Event&, const Event&) = default;
};

// The event's type as the log names it: "plan", "replan", "action", "job", "error", "recovery",
// "failure", "task_done", "task_dropped", "reserve", "arrival", "hazard", "beacon", "mission_end".
std::string_view type_name(const Event& event);

// Called with every event of a run, in order, on run()'s thread.
using EventObserver = std::function<void(const Event&)>;

}  // namespace sewerplan::executor
