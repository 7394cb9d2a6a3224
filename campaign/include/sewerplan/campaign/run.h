// SPDX-License-Identifier: MIT
// One run of a fault campaign: a seeded simulated mission with random hidden faults, carried out
// three ways on the same faults.
//
// A run is fixed by the map, the mission, the fault rates, the campaign's seed and the run's index:
// run_seed() derives its own seed, random_faults() (hal/fault_scenario.h) draws the faults from it,
// and then
//   - ours: the Executor with the default Replanner (goal re-selection after every failure), as
//     `sewerplan simulate` runs it;
//   - the baseline: the same Executor with the paper-era Replanner policy
//     (ReplannerOptions::Goals::kPaperBaseline: after a failure, the same goal list without goal
//     selection, else the nearest exit);
//   - the oracle: one plan, with goal selection, from a mission that knows in advance every
//     obstacle no recovery can clear (executor::recovery_clears: permanent ones, and push-only ones
//     when pushing is not allowed; recovery clears each kind from both sides or from neither),
//     every danger spot and every dangerous passage. It is counted, not
//     driven: it has the whole battery, no malfunction and no detour, so its task count bounds what
//     any policy could do on the same faults (exactly so where the planner is optimal,
//     docs/campaign.md); and when it finds no way to end the mission, no policy could have reached
//     an exit.
// Everything in a RunResult but `measured` is the same on every machine for the same inputs.
//
//   RunResult r = *run_one(map, mission, {.rates = {}, .campaign_seed = 7}, 12);
//   std::cout << run_json_line(r) << '\n';
//
// Thread safety: Plain values and pure functions; run_one builds its own Replanner, Executor
// and simulated robot and only reads the map and mission, so runs may go on in parallel.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/campaign/world_score.h"
#include "sewerplan/core/map_discrepancy.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/world_errors.h"

namespace sewerplan::campaign {

// The fault rates of a campaign, as `--fault-rates` writes them:
// "obstacles=20,danger=5,passages=0.01,malfunctions=0.5,permanent=0.1,transient=0.5".
struct FaultRates {
  double obstacles_per_km = 20;  // obstacles per km of drivable pipe
  double danger_per_km = 5;      // danger spots per km of drivable pipe
  double passage_share = 0.01;   // share of passages between drivable pipes that are dangerous
  double malfunctions_per_hour = 0.5;
  double permanent_share = 0.1;  // of malfunctions
  double transient_share = 0.5;  // of obstacles (half cleared by lifting the head, half by pushing)
  friend bool operator==(const FaultRates&, const FaultRates&) = default;
};

// A named set of fault rates. Obstacle and danger rates are per kilometre of pipe the robot can
// drive (a Poisson count per pipe), so a robot meets that many on each kilometre it drives,
// whatever the network's size; passages are a share of the passages, malfunctions per hour of
// mission time (docs/campaign.md, "Fault-rate profiles", with the oracle's measured task share).
struct FaultRateProfile {
  std::string_view name;
  FaultRates rates;
  std::string_view meant_for;
};

inline constexpr std::array<FaultRateProfile, 4> kFaultRateProfiles{{
    {"default", FaultRates{}, "the AIS test bed's campaigns since issue 14"},
    {"realistic",
     FaultRates{.obstacles_per_km = 2,
                .danger_per_km = 0.5,
                .passage_share = 0.002,
                .malfunctions_per_hour = 0.25,
                .permanent_share = 0.05,
                .transient_share = 0.5},
     "a real sewer: the tour, most tasks still possible"},
    {"moderate",
     FaultRates{.obstacles_per_km = 40,
                .danger_per_km = 10,
                .passage_share = 0.05,
                .malfunctions_per_hour = 2,
                .permanent_share = 0.1,
                .transient_share = 0.5},
     "the way out, on large networks"},
    {"harsh",
     FaultRates{.obstacles_per_km = 80,
                .danger_per_km = 20,
                .passage_share = 0.1,
                .malfunctions_per_hour = 3,
                .permanent_share = 0.05,
                .transient_share = 0.5},
     "the way out: nearly every pipe holds a fault"},
}};

// The profile of that name, or none.
std::optional<FaultRates> fault_rate_profile(std::string_view name);

// Reads "[PROFILE,]name=value,..." (any subset; the others keep the profile's rates, or the
// defaults). An error names the bad item, or the unknown profile and the known ones.
Result<FaultRates> parse_fault_rates(std::string_view text);
std::string format_fault_rates(const FaultRates& rates);

struct RunSettings {
  FaultRates rates;
  std::uint64_t campaign_seed = 0;
  bool push_allowed = false;  // recovery phase 3 (executor/recovery.h)
  // The deadline of each plan of ours and the baseline (ReplannerOptions::planner.time_limit_s; 0:
  // none); not the oracle's. Measured on the wall clock, so a limit some plans reach makes runs
  // depend on the machine.
  double planner_time_limit_s = 0;
  // The bound on each plan's computed stranding risk of ours and the risk-aware execution
  // (search::PlannerOptions::max_strand_risk; 0: every contingency reserve kept); not the
  // oracle's or the baseline's, which keep none.
  double max_strand_risk = 0;
  // Hidden obstacles drawn from the inspection findings too (Mission::hazards): each possible
  // blockage becomes a permanent obstacle at its offset with its probability, on top of the
  // random faults of `rates` (docs/campaign.md, "Faults from condition data").
  bool faults_from_condition = false;
  // Risk-aware planning (domain::RiskCosts): when active, a fourth execution, the default
  // Replanner planning with these costs (RunResult::risk_aware), on the same faults.
  domain::RiskCosts risk;
  // The true world each run's robot drives (hal/world_errors.h), drawn from the run's seed; ours
  // and the baseline still plan on the map, the oracle on the true world. "none": the map.
  hal::WorldErrorProfile world_errors;
};

// The true world of run `index` (the map itself, as a copy, with no world errors).
Result<hal::TrueWorld> run_world(const SewerMap& map, const RunSettings& settings,
                                 std::size_t index);

// The run's own seed: splitmix64 of the campaign seed and the index.
std::uint64_t run_seed(std::uint64_t campaign_seed, std::size_t index);

// The hidden faults of run `index`.
Result<hal::FaultScenario> run_faults(const SewerMap& map, const Mission& mission,
                                      const RunSettings& settings, std::size_t index);

// How a mission ended, checked on the simulated robot's true pose.
enum class Outcome {
  kExit,      // in or at an exit manhole
  kEndPoint,  // at the mission's own end point (its final task, done)
  kBeacon,    // the robot called for recovery: beacon on
  kStranded,  // neither at an exit or the end point nor with the beacon on
};
std::string_view to_string(Outcome outcome);
std::optional<Outcome> outcome_from_string(std::string_view name);

struct Execution {
  std::size_t tasks = 0;  // tasks done
  Outcome outcome = Outcome::kExit;
  std::string end;  // the executor's words: "exit M4", or why the beacon is on
  bool reserve_kept = true;
  // The Replanner sent the robot out on its reserve (no exit above it: exit-on-reserve); a
  // reserve spent so is not a violation.
  bool exit_on_reserve = false;
  std::size_t replans = 0;
  // The first plan's computed stranding risk (search::PlanOutcome::strand_probability): the
  // chance, as planned at the start, of meeting a blockage without the battery kept to get out.
  double strand_risk = 0;
  double time_s = 0;  // mission time and energy, simulated (deterministic)
  double energy_wh = 0;
  bool disabled = false;  // a permanent malfunction struck
  // Why the beacon is on ("none" otherwise); "limit" must never happen.
  executor::MissionReport::BeaconCause beacon_cause = executor::MissionReport::BeaconCause::kNone;
  std::vector<double> planning_times_s;  // measured
  // How many of the mission's plans each rung of the anytime ladder answered, indexed by
  // executor::PlanResponse::Rung (the first plan and every replan).
  std::array<std::size_t, executor::PlanResponse::kRungCount> rungs{};
  // What the robot observed of the mission's hazards (Mission::hazards: condition data with
  // `--risk expected` or `--faults-from-condition`): the Replanner's beliefs at the end
  // (executor::Learnt::hazards), one per hazard it drove past or was stopped by, in the order first
  // met; the observations `sewerplan fit-risk` fits the risk table from (core/risk_fit.h).
  std::vector<executor::HazardBelief> hazards;
  // Ours only, with world errors (RunSettings::world_errors not "none"): its localisation and
  // measured map scored against the true world (world_score.h).
  std::optional<WorldScore> world;
  friend bool operator==(const Execution&, const Execution&) = default;
};

struct FaultCounts {
  std::size_t obstacles = 0;
  std::size_t permanent_obstacles = 0;
  std::size_t danger_spots = 0;
  std::size_t dangerous_passages = 0;
  std::size_t malfunctions = 0;
  std::size_t permanent_malfunctions = 0;
  friend bool operator==(const FaultCounts&, const FaultCounts&) = default;
};

struct RunResult {
  std::size_t index = 0;
  std::uint64_t seed = 0;
  std::size_t tasks = 0;  // in the mission
  FaultCounts faults;
  std::size_t oracle_tasks = 0;
  bool oracle_can_end = false;  // the oracle found a way to end the mission
  // The oracle can end the mission and no permanent malfunction stopped our robot: a run in which
  // the robot must end at an exit or the end point.
  bool could_reach_exit = false;
  Execution ours;
  Execution baseline;
  std::optional<Execution> risk_aware;  // with RunSettings::risk
  double wall_s = 0;                    // measured
  // How the run's true world differs from the map, in the map's terms (empty with no world
  // errors); written to runs.jsonl as "world", and read back.
  std::vector<Discrepancy> seeded;
  friend bool operator==(const RunResult&, const RunResult&) = default;
};

// Runs the three (with RunSettings::risk, four) executions of run `index`. Errors: the faults
// cannot be drawn (bad rates).
Result<RunResult> run_one(const SewerMap& map, const Mission& mission, const RunSettings& settings,
                          std::size_t index);

// The executions of a run that drive the simulated robot (the oracle is counted, not driven).
enum class Policy { kOurs, kBaseline, kRiskAware };
std::string_view to_string(Policy policy);  // "ours", "baseline", "risk_aware"
std::optional<Policy> policy_from_string(std::string_view name);
std::string policy_names();  // "ours, baseline, risk_aware": what policy_from_string reads

// What to see of an execution replayed: its events as the executor sends them (the lines of
// `simulate --log`), and each plan it follows.
struct ExecutionObservers {
  executor::EventObserver on_event;
  executor::Executor::PlanObserver on_plan;
};

// One execution of run `index` again, as run_one carries it out (the same faults, the same
// seeded robot, the same policy), seen by `observers`: a campaign run's event log without storing
// every log. Its result equals the run's record but for the measured planning times (unless a
// planner time limit made the run depend on the machine, RunSettings::planner_time_limit_s).
// Errors: bad rates; kRiskAware without RunSettings::risk.
Result<Execution> replay_execution(const SewerMap& map, const Mission& mission,
                                   const RunSettings& settings, std::size_t index, Policy policy,
                                   const ExecutionObservers& observers);

}  // namespace sewerplan::campaign
