// SPDX-License-Identifier: MIT
// Replanner: the planning system that robot software embeds (the paper's sections 4.5 to 4.7).
//
// It holds the map, the mission and what the robot has reported, and answers with a fused plan
// (fusion/fuse.h: actions with every parameter resolved) or with the decision to call for
// recovery. When the robot meets trouble that its own recovery could not clear, the Replanner
// changes its world model: a blocked pipe cannot be passed at the obstacle (so it is disconnected
// between its manholes, but the robot can back out), a dangerous spot likewise, a dangerous
// passage is closed. Then it replans from where the robot really is, with goal selection: the
// most tasks that can still be done with the battery left, and still reaching an exit. If the
// mission's end point (its final task) is cut off, the mission ends at the nearest reachable exit
// instead. The answer is anytime: when the time limit or a cancel stops the search first, it is the
// first safe rung of a ladder (PlanResponse::Rung, issue 34): the best plan the search had; the
// rest of the current plan if it still holds (the robot is at a state it passed through, and what
// was learnt since and the battery left do not break the rest; kFollowPlan, as it does every task
// it did); the current plan's tasks repaired onto new routes; a greedy insertion; and only then the
// nearest reachable exit (kDegraded). Each is validated as a plan is. The battery reserve is
// the last way out, not a wall: when a search proved that no exit can be reached above the
// reserve, the answer is the nearest exit the robot can reach on the charge it has left
// (kExitOnReserve, every task left dropped). The beacon (kCallForRecovery) is only the answer when
// a search proved that not even that exit can be reached, or the robot cannot move (kStuck); a
// limit never calls it. Tasks done stay done; tasks dropped stay
// dropped, each with its reason. Probabilities learn (issue 34): a hazard of the condition data
// (Mission::hazards) the robot drives past safely (observe_pass) has its blockage probability
// lowered by a Bayesian update, one it meets as a blockage (report_failure) becomes certain; the
// Replanner keeps these in what it learnt (Learnt::hazards), so every replan after weighs them.
//
//   Replanner replanner(map, mission);
//   PlanResponse r = replanner.plan();
//   // ... execute r.fused; on progress:  replanner.update(progress, heading_end);
//   // ... after a drive in pipe p from 0 to 12.5 m that was not stopped:
//   replanner.observe_pass(p, 0.0, 12.5);  // the hazards passed are less likely to block
//   // ... after a drive stopped at 7.5 m: the hazards behind the stop were passed
//   replanner.observe_stop(p, 0.0, 7.5);
//   // ... on a blockage recovery could not clear:
//   r = replanner.report_failure({.kind = Failure::Kind::kBlockage, .pipe = p5, .offset_m = 4.0});
//   if (calls_beacon(r.decision)) robot.activate_beacon();
//
// Thread safety: A Replanner is not thread-safe: one thread at a time (BackgroundReplan,
// background_replan.h, lends it to a thread of its own); the SewerMap it holds may be shared with
// other readers. The free functions share nothing. Cancel from another thread through
// ReplannerOptions::planner.cancel or BackgroundReplan::cancel().
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/domain/robot_state.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/executor/learnt.h"
#include "sewerplan/fusion/fuse.h"
#include "sewerplan/hal/robot.h"
#include "sewerplan/search/planner.h"

namespace sewerplan::executor {

// What the robot met that its own recovery could not clear.
struct Failure {
  enum class Kind {
    kBlockage,          // an obstacle in `pipe` at `offset_m`
    kDangerInPipe,      // a spot in `pipe` at `offset_m` the robot must not drive onto
    kDangerousPassage,  // passing `manhole` from slot `from` to slot `to`
    kStuck,             // the robot cannot move any more (a permanent malfunction)
  };
  Kind kind = Kind::kBlockage;
  PipeId pipe{0};
  double offset_m = 0;
  ManholeId manhole{0};
  SlotIndex from{0};
  SlotIndex to{0};
  std::string detail{};  // the robot's own words: for people, never read to decide
  // What stopped the robot, as it typed it (hal::RobotErrorCause): for kStuck, whether it failed
  // itself (kFault, kBatteryEmpty, a reboot that failed), its link did (kLink), or something held
  // it. Empty when the failure is the executor's own finding (the plan and the robot disagree).
  std::optional<hal::RobotErrorCause> cause{};
};

// The stable name of a failure kind ("blockage", "danger", "dangerous passage", "stuck") and
// back; parse_failure_kind is empty for any other text.
std::string_view to_string(Failure::Kind kind);
std::optional<Failure::Kind> parse_failure_kind(std::string_view name);

// A hazard's probability changed by what the robot observed (observe_pass, report_failure).
struct HazardUpdate {
  HazardBelief belief;  // after: pipe, offset, reason, probability, passes, blocked
  double probability_before = 0;
  friend bool operator==(const HazardUpdate&, const HazardUpdate&) = default;
};

struct PlanResponse {
  // What the caller does with the answer; switch on it. The names (to_string, parse_decision)
  // are stable: the event log and every CLI --json output carry them.
  enum class Decision {
    kFollowPlan,     // "follow-plan": carry out `fused` (empty when the mission is already ended);
                     // also when the time ran out and the rest of the current plan still holds
                     // (`reason` says so): it does every task the robot was doing
    kDegraded,       // "degraded": carry out `fused`; it does less than asked (tasks dropped,
                     // the end point given up, or the time ran out and it heads for an exit)
    kExitOnReserve,  // "exit-on-reserve": carry out `fused`: a search proved that no exit can
                     // be reached above the battery reserve, so it heads for the nearest exit
                     // the robot can reach on what is left, into the reserve; every task left
                     // is dropped. Every later plan of the mission is on the reserve too.
    kCallForRecovery,  // "call-for-recovery": a search proved that no exit can be reached, not
                       // even on the battery reserve: activate the beacon and wait
    kStuck,            // "stuck": the robot cannot move: activate the beacon and wait
    kInvalidReport,    // "invalid-report": the report was rejected (`reason` says why) and the
                       // world model is unchanged; the robot's last plan stands
  };
  Decision decision = Decision::kFollowPlan;
  // Which answer of the anytime ladder this is (ReplannerOptions, docs/executor.md); the names
  // (to_string) are stable, for the event log and the campaigns to count. kSearch: the planner
  // finished (or proved there is no plan); the others answer when the time limit, a cancel or a
  // planner error stopped it first, each only if its plan is valid on the world model as it is now
  // and ends the mission within the battery left above the reserve:
  enum class Rung {
    kSearch,        // "search"
    kBestSoFar,     // "best-so-far": the best plan the planner had when its time ran out
    kCurrentPlan,   // "current-plan": the rest of the current plan, replayed: it still holds
    kRepairedPlan,  // "repaired-plan": the current plan's tasks left, in its order, on new routes,
                    // those that became impossible or no longer fit the battery dropped
    kGreedy,        // "greedy": the cheapest insertion of the tasks left from the robot's place
    kNearestExit,   // "nearest-exit": every task left dropped, the nearest reachable exit
  };
  static constexpr std::size_t kRungCount = 6;  // for counts indexed by Rung
  Rung rung = Rung::kSearch;
  domain::Plan plan;
  fusion::FusedPlan fused;
  std::vector<TaskId> goals;                       // the tasks the plan does
  std::vector<domain::DroppedTask> newly_dropped;  // left out by this planning
  std::string end;     // where the plan ends: "exit M4", "pipe P9 (final task 'end')"
  std::string reason;  // why this plan was made ("start", "blockage in P5 at 4.00 m"), or why
                       // there is none
  double planning_time_s = 0;
  double cost_s = 0;
  double energy_wh = 0;
  // What the report this answers taught about the hazards (report_failure: the hazard a blockage
  // was met at, now certain); empty for plan().
  std::vector<HazardUpdate> hazard_updates;
  // The plan's computed stranding risk (search::PlanOutcome::strand_probability; 0 for an answer
  // not from the planner: the rest of the current plan, or none).
  double strand_probability = 0;
};

// Whether a failure report can be applied to `map`: known pipe, manhole and slots, a finite offset
// within the pipe, two different slots of a dangerous passage. The error names what is wrong.
Result<void> check_failure(const Failure& failure, const SewerMap& map);
// Whether a progress report fits `map` and `mission`: a known place (a finite offset within its
// pipe), one done flag per task, a finite energy of at least 0, a heading end of 0 or 1.
Result<void> check_progress(const domain::MissionProgress& progress, std::uint8_t heading_end,
                            const SewerMap& map, const Mission& mission);

// The stable name of a decision ("follow-plan", "degraded", "exit-on-reserve",
// "call-for-recovery", "stuck", "invalid-report") and back; parse_decision is empty for any other
// text.
std::string_view to_string(PlanResponse::Decision decision);
std::optional<PlanResponse::Decision> parse_decision(std::string_view name);
// The stable name of a rung ("search", "best-so-far", "current-plan", "repaired-plan", "greedy",
// "nearest-exit") and back; parse_rung is empty for any other text.
std::string_view to_string(PlanResponse::Rung rung);
std::optional<PlanResponse::Rung> parse_rung(std::string_view name);
// kFollowPlan, kDegraded and kExitOnReserve: there is a plan to carry out.
bool has_plan(PlanResponse::Decision decision);
// kCallForRecovery and kStuck: the robot switches its locator beacon on.
bool calls_beacon(PlanResponse::Decision decision);

struct ReplannerOptions {
  // Goal selection is always on. The robot waits while it replans, so by default there is no
  // improvement search after the first plan (for a task beyond exhaustive A*, the tour search's
  // plan: bench/executor/replan_bench.cc); give it expansions to trade time for cost.
  // `planner.time_limit_s` (0: none) is the deadline of each plan() and report_failure() as a
  // whole, and `planner.cancel` cuts it short: either way the answer is the first safe one of an
  // anytime ladder (PlanResponse::Rung): the best plan the planner had by then (kBestSoFar); the
  // rest of the current plan if it still holds (kCurrentPlan, kFollowPlan; a replay, no search);
  // the current plan's tasks left in its order on new routes, those that cannot be done dropped
  // (kRepairedPlan); the cheapest insertion of the tasks left (kGreedy); the nearest reachable exit
  // (kNearestExit, kDegraded). Each is checked as a plan is (valid on the world model as it is
  // now, ending the mission within the battery left above the reserve), or the next is tried. The
  // last three each take one compile that the limit does not bound (a cancel does, but for the
  // nearest exit), and are deterministic: they may overshoot the deadline by that compile
  // (bench/executor/deadline_bench.cc). The paper-era baseline (kPaperBaseline) skips the
  // repaired plan and the greedy insertion: its answer past a limit stays the nearest exit.
  // `planner.risk` (domain::RiskCosts, default none) makes every plan and replan risk-aware
  // where the mission has hazards (Mission::hazards: plan --risk expected, docs/planning.md):
  // routes and task orders weigh the expected cost of a possible blockage, more on the way back
  // to the exit. The safe answer (the nearest reachable exit) stays risk-blind: the shortest way.
  search::PlannerOptions planner{.improvement_expansions = 0};
  // Used to time the planning (default: a steady clock).
  const Clock* clock = nullptr;
  // What a failure does to the goals. kReselect (the default, the paper's section 4.7): plan again
  // with goal selection. kPaperBaseline, the paper-era behaviour that fault campaigns compare
  // against (docs/campaign.md): the first plan selects its goals as kReselect does; after a failure
  // (or a low battery) the same goal list is planned again without goal selection, and if that
  // fails, every task left is dropped and the robot goes to the nearest exit of the map. The
  // baseline keeps its reserve as a wall: it never answers kExitOnReserve.
  enum class Goals { kReselect, kPaperBaseline };
  Goals goals = Goals::kReselect;
  // How hazards learn (HazardBelief, docs/executor.md "Probabilities that learn"):
  // `prior_strength` k is how many observations the risk table's probability weighs as (a safe
  // pass takes p to p (k + n) / (k + n + 1) after n passes; 0: one pass proves the place open;
  // infinity: nothing learns); a blockage reported within `blockage_match_m` of a hazard in the
  // same pipe (the nearest, if several) is that hazard met: it becomes certain.
  struct HazardLearning {
    double prior_strength = kDefaultHazardPriorStrength;
    double blockage_match_m = 1.0;
  };
  HazardLearning hazard_learning{};
};

class Replanner {
 public:
  Replanner(const SewerMap& map, Mission mission, ReplannerOptions options = {});

  // A plan from progress() (at first: the mission's start).
  PlanResponse plan(const std::string& reason = "start");

  // Where the robot is, what it has done and the energy it has used; `heading_end` is the end of
  // its pipe its front points to (0 or 1) when it is in a pipe. A report that check_progress
  // rejects is an error, and the progress stays as it was.
  Result<void> update(const domain::MissionProgress& progress, std::uint8_t heading_end);

  // Changes the world model for `failure` and plans again from progress(). A report that
  // check_failure rejects changes nothing: the answer is kInvalidReport, its reason the error.
  // A new plan identical to the one that just failed would fail the same way: the task it heads
  // for first is dropped instead (the robot cannot get there), and the answer is kDegraded.
  PlanResponse report_failure(const Failure& failure);

  // The robot drove pipe `pipe` from offset `from_m` to `to_m` (either way) and was not stopped:
  // every hazard of the mission strictly between the two (as the planner counts a hazard passed,
  // domain/route_risk.h) and not met as a blockage is observed open once, and its probability
  // lowered (HazardBelief). An unknown pipe or an offset outside it is an error, and nothing
  // changes. Returns the updates, in the order of driving.
  Result<std::vector<HazardUpdate>> observe_pass(PipeId pipe, double from_m, double to_m);

  // The robot drove pipe `pipe` from offset `from_m` towards `stop_m` and was stopped at `stop_m`
  // (a blockage, a danger, a malfunction: a job it did not finish): the hazards it went past
  // before the stop were not blocked. Each hazard strictly between the two, as observe_pass, but
  // for one within hazard_learning.blockage_match_m of the stop: that may be what stopped the
  // robot (report_failure matches a blockage to it within that distance), and the dead reckoning
  // knows the stop no better. Errors and updates as observe_pass. Without it the hazards behind a
  // stop were never counted passed, and what the robot learnt (and the risk fits made from it)
  // over-counted blockages against passes.
  Result<std::vector<HazardUpdate>> observe_stop(PipeId pipe, double from_m, double stop_m);

  // The robot drove pipe `pipe` from offset `from_m` to `to_m` (either way): a blockage learnt
  // strictly between the two (more than kDroveThroughMarginM inside: a failure reported there, or
  // one an earlier mission learnt) is not there any more (an obstacle that has gone, or a failure
  // placed where the robot was not) and leaves the world model; the operator's closures and the
  // danger spots stay. The next plan's reason names each one dropped. Errors as observe_pass.
  // Returns the blockages dropped. Without it, a robot found past a transient obstacle it had
  // reported (on the meshed network, realistic world, seed 2, run 30) was shut in behind it and
  // called for recovery with an exit 5 m away.
  Result<std::vector<Blockage>> drove_through(PipeId pipe, double from_m, double to_m);
  static constexpr double kDroveThroughMarginM = 0.05;

  // A blockage (`kind` kBlockage) or danger spot (kDangerInPipe) learnt at `from` (a failure
  // reported there) was truly at `to`: it
  // was placed under a belief a later arrival refuted (a robot that drove through a manhole unseen
  // met an obstacle in the pipe beyond, and it was closed in the pipe before; the robot, backing
  // out, arrived at that manhole from the pipe it was really in). It moves, in the world model
  // and in learnt(); the next plan's reason says so, `why` its words. False (nothing changes)
  // when nothing was learnt at `from`, or `to` is not a place on the map. Without it, the
  // closure shut the robot's way on (the meshed network, realistic world, seed 26, run 5).
  bool move_learnt(Failure::Kind kind, const Blockage& from, const Blockage& to,
                   const std::string& why);

  // Adds what an earlier mission learnt (learnt.h) to the world model, for the next plan; an
  // entry that check_failure, check_hazard_belief or localisation::check_memory would reject is
  // an error, and nothing is added. A belief about a hazard already learnt replaces it; a junction
  // memory that is not empty replaces the one kept (the filter's memory at a mission's end holds
  // what it started from: the Executor hands it over so).
  Result<void> learn(const Learnt& learnt);

  // Issue 35: plans and replans take their routes from `index`, the map's routing index for the
  // mission's robot and motion table made beforehand (domain/route_index.h), instead of building
  // one; a stale index is refused (kInvalidArgument: domain::CompileCache::use_route_index).
  Result<void> use_route_index(domain::RouteIndex index);
  // What this Replanner has learnt: learn()'s and every failure reported since.
  const Learnt& learnt() const { return learnt_; }

  // The mission as the Replanner now sees it: the operator's with what was learnt
  // (with_learnt), and without its final task once the end point was cut off.
  const Mission& mission() const { return mission_; }
  const domain::MissionProgress& progress() const { return progress_; }

  // report_failure(*failure), or plan(reason) without one, cancelled by `cancel` (from any
  // thread): then kCancelled, without the safe fallback, and the world model keeps what the
  // report taught. What BackgroundReplan (background_replan.h) runs on its thread.
  Result<PlanResponse> plan_cancellable(const std::optional<Failure>& failure,
                                        const std::string& reason, const std::atomic<bool>& cancel);
  const std::vector<domain::DroppedTask>& dropped() const { return dropped_; }
  std::uint8_t heading_end() const { return heading_end_; }
  // The share of the battery the operator's mission keeps in reserve. Once the robot heads out on
  // the reserve (on_reserve(), kExitOnReserve), mission() plans with none, so this is where the
  // operator's share stays.
  double reserve_fraction() const { return reserve_fraction_; }
  bool on_reserve() const { return on_reserve_; }

 private:
  const Clock& clock() const;
  std::vector<ManholeId> map_exits() const;
  // The planner's options, with a time limit to `deadline_s` (infinite: none).
  search::PlannerOptions bounded(double deadline_s) const;
  Result<search::PlanOutcome> plan_from_here(double deadline_s);
  Result<search::PlanOutcome> baseline_from_here(double deadline_s);
  // The safe answer: the nearest exit the robot can reach, every task left dropped for `why`.
  // One optimal search over the robot's places, without a time limit or a cancel.
  Result<search::PlanOutcome> exit_from_here(const std::string& why);
  // The last way out, after a search proved that no exit can be reached above the reserve
  // (`why`, the planner's words): the nearest exit on the charge left, the reserve included,
  // every task left dropped. kNoPlan when not even that exit can be reached, when the robot is
  // already on the reserve, when the mission keeps none, or for the paper-era baseline.
  Result<search::PlanOutcome> exit_on_reserve(const std::string& why);
  // The rest of the plan answered last, from where the robot is now, if it still holds: the
  // robot's place and tasks done are a state that plan passed through, and the steps after it
  // replay on the world model as it is now (with what was learnt since) to the mission's end
  // within the battery left. One replay of each: no search.
  std::optional<search::PlanOutcome> rest_of_current_plan() const;
  // Rungs kRepairedPlan and kGreedy, for when the planner stopped (`why`): the first whose plan
  // is safe(), its tasks left out dropped for `why`; empty if neither.
  std::optional<search::PlanOutcome> quick_answer(const std::string& why, PlanResponse::Rung& rung);
  // The tasks the last plan answered still had to do, in its order.
  std::vector<TaskId> tasks_of_current_plan() const;
  // Whether `outcome`'s plan, from progress() with the tasks dropped so far and those it drops
  // counted as done, is valid on the world model as it is now and ends the mission within the
  // battery left above the reserve; its validation report if so.
  std::optional<domain::ValidationReport> safe(const search::PlanOutcome& outcome) const;
  // The first task `plan` does from progress(), if any.
  std::optional<TaskId> first_task_of(const domain::Plan& plan) const;
  PlanResponse respond(search::PlanOutcome outcome, const std::string& reason, double seconds);
  // Records what was observed of mission_.hazards[h]: a safe pass or (`blocked`) a blockage met
  // there, in the mission and in what was learnt.
  HazardUpdate observe_hazard(std::size_t h, bool blocked);
  // observe_pass and observe_stop: the hazards between `from_m` and `to_m` farther than
  // `margin_m` from `to_m` observed open.
  Result<std::vector<HazardUpdate>> observe_driven(PipeId pipe, double from_m, double to_m,
                                                   double margin_m);

  const SewerMap& map_;
  Mission mission_;
  ReplannerOptions options_;
  SteadyClock steady_;
  domain::MissionProgress progress_;
  std::uint8_t heading_end_ = 1;
  std::vector<domain::DroppedTask> dropped_;
  Learnt learnt_;
  // What drove_through() dropped since the last plan, for that plan's reason.
  std::string dropped_note_;
  // During plan_cancellable: its cancel flag, and whether it stopped the replan.
  const std::atomic<bool>* background_cancel_ = nullptr;
  bool cancelled_ = false;
  bool planned_ = false;  // a first plan was made
  // The operator's battery reserve, and whether the robot is heading out on it (then
  // mission_.battery_reserve_fraction is 0).
  double reserve_fraction_ = 0;
  bool on_reserve_ = false;
  // The steps of the last plan answered: after a failure, the plan that failed.
  std::vector<domain::PlanStep> last_steps_;
  // Where that plan began (the tasks dropped by then counted as done); empty when the last answer
  // had no plan.
  std::optional<domain::MissionProgress> last_start_;
  // Kept across its plans (issue 16: a replan need not rebuild the map's indices); shared by
  // copies, which is safe (domain::CompileCache is thread-safe).
  std::shared_ptr<domain::CompileCache> compile_cache_ = std::make_shared<domain::CompileCache>();
};

}  // namespace sewerplan::executor
