// SPDX-License-Identifier: MIT
// One campaign run: faults, the oracle, ours and the baseline (run.h).
#include "sewerplan/campaign/run.h"

#include <algorithm>
#include <charconv>
#include <chrono>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/enum_names.h"
#include "sewerplan/core/rng.h"
#include "sewerplan/domain/robot_state.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/executor/recovery_clears.h"
#include "sewerplan/executor/replanner.h"
#include "sewerplan/hal/sim_robot.h"

namespace sewerplan::campaign {
namespace {

// The names the campaign's files and --json outputs carry (run.h).
constexpr detail::EnumNames<Outcome, 4> kOutcomes{{
    {Outcome::kExit, "exit"},
    {Outcome::kEndPoint, "end_point"},
    {Outcome::kBeacon, "beacon"},
    {Outcome::kStranded, "stranded"},
}};

constexpr detail::EnumNames<Policy, 3> kPolicies{{
    {Policy::kOurs, "ours"},
    {Policy::kBaseline, "baseline"},
    {Policy::kRiskAware, "risk_aware"},
}};

static_assert(detail::distinct(kOutcomes) && detail::distinct(kPolicies));

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

// The simulated robot starts where the mission puts it; in a pipe it faces the pipe's ends[1], as
// fusion assumes (fusion/fuse.h).
hal::SimPose start_pose(const domain::RobotPosition& p) {
  if (const auto* in = std::get_if<domain::InManhole>(&p)) return hal::InManhole{in->manhole};
  if (const auto* at = std::get_if<domain::AtSlot>(&p)) return hal::AtSlot{at->manhole, at->slot};
  const auto& pipe = std::get<domain::InPipe>(p);
  return hal::InPipe{pipe.pipe, pipe.offset_m, hal::Heading::kTowardsEnd1};
}

std::optional<ManholeId> manhole_of(const hal::SimPose& pose) {
  if (const auto* in = std::get_if<hal::InManhole>(&pose)) return in->manhole;
  if (const auto* at = std::get_if<hal::AtSlot>(&pose)) return at->manhole;
  return std::nullopt;
}

// Whether a permanent malfunction struck the robot during its mission.
bool disabled(const hal::FaultScenario& faults, const hal::SimRobot& robot) {
  return std::any_of(faults.malfunctions.begin(), faults.malfunctions.end(),
                     [&](const hal::Malfunction& m) {
                       if (m.kind != hal::MalfunctionKind::kPermanent) return false;
                       if (const auto* job = std::get_if<hal::AtJob>(&m.when)) {
                         return job->index < robot.jobs_executed();
                       }
                       return std::get<hal::AtTime>(m.when).time_s <= robot.status().elapsed_s;
                     });
}

// The staged recovery of ours and the baseline.
executor::RecoveryProfile recovery_of(const RunSettings& settings) {
  executor::RecoveryProfile recovery;
  recovery.push_allowed = settings.push_allowed;
  return recovery;
}

// The oracle plans without knowing which way the robot will meet each obstacle, so it presumes
// that recovery clears an obstacle from both sides or from neither. hal's table says so for every
// kind (a push works both ways since issue 30: before, a push-only obstacle met while backing
// stayed, and a second oracle plan had to judge the way out). A one-sided row makes this fail:
// then the oracle must learn which way each obstacle is met.
constexpr bool cleared_from_both_sides_or_neither() {
  for (const hal::ObstacleClearing& row : hal::kObstacleClearing) {
    if (hal::clears_from(row.kind, hal::Approach::kFront) !=
        hal::clears_from(row.kind, hal::Approach::kRear)) {
      return false;
    }
  }
  return true;
}
static_assert(cleared_from_both_sides_or_neither(),
              "the oracle presumes every obstacle clears from both sides or neither");

// The mission as the oracle knows it: every fault no recovery clears, in advance. Which
// obstacles those are is the recovery's own answer (executor::recovery_clears, from hal's table),
// so the oracle and the action controller agree on every obstacle, met either way.
Mission clairvoyant(const Mission& mission, const hal::FaultScenario& faults,
                    const executor::RecoveryProfile& recovery) {
  Mission known = mission;
  for (const hal::Obstacle& o : faults.obstacles) {
    if (!executor::recovery_clears(recovery, o.kind, hal::Approach::kFront)) {
      known.blockages.push_back({o.pipe, o.offset_m});
    }
  }
  for (const hal::DangerSpot& d : faults.danger_spots)
    known.blockages.push_back({d.pipe, d.offset_m});
  for (const hal::DangerousPassage& p : faults.dangerous_passages) {
    known.closed_passages.push_back({p.manhole, p.from_slot, p.to_slot});
  }
  return known;
}

// The mission in the true world's terms (its places in pipes moved with hal::world_spot), for the
// oracle, which plans on the world.
Mission in_world(const SewerMap& map, const hal::TrueWorld& truth, Mission mission) {
  if (truth.seeded.empty()) return mission;
  const auto move = [&](PipeSpot& spot) {
    if (!spot.offset_m) return;
    const hal::WorldSpot w = hal::world_spot(map, truth, spot.pipe, *spot.offset_m);
    spot.pipe = w.pipe;
    spot.offset_m = w.offset_m;
  };
  if (auto* spot = std::get_if<PipeSpot>(&mission.start)) move(*spot);
  for (Task& t : mission.tasks) {
    if (auto* spot = std::get_if<PipeSpot>(&t.place)) move(*spot);
  }
  for (Blockage& b : mission.blockages) {
    const hal::WorldSpot w = hal::world_spot(map, truth, b.pipe, b.offset_m);
    b = {w.pipe, w.offset_m};
  }
  for (Hazard& h : mission.hazards) {
    const hal::WorldSpot w = hal::world_spot(map, truth, h.pipe, h.offset_m);
    h.pipe = w.pipe;
    h.offset_m = w.offset_m;
  }
  std::erase_if(mission.closed_passages, [&](const ClosedPassage& c) {
    const std::size_t n = truth.world.manhole(c.manhole).slot_count;
    return c.from.index() >= n || c.to.index() >= n;
  });
  return mission;
}

// `map` is what the executor plans on; the robot drives `truth.world` with the faults (in the
// world's terms) and senses it as the profile says.
Execution execute(const SewerMap& map, const hal::TrueWorld& truth, const Mission& mission,
                  const hal::FaultScenario& faults, const RunSettings& settings,
                  executor::ReplannerOptions::Goals goals, domain::RiskCosts risk = {},
                  const ExecutionObservers& observers = {}, bool score_world = false) {
  executor::ReplannerOptions replanner_options{.goals = goals};
  replanner_options.planner.time_limit_s = settings.planner_time_limit_s;
  replanner_options.planner.risk = risk;
  // The paper-era baseline plans as MAKRO did: no battery kept for a blocked hazard pipe.
  replanner_options.planner.contingency =
      goals != executor::ReplannerOptions::Goals::kPaperBaseline;
  replanner_options.planner.max_strand_risk = settings.max_strand_risk;
  executor::Replanner replanner(map, mission, replanner_options);
  hal::SimRobot robot(truth.world, mission.profile,
                      hal::world_pose(map, truth, start_pose(replanner.progress().position)),
                      faults, hal::SimOptions{.sensing = hal::make_sensing(truth)});
  executor::ExecutorOptions options;
  options.recovery = recovery_of(settings);
  executor::Executor executor(map, replanner, robot, options);
  if (observers.on_event) executor.subscribe(observers.on_event);
  if (observers.on_plan) executor.subscribe_plans(observers.on_plan);
  Execution e;
  std::optional<double> strand_risk;  // the first plan's
  executor.subscribe_plans([&](const executor::PlanResponse& r) {
    ++e.rungs[static_cast<std::size_t>(r.rung)];
    if (!strand_risk) strand_risk = r.strand_probability;
  });
  // Watches from outside the robot's loop: it reads the simulated robot's true pose, and nothing of
  // it reaches the executor.
  std::optional<WorldScorer> scorer;
  if (score_world) scorer.emplace(map, truth, robot).watch(executor);
  const executor::MissionReport report = executor.run();
  e.tasks = report.tasks_done.size();
  e.end = report.end;
  e.reserve_kept = report.battery_reserve_kept;
  e.exit_on_reserve = report.exit_on_reserve;
  e.replans = report.replans;
  e.strand_risk = strand_risk.value_or(0);
  e.time_s = report.time_s;
  e.energy_wh = report.energy_wh;
  e.disabled = disabled(faults, robot);
  e.beacon_cause = report.beacon_cause;
  e.planning_times_s = report.planning_times_s;
  e.hazards = replanner.learnt().hazards;
  if (scorer) e.world = scorer->score();
  const std::optional<ManholeId> m = manhole_of(robot.pose());
  // A final task that is a place (go to a pipe or a manhole) is done by ending there: the executor
  // counts it when the robot is confirmed there at the end of the plan.
  const Task* final_task = replanner.mission().final_task();
  const bool ended = report.outcome == executor::MissionReport::Outcome::kEnded;
  const bool at_end_point = ended && final_task != nullptr &&
                            std::find(report.tasks_done.begin(), report.tasks_done.end(),
                                      final_task->name) != report.tasks_done.end();
  // An exit of the mission (its list, "map" or "all"), not the map's exit flag: an operator may
  // name any manhole where the robot can be recovered, and imported maps mark few or none.
  const std::vector<ManholeId>& exits = replanner.mission().exits;
  if (m && std::find(exits.begin(), exits.end(), *m) != exits.end()) {
    e.outcome = Outcome::kExit;
  } else if (at_end_point) {
    e.outcome = Outcome::kEndPoint;
  } else if (robot.status().beacon_on) {
    e.outcome = Outcome::kBeacon;
  } else {
    e.outcome = Outcome::kStranded;
  }
  return e;
}

// Ours is scored against the true world whenever there is one apart from the map, or sensing
// errors (any rate of the profile); with "none" its record has no scores.
bool scores_world(const RunSettings& settings) {
  return settings.world_errors != hal::WorldErrorProfile{};
}

}  // namespace

std::optional<FaultRates> fault_rate_profile(std::string_view name) {
  for (const FaultRateProfile& p : kFaultRateProfiles) {
    if (p.name == name) return p.rates;
  }
  return std::nullopt;
}

Result<FaultRates> parse_fault_rates(std::string_view text) {
  FaultRates r;
  // A profile first, then rates of its own.
  if (const std::string_view first = text.substr(0, text.find(','));
      !first.empty() && first.find('=') == std::string_view::npos) {
    const std::optional<FaultRates> profile = fault_rate_profile(first);
    if (!profile) {
      std::string known;
      for (const FaultRateProfile& p : kFaultRateProfiles) {
        known += (known.empty() ? "" : ", ") + std::string(p.name);
      }
      return Error{
          ErrorCode::kInvalidArgument,
          "--fault-rates: unknown profile '" + std::string(first) + "' (known: " + known + ")"};
    }
    r = *profile;
    text = first.size() == text.size() ? std::string_view{} : text.substr(first.size() + 1);
  }
  while (!text.empty()) {
    const std::size_t comma = text.find(',');
    const std::string_view item = text.substr(0, comma);
    text = comma == std::string_view::npos ? std::string_view{} : text.substr(comma + 1);
    const std::size_t eq = item.find('=');
    auto bad = [&](const std::string& why) {
      return Error{ErrorCode::kInvalidArgument,
                   "--fault-rates: '" + std::string(item) + "': " + why +
                       " (expected obstacles=, danger=, passages=, malfunctions=, permanent=, "
                       "transient=)"};
    };
    if (eq == std::string_view::npos) return bad("no '='");
    const std::string_view name = item.substr(0, eq);
    const std::string value(item.substr(eq + 1));
    double v = 0;
    try {
      std::size_t used = 0;
      v = std::stod(value, &used);
      if (used != value.size()) return bad("not a number");
    } catch (const std::exception&) {
      return bad("not a number");
    }
    if (!(v >= 0) || v > 1e6) return bad("must be a number from 0");
    const bool share = name == "passages" || name == "permanent" || name == "transient";
    if (share && v > 1) return bad("a share must be at most 1");
    if (name == "obstacles") {
      r.obstacles_per_km = v;
    } else if (name == "danger") {
      r.danger_per_km = v;
    } else if (name == "passages") {
      r.passage_share = v;
    } else if (name == "malfunctions") {
      r.malfunctions_per_hour = v;
    } else if (name == "permanent") {
      r.permanent_share = v;
    } else if (name == "transient") {
      r.transient_share = v;
    } else {
      return bad("unknown rate");
    }
  }
  return r;
}

namespace {

// The shortest text that reads back as the same double, so that a reproduce command is exact.
std::string exact(double v) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
  return ec == std::errc{} ? std::string(buffer, end) : std::to_string(v);
}

}  // namespace

std::string format_fault_rates(const FaultRates& r) {
  return "obstacles=" + exact(r.obstacles_per_km) + ",danger=" + exact(r.danger_per_km) +
         ",passages=" + exact(r.passage_share) + ",malfunctions=" + exact(r.malfunctions_per_hour) +
         ",permanent=" + exact(r.permanent_share) + ",transient=" + exact(r.transient_share);
}

std::uint64_t run_seed(std::uint64_t campaign_seed, std::size_t index) {
  return splitmix64(splitmix64(campaign_seed) ^ (0xD1B54A32D192ED03ULL * (index + 1)));
}

std::string_view to_string(Outcome outcome) { return detail::name_of(kOutcomes, outcome); }

std::optional<Outcome> outcome_from_string(std::string_view name) {
  return detail::value_of(kOutcomes, name);
}

Result<hal::FaultScenario> run_faults(const SewerMap& map, const Mission& mission,
                                      const RunSettings& settings, std::size_t index) {
  const FaultRates& r = settings.rates;
  hal::RandomFaultOptions o = hal::random_fault_options(mission.profile);
  o.seed = run_seed(settings.campaign_seed, index);
  o.obstacle_rate_per_km = r.obstacles_per_km;
  o.transient_share = r.transient_share;
  o.danger_rate_per_km = r.danger_per_km;
  o.dangerous_passage_share = r.passage_share;
  o.malfunction_rate_per_hour = r.malfunctions_per_hour;
  o.permanent_malfunction_share = r.permanent_share;
  Result<hal::FaultScenario> faults = hal::random_faults(map, o);
  if (!faults.has_value() || !settings.faults_from_condition) return faults;
  // Each possible blockage of the condition data stops the robot with its probability: a draw of
  // its own stream, so the random faults stay those of the same seed without condition data.
  Rng rng(splitmix64(o.seed ^ 0x5A17C0DE5A17C0DEULL));
  for (const Hazard& h : mission.hazards) {
    if (rng.bernoulli(h.probability)) {
      faults->obstacles.push_back({h.pipe, h.offset_m, hal::ObstacleKind::kPermanent});
    }
  }
  return faults;
}

Result<hal::TrueWorld> run_world(const SewerMap& map, const RunSettings& settings,
                                 std::size_t index) {
  // A stream apart from the faults' (which keep the seed they had before world errors).
  return hal::make_true_world(
      map, settings.world_errors,
      splitmix64(run_seed(settings.campaign_seed, index) ^ 0x3017DE5EED5EED00ULL));
}

Result<RunResult> run_one(const SewerMap& map, const Mission& mission, const RunSettings& settings,
                          std::size_t index) {
  const auto wall_start = std::chrono::steady_clock::now();
  Result<hal::FaultScenario> map_faults = run_faults(map, mission, settings, index);
  if (!map_faults.has_value()) return map_faults.error();
  Result<hal::TrueWorld> truth = run_world(map, settings, index);
  if (!truth.has_value()) return truth.error();
  const SewerMap& world = truth->world;
  const Result<hal::FaultScenario> faults = hal::world_faults(map, *truth, std::move(*map_faults));
  const Mission world_mission = in_world(map, *truth, mission);
  RunResult r;
  r.index = index;
  r.seed = run_seed(settings.campaign_seed, index);
  r.tasks = mission.tasks.size();
  for (const hal::Obstacle& o : faults->obstacles) {
    ++r.faults.obstacles;
    if (o.kind == hal::ObstacleKind::kPermanent) ++r.faults.permanent_obstacles;
  }
  r.faults.danger_spots = faults->danger_spots.size();
  r.faults.dangerous_passages = faults->dangerous_passages.size();
  for (const hal::Malfunction& m : faults->malfunctions) {
    ++r.faults.malfunctions;
    if (m.kind == hal::MalfunctionKind::kPermanent) ++r.faults.permanent_malfunctions;
  }

  ManualClock no_time;
  // The oracle knows which hazards stop the robot: it keeps no battery for the others.
  executor::ReplannerOptions oracle_options{.clock = &no_time};
  oracle_options.planner.contingency = false;
  const executor::RecoveryProfile recovery = recovery_of(settings);
  const Mission bound = clairvoyant(world_mission, *faults, recovery);
  executor::Replanner oracle(world, bound, oracle_options);
  const executor::PlanResponse plan = oracle.plan("oracle");
  r.oracle_can_end = executor::has_plan(plan.decision);
  r.oracle_tasks = r.oracle_can_end ? plan.goals.size() : 0;

  r.ours = execute(map, *truth, mission, *faults, settings,
                   executor::ReplannerOptions::Goals::kReselect, {}, {}, scores_world(settings));
  r.baseline = execute(map, *truth, mission, *faults, settings,
                       executor::ReplannerOptions::Goals::kPaperBaseline);
  if (settings.risk.active()) {
    r.risk_aware = execute(map, *truth, mission, *faults, settings,
                           executor::ReplannerOptions::Goals::kReselect, settings.risk);
  }
  r.seeded = truth->seeded;
  r.could_reach_exit = r.oracle_can_end && !r.ours.disabled;
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return r;
}

std::string_view to_string(Policy policy) { return detail::name_of(kPolicies, policy); }

std::optional<Policy> policy_from_string(std::string_view name) {
  return detail::value_of(kPolicies, name);
}

std::string policy_names() { return detail::names_joined(kPolicies); }

Result<Execution> replay_execution(const SewerMap& map, const Mission& mission,
                                   const RunSettings& settings, std::size_t index, Policy policy,
                                   const ExecutionObservers& observers) {
  if (policy == Policy::kRiskAware && !settings.risk.active()) {
    return Error{ErrorCode::kInvalidArgument,
                 "the campaign has no risk-aware execution (risk \"expected\")"};
  }
  Result<hal::FaultScenario> map_faults = run_faults(map, mission, settings, index);
  if (!map_faults.has_value()) return map_faults.error();
  Result<hal::TrueWorld> truth = run_world(map, settings, index);
  if (!truth.has_value()) return truth.error();
  const hal::FaultScenario faults = hal::world_faults(map, *truth, std::move(*map_faults));
  using Goals = executor::ReplannerOptions::Goals;
  switch (policy) {
    case Policy::kOurs:
      return execute(map, *truth, mission, faults, settings, Goals::kReselect, {}, observers,
                     scores_world(settings));
    case Policy::kBaseline:
      return execute(map, *truth, mission, faults, settings, Goals::kPaperBaseline, {}, observers);
    case Policy::kRiskAware:
      return execute(map, *truth, mission, faults, settings, Goals::kReselect, settings.risk,
                     observers);
  }
  return Error{ErrorCode::kInvalidArgument, "unknown policy"};
}

}  // namespace sewerplan::campaign
