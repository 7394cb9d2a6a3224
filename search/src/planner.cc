// SPDX-License-Identifier: MIT
#include "sewerplan/search/planner.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "sewerplan/search/best_first_search.h"
#include "sewerplan/search/enforced_hill_climbing.h"
#include "sewerplan/search/tour_search.h"

namespace sewerplan::search {

std::string_view to_string(Algorithm algorithm) {
  switch (algorithm) {
    case Algorithm::kAuto:
      return "auto";
    case Algorithm::kEhc:
      return "ehc";
    case Algorithm::kGbfs:
      return "gbfs";
    case Algorithm::kWeightedAstar:
      return "wastar";
    case Algorithm::kAstar:
      return "astar";
  }
  return "ehc";
}

std::optional<Algorithm> algorithm_from_string(std::string_view name) {
  for (Algorithm a : {Algorithm::kAuto, Algorithm::kEhc, Algorithm::kGbfs,
                      Algorithm::kWeightedAstar, Algorithm::kAstar}) {
    if (to_string(a) == name) return a;
  }
  return std::nullopt;
}

Algorithm resolve(Algorithm algorithm, const domain::CompiledTask& task) {
  if (algorithm != Algorithm::kAuto) return algorithm;
  double states = 1;
  for (std::size_t v = 0; v < task.variable_count(); ++v) {
    states *= task.domain_size(domain::VarId{static_cast<std::uint32_t>(v)});
  }
  return states <= static_cast<double>(1 << 12) ? Algorithm::kAstar : Algorithm::kWeightedAstar;
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

// Anytime improvement: each search may only return plans cheaper than the best so far. One that
// exhausts its bounded space proves no cheaper plan exists.
void improve(const domain::CompiledTask& task, const StopCondition& stop, const Clock& clock,
             std::uint64_t budget, SearchResult& best, PlanOutcome& outcome) {
  SearchStatistics total = best.statistics;
  for (double weight : {3.0, 2.0, 1.5, 1.0}) {
    if (budget == 0 || best.cost == 0) break;
    const bool last = weight == 1.0;
    auto h = make_heuristic(last ? HeuristicKind::kMax : HeuristicKind::kFf, task);
    BestFirstSearch search(task, *h, BestFirstSearch::weighted_astar(weight), best.cost - 1);
    StopCondition limited = stop;
    limited.with_max_expansions(budget);
    SearchResult r = search.search(limited, clock);
    accumulate(total, r.statistics);
    budget -= std::min(budget, r.statistics.expanded);
    if (r.status == SearchStatus::kSolved) {
      best.plan = std::move(r.plan);
      best.cost = r.cost;
      ++outcome.improvements;
      outcome.optimal = last;
    } else if (r.status == SearchStatus::kUnsolvable) {
      outcome.optimal = true;  // nothing cheaper within the bound
      break;
    } else {
      break;  // a limit, or cancelled: keep the best plan so far
    }
  }
  best.statistics = total;
}

}  // namespace

Result<PlanOutcome> plan_mission(const SewerMap& map, const Mission& mission,
                                 const domain::MissionProgress& progress,
                                 const PlannerOptions& options) {
  const SteadyClock steady;
  const Clock& clock = options.clock != nullptr ? *options.clock : steady;
  Result<domain::SewerTask> compiled =
      domain::compile_sewer_task(map, mission, progress, {.select_goals = options.select_goals});
  if (!compiled.has_value()) return compiled.error();
  const domain::CompiledTask& task = compiled->task();
  // An admissible estimate already beyond the battery proves there is no plan, whatever the
  // algorithm: without this, greedy searches would exhaust the bounded state space to find out.
  // (With goal selection, forgoing tasks is always possible, and the estimate includes penalties.)
  if (auto lower =
          make_heuristic(HeuristicKind::kMax, task)->evaluate(task.initial_state(), nullptr);
      lower == Heuristic::kDeadEnd || (task.penalty_unit() == 0 && lower > task.cost_bound())) {
    return search_failure(SearchStatus::kUnsolvable, mission, progress, task);
  }
  const Algorithm algorithm = resolve(options.algorithm, task);
  const HeuristicKind kind = options.heuristic.value_or(
      algorithm == Algorithm::kAstar ? HeuristicKind::kMax : HeuristicKind::kFf);
  std::unique_ptr<Heuristic> heuristic = make_heuristic(kind, task);
  std::unique_ptr<SearchEngine> engine = make_engine(algorithm, task, *heuristic, options.weight);
  StopCondition stop = options.time_limit_s > 0
                           ? StopCondition::after_seconds(clock, options.time_limit_s)
                           : StopCondition();
  if (options.max_expansions > 0) stop.with_max_expansions(options.max_expansions);
  if (options.cancel != nullptr) stop.with_cancel(*options.cancel);
  // kAuto beyond exhaustive A*: the tour search's first plan, where the task has its shape.
  std::optional<SearchResult> tour;
  if (options.algorithm == Algorithm::kAuto && algorithm != Algorithm::kAstar) {
    tour = tour_search(task);
  }
  SearchResult result = tour ? std::move(*tour) : engine->search(stop, clock);
  if (result.status != SearchStatus::kSolved) {
    return search_failure(result.status, mission, progress, task);
  }
  PlanOutcome outcome;
  outcome.optimal = !tour && algorithm == Algorithm::kAstar && heuristic->admissible();
  if (!outcome.optimal && options.improvement_expansions > 0) {
    improve(task, stop, clock, options.improvement_expansions, result, outcome);
  }
  outcome.plan = compiled->expand(result.plan);
  outcome.cost_s = domain::to_seconds(task.real_cost(result.cost));
  outcome.dropped = compiled->dropped();
  for (TaskId t : compiled->forgone(result.plan)) {
    outcome.dropped.push_back({t, "not enough battery to do it as well and still end the mission"});
  }
  std::sort(outcome.dropped.begin(), outcome.dropped.end(),
            [](const auto& a, const auto& b) { return a.task < b.task; });
  outcome.energy_wh = mission.profile.energy_wh(outcome.cost_s);
  outcome.search = result.statistics;
  outcome.compile = compiled->statistics();
  outcome.algorithm = tour ? std::string("tour search")
                           : std::string(engine->name()) + " + " + std::string(heuristic->name());
  if (outcome.improvements > 0) outcome.algorithm += ", improved by weighted A*";
  return outcome;
}

}  // namespace sewerplan::search
