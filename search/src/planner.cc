// SPDX-License-Identifier: MIT
#include "sewerplan/search/planner.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>

#include "sewerplan/core/enum_names.h"
#include "sewerplan/search/best_first_search.h"
#include "sewerplan/search/enforced_hill_climbing.h"
#include "sewerplan/search/portfolio.h"
#include "sewerplan/search/tour_search.h"

namespace sewerplan::search {

namespace {

// sewerplan::detail in full, as everywhere in search, which has a detail namespace of its own.
constexpr sewerplan::detail::EnumNames<Algorithm, 6> kAlgorithms{{
    {Algorithm::kAuto, "auto"},
    {Algorithm::kEhc, "ehc"},
    {Algorithm::kGbfs, "gbfs"},
    {Algorithm::kWeightedAstar, "wastar"},
    {Algorithm::kAstar, "astar"},
    {Algorithm::kExact, "exact"},
}};
static_assert(sewerplan::detail::distinct(kAlgorithms));

}  // namespace

std::string_view to_string(Algorithm algorithm) {
  return sewerplan::detail::name_of(kAlgorithms, algorithm);
}

std::optional<Algorithm> algorithm_from_string(std::string_view name) {
  return sewerplan::detail::value_of(kAlgorithms, name);
}

std::string algorithm_names() { return sewerplan::detail::names_joined(kAlgorithms); }

Algorithm resolve(Algorithm algorithm, const domain::CompiledTask& task) {
  return resolve(algorithm, ProblemSize{.states = state_count(task)});
}

std::unique_ptr<SearchEngine> make_engine(Algorithm algorithm, const domain::CompiledTask& task,
                                          Heuristic& heuristic, double weight) {
  switch (algorithm) {
    case Algorithm::kAuto:
      return make_engine(resolve(algorithm, task), task, heuristic, weight);
    case Algorithm::kEhc:
      return std::make_unique<EnforcedHillClimbing>(task, heuristic);
    case Algorithm::kGbfs:
      return std::make_unique<BestFirstSearch>(task, heuristic, BestFirstSearch::greedy());
    case Algorithm::kWeightedAstar:
      return std::make_unique<BestFirstSearch>(task, heuristic,
                                               BestFirstSearch::weighted_astar(weight));
    case Algorithm::kAstar:
    case Algorithm::kExact:  // where the exact tour search does not apply
      return std::make_unique<BestFirstSearch>(task, heuristic, BestFirstSearch::astar());
  }
  return nullptr;
}

namespace {

std::string wh(double v) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << v << " Wh";
  return out.str();
}

Error search_failure(SearchStatus status, const Mission& mission,
                     const domain::MissionProgress& progress, const domain::CompiledTask& task) {
  switch (status) {
    case SearchStatus::kUnsolvable: {
      const double available = mission.profile.energy_wh(domain::to_seconds(task.cost_bound()));
      std::size_t pending = 0;
      for (bool done : progress.done) pending += done ? 0U : 1U;
      return Error{
          ErrorCode::kNoPlan,
          "the mission cannot be completed:\n  - no plan does all " + std::to_string(pending) +
              " remaining tasks within the battery's " + wh(available) + " (battery " +
              wh(mission.profile.battery_wh) + " less " +
              std::to_string(static_cast<int>(mission.battery_reserve_fraction * 100)) +
              "% reserve" +
              (progress.energy_used_wh > 0 ? ", less " + wh(progress.energy_used_wh) + " used"
                                           : std::string()) +
              "), though each task alone is within reach"};
    }
    case SearchStatus::kTimeLimit:
      return Error{ErrorCode::kSearchLimit, "the search reached its time limit without a plan"};
    case SearchStatus::kExpansionLimit:
      return Error{ErrorCode::kSearchLimit,
                   "the search reached its expansion limit without a plan"};
    case SearchStatus::kCancelled:
      return Error{ErrorCode::kCancelled, "the search was cancelled"};
    case SearchStatus::kSolved:
      break;
  }
  return Error{ErrorCode::kNoPlan, "no plan"};
}

Error battery_exceeded(const Mission& mission, const domain::CompiledTask& task, Cost cheapest) {
  const auto energy = [&](Cost c) { return wh(mission.profile.energy_wh(domain::to_seconds(c))); };
  return Error{ErrorCode::kSearchLimit,
               "no plan found that does all " + std::to_string(task.variable_count() - 1) +
                   " remaining tasks within the battery's " + energy(task.cost_bound()) +
                   ": the cheapest order of them the tour search found needs " + energy(cheapest) +
                   " (not a proof that none fits; with --select-goals the plan does as many "
                   "tasks as fit)"};
}

// The outcome of `result`, a plan of `compiled`: its primitive plan, costs, tasks dropped and
// statistics.
// `strand_budget`: the battery the plan has (as a cost) for its stranding risk, where the
// compiled task's bound is not the real battery's (a risk-aware plan on a relaxed battery).
void complete(const domain::SewerTask& compiled, const Mission& mission, const SearchResult& result,
              PlanOutcome& outcome, std::optional<Cost> strand_budget = std::nullopt) {
  const domain::CompiledTask& task = compiled.task();
  outcome.plan = compiled.expand(result.plan);
  const Cost risk = compiled.risk_cost(result.plan);
  outcome.cost_s = domain::to_seconds(task.real_cost(result.cost) - risk);
  outcome.risk_cost_s = domain::to_seconds(risk);
  outcome.dropped = compiled.dropped();
  for (TaskId t : compiled.forgone(result.plan)) {
    outcome.dropped.push_back({t, "not enough battery to do it as well and still end the mission"});
  }
  std::sort(outcome.dropped.begin(), outcome.dropped.end(),
            [](const auto& a, const auto& b) { return a.task < b.task; });
  outcome.energy_wh = mission.profile.energy_wh(outcome.cost_s);
  domain::StrandRisk strand = compiled.strand_risk(result.plan, strand_budget);
  outcome.strand_probability = strand.probability;
  outcome.uninsured = std::move(strand.uninsured);
  outcome.search = result.statistics;
  outcome.compile = compiled.statistics();
}

}  // namespace

namespace {

// `strand_budget`: as complete's.
Result<PlanOutcome> plan_once(const SewerMap& map, const Mission& mission,
                              const domain::MissionProgress& progress,
                              const PlannerOptions& options,
                              std::optional<Cost> strand_budget = std::nullopt) {
  const SteadyClock steady;
  const Clock& clock = options.clock != nullptr ? *options.clock : steady;
  // The time limit bounds the compile and the search together.
  StopCondition stop = options.time_limit_s > 0
                           ? StopCondition::after_seconds(clock, options.time_limit_s)
                           : StopCondition();
  if (options.cancel != nullptr) stop.with_cancel(*options.cancel);
  Result<domain::SewerTask> compiled =
      domain::compile_sewer_task(map, mission, progress,
                                 {.select_goals = options.select_goals,
                                  .stop = stop,
                                  .risk = options.risk,
                                  .contingency = options.contingency,
                                  .insured = options.insured,
                                  .cache = options.compile_cache});
  if (!compiled.has_value()) return compiled.error();
  const domain::CompiledTask& task = compiled->task();
  // Checked between the stretches here (each well under a millisecond, issue 14) as the searches
  // check theirs.
  if (auto stopped = stop.interrupted()) return search_failure(*stopped, mission, progress, task);
  // An admissible estimate already beyond the battery proves there is no plan, whatever the
  // algorithm: without this, greedy searches would exhaust the bounded state space to find out.
  // (With goal selection, forgoing tasks is always possible, and the estimate includes penalties.)
  std::unique_ptr<Heuristic> admissible = make_heuristic(HeuristicKind::kMax, task);
  admissible->watch(&stop);
  const Cost lower = admissible->evaluate(task.initial_state(), nullptr);
  admissible.reset();
  if (lower == Heuristic::kInterrupted) {
    return search_failure(stop.interrupted().value_or(SearchStatus::kTimeLimit), mission, progress,
                          task);
  }
  // A finished proof stands even if the stop fired as it finished.
  if (lower == Heuristic::kDeadEnd || (task.penalty_unit() == 0 && lower > task.cost_bound())) {
    return search_failure(SearchStatus::kUnsolvable, mission, progress, task);
  }
  if (auto stopped = stop.interrupted()) return search_failure(*stopped, mission, progress, task);
  if (options.max_expansions > 0) stop.with_max_expansions(options.max_expansions);
  // Which searches run, with which budgets: from the problem's size, never from the compile's
  // work (portfolio.h).
  const Portfolio portfolio =
      choose_portfolio(problem_size(map, task, compiled->statistics()), options);
  Result<PortfolioRun> run = run_portfolio(
      portfolio, task, stop, clock,
      {.status = [&](SearchStatus s) { return search_failure(s, mission, progress, task); },
       .battery_exceeded =
           [&](Cost cheapest) { return battery_exceeded(mission, task, cheapest); }});
  if (!run.has_value()) return run.error();
  PlanOutcome outcome;
  outcome.optimal = run->optimal;
  outcome.improvements = run->improvements;
  // The deadline (or a cancel) came after a first plan, before the planner had done all it meant
  // to: the plan is the best found by then.
  outcome.best_so_far = stop.interrupted().has_value();
  complete(*compiled, mission, run->result, outcome, strand_budget);
  outcome.algorithm = std::move(run->algorithm);
  return outcome;
}

Result<PlanOutcome> plan_weighing_risks(const SewerMap& map, const Mission& mission,
                                        const domain::MissionProgress& progress,
                                        const PlannerOptions& options) {
  if (!options.risk.active() || mission.hazards.empty()) {
    return plan_once(map, mission, progress, options);
  }
  const SteadyClock steady;
  const Clock& clock = options.clock != nullptr ? *options.clock : steady;
  const double started_s = clock.now_s();
  // The expected cost of stops is not energy: the risk-aware search gets a battery larger by as
  // much as any plan's expected cost can be (each route or inspection at most C, the way out at
  // most return_s), and its plan must then fit the real battery by its true cost.
  std::size_t pending = 0;
  for (bool done : progress.done) pending += done ? 0 : 1;
  const double allowance_s =
      options.risk.return_s + options.risk.blockage_s * 2 * static_cast<double>(pending + 1);
  Mission relaxed = mission;
  relaxed.profile.battery_wh +=
      mission.profile.energy_wh(allowance_s) / (1 - mission.battery_reserve_fraction);
  const double budget_wh =
      mission.profile.battery_wh * (1 - mission.battery_reserve_fraction) - progress.energy_used_wh;
  // One time limit bounds every attempt together: each gets what the earlier ones left.
  const auto time_left = [&](PlannerOptions o) -> std::optional<PlannerOptions> {
    if (o.time_limit_s <= 0) return o;
    o.time_limit_s -= clock.now_s() - started_s;
    if (o.time_limit_s <= 0) return std::nullopt;
    return o;
  };
  // The relaxed plan's stranding risk weighs what the real battery leaves at each hazard.
  const Cost real_budget = domain::to_cost(mission.profile.seconds_for(std::max(0.0, budget_wh)));
  Result<PlanOutcome> aware = plan_once(map, relaxed, progress, options, real_budget);
  if (aware.has_value() && aware->energy_wh > budget_wh + 1e-9) {
    // Too tight for that: weigh the risks within the real battery (the expected cost then takes
    // battery too, so the plan fits by construction).
    std::optional<PlannerOptions> retry = time_left(options);
    if (!retry) {
      return Error{ErrorCode::kSearchLimit,
                   "time limit reached before a risk-weighed plan fitting the battery"};
    }
    aware = plan_once(map, mission, progress, *retry);
  }
  const bool no_plan = !aware.has_value() && aware.error().code == ErrorCode::kNoPlan;
  const bool fewer_tasks = aware.has_value() && options.select_goals && !aware->dropped.empty();
  if (!no_plan && !fewer_tasks) return aware;
  std::optional<PlannerOptions> blind = time_left(options);
  if (!blind) return aware;
  blind->risk = {};
  Result<PlanOutcome> fallback = plan_once(map, mission, progress, *blind);
  if (!fallback.has_value()) return aware.has_value() ? std::move(aware) : std::move(fallback);
  if (fewer_tasks && fallback->dropped.size() >= aware->dropped.size()) return aware;
  fallback->risk_note = no_plan ? "risk-blind: no plan weighing the risks fits the battery"
                                : "risk-blind: weighing the risks would drop tasks";
  return fallback;
}

// plan_weighing_risks with the hazards options.insured names keeping their reserves; where no
// plan keeps them, without any.
Result<PlanOutcome> plan_insured(const SewerMap& map, const Mission& mission,
                                 const domain::MissionProgress& progress,
                                 const PlannerOptions& options) {
  const SteadyClock steady;
  const Clock& clock = options.clock != nullptr ? *options.clock : steady;
  const double started_s = clock.now_s();
  Result<PlanOutcome> kept = plan_weighing_risks(map, mission, progress, options);
  if (kept.has_value() || kept.error().code != ErrorCode::kNoPlan || !options.contingency ||
      mission.hazards.empty()) {
    return kept;
  }
  // No plan keeps the reserves: the best there is without them (a robot that may still drive
  // out is better than a beacon), within what is left of the time limit.
  PlannerOptions without = options;
  without.contingency = false;
  if (without.time_limit_s > 0) {
    without.time_limit_s -= clock.now_s() - started_s;
    if (without.time_limit_s <= 0) return kept;
  }
  Result<PlanOutcome> plain = plan_weighing_risks(map, mission, progress, without);
  if (!plain.has_value()) return plain.error().code == ErrorCode::kNoPlan ? kept : plain;
  plain->contingency_note =
      "no plan keeps the battery to back out of a blocked hazard pipe and reach an exit another "
      "way: planned without that reserve";
  return plain;
}

// Whether `a` does more tasks than `b`, or as many in less time.
bool does_better(const PlanOutcome& a, const PlanOutcome& b) {
  if (a.dropped.size() != b.dropped.size()) return a.dropped.size() < b.dropped.size();
  return a.cost_s < b.cost_s - 1e-6;
}

// Chance-constrained contingency (PlannerOptions::max_strand_risk, 0 < bound < 1): a risk
// budget allocated over the plan, greedily by the tasks each reserve costs per unit of risk it
// removes. Plans with every hazard insured (the fallback: within the bound unless hazards no
// reserve covers are passed) and with none; then, while the plan with the current insured set
// is over the bound, tries insuring each hazard it passes uninsured (by probability, the
// highest first, at most kStrandCandidates a round) and takes the one that loses the fewest
// tasks per unit of computed risk it removes (then the most risk removed, then the quickest
// plan); where none removes any (each reserve moved the tour past hazards it did not pass
// before), the one that loses the fewest tasks, and the next round insures what it passes. Every
// plan tried that is within the bound and does more tasks than the best so far (or as many sooner)
// becomes the answer. At most kMaxStrandRounds plans beyond the fully insured one, deterministic
// (counts, not time); a time limit bounds them all together, and when it runs out the best so far
// is the answer.
Result<PlanOutcome> plan_within_strand_risk(const SewerMap& map, const Mission& mission,
                                            const domain::MissionProgress& progress,
                                            const PlannerOptions& options) {
  const SteadyClock steady;
  const Clock& clock = options.clock != nullptr ? *options.clock : steady;
  const double started_s = clock.now_s();
  // Within rounding: 1 - (1 - 0.05) is a hair above 0.05.
  const double bound = options.max_strand_risk + 1e-9;
  const std::size_t n = mission.hazards.size();
  PlannerOptions all = options;
  all.insured.clear();
  Result<PlanOutcome> best = plan_insured(map, mission, progress, all);
  if (!best.has_value() || best->strand_probability > bound) return best;
  std::vector<bool> best_insured(n, true);
  std::size_t plans = 0;
  // One more plan with `insured`, within what is left of the time limit; none when it is out, the
  // plans are spent or the plan fails.
  const auto attempt = [&](const std::vector<bool>& insured) -> std::optional<PlanOutcome> {
    if (plans >= kMaxStrandRounds) return std::nullopt;
    PlannerOptions o = options;
    o.insured = insured;
    if (o.time_limit_s > 0) {
      o.time_limit_s -= clock.now_s() - started_s;
      if (o.time_limit_s <= 0) return std::nullopt;
    }
    ++plans;
    Result<PlanOutcome> r = plan_insured(map, mission, progress, o);
    if (!r.has_value()) return std::nullopt;
    return std::move(*r);
  };
  const auto keep_if_better = [&](const PlanOutcome& r, const std::vector<bool>& insured) {
    if (r.strand_probability > bound || !does_better(r, *best)) return;
    *best = r;
    best_insured = insured;
  };
  std::vector<bool> insured(n, false);
  std::optional<PlanOutcome> current = attempt(insured);
  if (current) keep_if_better(*current, insured);
  while (current && current->strand_probability > bound) {
    std::vector<std::size_t> candidates;
    for (std::size_t h : current->uninsured) {
      if (!insured[h]) candidates.push_back(h);
    }
    std::stable_sort(candidates.begin(), candidates.end(), [&](std::size_t a, std::size_t b) {
      return mission.hazards[a].probability > mission.hazards[b].probability;
    });
    if (candidates.size() > kStrandCandidates) candidates.resize(kStrandCandidates);
    struct Choice {
      std::size_t hazard = 0;
      double lost_per_risk = 0;
      double removed = 0;
      PlanOutcome plan;
    };
    std::optional<Choice> chosen;
    // Where no candidate removes risk: the one whose plan loses the fewest tasks (then carries
    // the least risk, then is quickest), to go on from.
    std::optional<Choice> detour;
    for (std::size_t h : candidates) {
      std::vector<bool> trial = insured;
      trial[h] = true;
      std::optional<PlanOutcome> r = attempt(trial);
      if (!r) break;
      keep_if_better(*r, trial);
      const double removed = current->strand_probability - r->strand_probability;
      if (!(removed > 1e-12)) {
        // No risk removed: the reserve moved the tour past hazards it did not pass before (a
        // task dropped, another order), which a later round can insure in turn.
        const bool fewer = !detour || r->dropped.size() < detour->plan.dropped.size() ||
                           (r->dropped.size() == detour->plan.dropped.size() &&
                            (r->strand_probability < detour->plan.strand_probability - 1e-12 ||
                             (r->strand_probability <= detour->plan.strand_probability + 1e-12 &&
                              r->cost_s < detour->plan.cost_s - 1e-6)));
        if (fewer) detour = Choice{h, 0, removed, std::move(*r)};
        continue;
      }
      const double lost =
          static_cast<double>(r->dropped.size()) - static_cast<double>(current->dropped.size());
      const double per = lost / removed;
      const bool better =
          !chosen || per < chosen->lost_per_risk - 1e-9 ||
          (per <= chosen->lost_per_risk + 1e-9 &&
           (removed > chosen->removed + 1e-12 ||
            (removed >= chosen->removed - 1e-12 && r->cost_s < chosen->plan.cost_s - 1e-6)));
      if (better) chosen = Choice{h, per, removed, std::move(*r)};
    }
    if (!chosen) chosen = std::move(detour);
    if (!chosen) break;
    insured[chosen->hazard] = true;
    current = std::move(chosen->plan);
  }
  best->strand_plans = plans;
  std::size_t uninsured = 0;
  for (std::size_t h = 0; h < n; ++h) uninsured += best_insured[h] ? 0U : 1U;
  std::ostringstream note;
  note << std::fixed << std::setprecision(4) << "within the bound " << options.max_strand_risk
       << ": "
       << (uninsured == 0 ? "every hazard keeps its reserve"
                          : std::to_string(n - uninsured) + " of " + std::to_string(n) +
                                " hazards keep their reserve")
       << " (" << plans << (plans == 1 ? " plan" : " plans")
       << " tried beyond the fully insured one)";
  best->strand_note = note.str();
  return best;
}

}  // namespace

Result<PlanOutcome> plan_mission(const SewerMap& map, const Mission& mission,
                                 const domain::MissionProgress& progress,
                                 const PlannerOptions& options) {
  if (!options.contingency || mission.hazards.empty() || !(options.max_strand_risk > 0)) {
    return plan_insured(map, mission, progress, options);
  }
  if (options.max_strand_risk >= 1) {
    // No reserve, but the ways out computed, so that the plan's stranding risk weighs the
    // battery it has left at each hazard (domain::SewerTask::strand_risk).
    PlannerOptions blind = options;
    blind.insured.assign(mission.hazards.size(), false);
    return plan_insured(map, mission, progress, blind);
  }
  return plan_within_strand_risk(map, mission, progress, options);
}

namespace {

// plan_greedily and plan_in_order: one compile without a time limit (the cancel is honoured),
// risk-blind, then `quick` on the compiled task; without the contingency reserves where no plan
// keeps them.
template <typename Quick>
Result<PlanOutcome> plan_quickly(const SewerMap& map, const Mission& mission,
                                 const domain::MissionProgress& progress,
                                 const PlannerOptions& options, std::string_view name,
                                 const Quick& quick) {
  StopCondition stop;
  if (options.cancel != nullptr) stop.with_cancel(*options.cancel);
  std::optional<Error> failure;
  // max_strand_risk: 1 keeps no reserve; below, the quick answer keeps every one (or those
  // options.insured names).
  const bool reserves = options.contingency && options.max_strand_risk < 1;
  for (const bool contingency : {true, false}) {
    if (contingency && !reserves) continue;
    Result<domain::SewerTask> compiled =
        domain::compile_sewer_task(map, mission, progress,
                                   {.select_goals = options.select_goals,
                                    .stop = stop,
                                    .contingency = contingency,
                                    .insured = options.insured,
                                    .cache = options.compile_cache});
    if (!compiled.has_value()) {
      if (compiled.error().code != ErrorCode::kNoPlan) return compiled.error();
      if (!failure) failure = compiled.error();
      continue;
    }
    std::optional<SearchResult> result = quick(*compiled, stop);
    if (auto stopped = stop.interrupted()) {
      return search_failure(*stopped, mission, progress, compiled->task());
    }
    if (!result) {
      if (!failure) {
        failure = Error{ErrorCode::kNoPlan, std::string(name) + ": no plan within the battery"};
      }
      continue;
    }
    PlanOutcome outcome;
    complete(*compiled, mission, *result, outcome);
    outcome.algorithm = std::string(name);
    if (reserves && !contingency && !mission.hazards.empty()) {
      outcome.contingency_note =
          "no plan keeps the battery to back out of a blocked hazard pipe and reach an exit "
          "another way: planned without that reserve";
    }
    return outcome;
  }
  return *failure;
}

}  // namespace

Result<PlanOutcome> plan_greedily(const SewerMap& map, const Mission& mission,
                                  const domain::MissionProgress& progress,
                                  const PlannerOptions& options) {
  const SteadyClock steady;
  const Clock& clock = options.clock != nullptr ? *options.clock : steady;
  return plan_quickly(map, mission, progress, options, "greedy insertion",
                      [&](const domain::SewerTask& compiled, const StopCondition& stop) {
                        return greedy_tour(compiled.task(), stop, &clock);
                      });
}

Result<PlanOutcome> plan_in_order(const SewerMap& map, const Mission& mission,
                                  const domain::MissionProgress& progress,
                                  std::span<const TaskId> order, const PlannerOptions& options) {
  return plan_quickly(map, mission, progress, options, "in a given order",
                      [&](const domain::SewerTask& compiled, const StopCondition& stop) {
                        const std::vector<TaskId>& goals = compiled.goal_tasks();
                        std::vector<domain::VarId> vars;
                        for (TaskId t : order) {
                          auto it = std::find(goals.begin(), goals.end(), t);
                          if (it == goals.end()) continue;  // done or dropped already
                          const auto v = static_cast<std::uint32_t>(it - goals.begin()) + 1;
                          if (std::find(vars.begin(), vars.end(), domain::VarId{v}) == vars.end()) {
                            vars.push_back(domain::VarId{v});
                          }
                        }
                        return ordered_tour(compiled.task(), vars, stop);
                      });
}

}  // namespace sewerplan::search
