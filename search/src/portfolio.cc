// SPDX-License-Identifier: MIT
#include "sewerplan/search/portfolio.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>

#include "sewerplan/search/best_first_search.h"
#include "sewerplan/search/tour_search.h"

#include "tour_shape.h"

namespace sewerplan::search {

std::string_view to_string(Engine engine) {
  switch (engine) {
    case Engine::kExactTour:
      return "exact tour search";
    case Engine::kTourSearch:
      return "tour search";
    case Engine::kSearch:
      return "search";
    case Engine::kExactImprovement:
      return "exact tour search (improvement)";
    case Engine::kImprovement:
      return "improvement";
  }
  return "search";
}

ProblemSize problem_size(const SewerMap& map, const domain::CompiledTask& task,
                         const domain::CompileStatistics& statistics) {
  ProblemSize size{.manholes = map.manhole_count(),
                   .pipes = map.pipe_count(),
                   .positions = statistics.graph_nodes,
                   .tasks = task.variable_count() > 0 ? task.variable_count() - 1 : 0,
                   .keys = statistics.keys,
                   .facts = task.fact_count(),
                   .actions = task.action_count()};
  size.states = state_count(task);
  return size;
}

double state_count(const domain::CompiledTask& task) {
  double states = 1;
  for (std::size_t v = 0; v < task.variable_count(); ++v) {
    states *= task.domain_size(domain::VarId{static_cast<std::uint32_t>(v)});
  }
  return states;
}

Algorithm resolve(Algorithm algorithm, const ProblemSize& size) {
  if (algorithm != Algorithm::kAuto) return algorithm;
  return size.states <= static_cast<double>(1 << 12) ? Algorithm::kAstar
                                                     : Algorithm::kWeightedAstar;
}

namespace {

// The route work a compile of this size does (Dijkstra nodes settled over all its searches),
// estimated from sizes alone: each key's searches settle at most the positions within the
// battery's reach, taken as at most kReachPositions.
double route_work(const ProblemSize& size) {
  return static_cast<double>(size.keys) *
         static_cast<double>(std::min(size.positions, kReachPositions));
}

// Work units: one Dijkstra node settled, or one fact or action visited by a heuristic evaluation.
double improvement_work(const ProblemSize& size) { return 4.0 * route_work(size) + 200'000.0; }

std::uint64_t improvement_budget(const ProblemSize& size, const PlannerOptions& options) {
  if (!options.adaptive_improvement || options.improvement_expansions == 0) {
    return options.improvement_expansions;
  }
  const double per_expansion =
      (static_cast<double>(size.keys) + 1.0) *
      static_cast<double>(std::max<std::size_t>(1, size.actions + size.facts));
  const double expansions = std::max(16.0, improvement_work(size) / per_expansion);
  return std::min(options.improvement_expansions, static_cast<std::uint64_t>(expansions));
}

// Whether the exact tour search fits the improvement's work: 2^K subsets x about 3K leave places
// x K goals x 3 options each.
bool exact_fits(const ProblemSize& size) {
  const std::size_t k = size.tasks;
  if (k > kMaxExactGoals) return false;
  const double work = std::ldexp(1.0, static_cast<int>(k)) * 9.0 * static_cast<double>(k * k);
  return work <= improvement_work(size);
}

// Issue 16: beyond that estimate, the exact tour search still replaces the improvement where its
// table (which bounds its work: each entry is extended once) is at most kExactBytesPerReach per
// unit of route work, up to kAutoExactBytes. The estimate above counts every goal at every entry
// and ignores that a first plan doing every task bounds the search (see exact_tour_search's
// `upper`). The table's size is known before it is allocated, so a table too large costs nothing.
// 0: none.
std::size_t exact_bytes(const ProblemSize& size) {
  if (exact_fits(size)) return kExactDefaultBytes;
  const std::size_t k = size.tasks;
  if (k > kMaxExactGoals) return 0;
  const auto work = static_cast<std::size_t>(route_work(size));
  const std::size_t bytes = std::min(kAutoExactBytes, kExactBytesPerReach * work);
  // At least one leave place per goal, each in half the subsets, 12 bytes an entry: a table
  // surely too large is not even read.
  return (std::size_t{1} << k) / 2 * k * 12 <= bytes ? bytes : 0;
}

bool admissible(HeuristicKind kind) {
  return kind == HeuristicKind::kMax || kind == HeuristicKind::kBlind;
}

// Anytime improvement: each search may only return plans cheaper than the best so far. One that
// exhausts its bounded space proves no cheaper plan exists.
void improve(const domain::CompiledTask& task, const StopCondition& stop, const Clock& clock,
             std::uint64_t budget, PortfolioRun& run) {
  SearchResult& best = run.result;
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
      ++run.improvements;
      run.optimal = last;
    } else if (r.status == SearchStatus::kUnsolvable) {
      run.optimal = true;  // nothing cheaper within the bound
      break;
    } else {
      break;  // a limit, or cancelled: keep the best plan so far
    }
  }
  best.statistics = total;
}

}  // namespace

Portfolio choose_portfolio(const ProblemSize& size, const PlannerOptions& options) {
  Portfolio portfolio;
  const Algorithm algorithm = resolve(options.algorithm, size);
  const bool optimal_search = algorithm == Algorithm::kAstar || algorithm == Algorithm::kExact;
  const HeuristicKind kind =
      options.heuristic.value_or(optimal_search ? HeuristicKind::kMax : HeuristicKind::kFf);
  const bool tour = options.algorithm == Algorithm::kAuto && algorithm != Algorithm::kAstar;
  if (algorithm == Algorithm::kExact) portfolio.stages.push_back({.engine = Engine::kExactTour});
  if (tour) portfolio.stages.push_back({.engine = Engine::kTourSearch});
  portfolio.stages.push_back({.engine = Engine::kSearch,
                              .algorithm = algorithm,
                              .heuristic = kind,
                              .weight = options.weight});
  if (optimal_search && admissible(kind)) return portfolio;  // optimal by construction
  if (options.improvement_expansions == 0) return portfolio;
  if (tour && options.adaptive_improvement) {
    const std::size_t bytes = exact_bytes(size);
    if (bytes > 0)
      portfolio.stages.push_back({.engine = Engine::kExactImprovement, .budget = bytes});
  }
  // Every plan sets each goal variable by an action of its own, and a best-first search expands
  // every state on the path it returns: within as many expansions as there are goals, none can
  // find a plan (issue 16: 16 expansions over 50 tasks, each evaluating the heuristic on a hundred
  // successors, took 5 times the compile's time on 1,000 manholes and never found one).
  const std::uint64_t expansions = improvement_budget(size, options);
  if (expansions > size.tasks) {
    portfolio.stages.push_back({.engine = Engine::kImprovement, .budget = expansions});
  }
  return portfolio;
}

Result<PortfolioRun> run_portfolio(const Portfolio& portfolio, const domain::CompiledTask& task,
                                   const StopCondition& stop, const Clock& clock,
                                   const PortfolioFailure& failure) {
  std::optional<PortfolioRun> run;
  // The tour search's reading of the task's shape, for the exact search after it.
  std::optional<detail::Shape> shape;
  bool from_tour = false;
  bool exact_improved = false;
  for (const Stage& stage : portfolio.stages) {
    switch (stage.engine) {
      case Engine::kExactTour: {
        if (run) break;
        std::optional<SearchResult> exact = exact_tour_search(task, stop, &clock);
        if (!exact) break;  // not of the shape: the next stage
        if (exact->status != SearchStatus::kSolved) return failure.status(exact->status);
        run = PortfolioRun{
            .result = std::move(*exact), .optimal = true, .algorithm = "exact tour search"};
        break;
      }
      case Engine::kTourSearch: {
        if (run) break;
        TourReport report;
        const double start_s = clock.now_s();
        shape = detail::read_shape(task, &stop);
        std::optional<SearchResult> found =
            detail::tour_search(task, shape, stop, clock, start_s, report);
        if (report.stopped && !found) return failure.status(*report.stopped);
        if (found) {
          run = PortfolioRun{.result = std::move(*found), .algorithm = "tour search"};
          from_tour = true;
          break;
        }
        if (report.has_shape && task.penalty_unit() == 0 &&
            report.cheapest_order != domain::kInfiniteCost &&
            report.cheapest_order > task.cost_bound()) {
          // Issue 14: a mission that does not fit the battery sent the fallback search through
          // the whole state space until the time limit. Prove it where the exact search can; else
          // say so at once (not a proof: exit 5, not 4).
          std::optional<SearchResult> exact = detail::exact_tour_search(
              task, shape, stop, clock, clock.now_s(), kExactDefaultBytes, domain::kInfiniteCost);
          if (!exact) return failure.battery_exceeded(report.cheapest_order);
          if (exact->status != SearchStatus::kSolved) return failure.status(exact->status);
          run = PortfolioRun{
              .result = std::move(*exact), .optimal = true, .algorithm = "exact tour search"};
        }
        break;
      }
      case Engine::kSearch: {
        if (run) break;
        std::unique_ptr<Heuristic> heuristic = make_heuristic(stage.heuristic, task);
        std::unique_ptr<SearchEngine> engine =
            make_engine(stage.algorithm, task, *heuristic, stage.weight);
        SearchResult result = engine->search(stop, clock);
        if (result.status != SearchStatus::kSolved) return failure.status(result.status);
        const bool optimal_search =
            stage.algorithm == Algorithm::kAstar || stage.algorithm == Algorithm::kExact;
        run = PortfolioRun{
            .result = std::move(result),
            .optimal = optimal_search && heuristic->admissible(),
            .algorithm = std::string(engine->name()) + " + " + std::string(heuristic->name())};
        break;
      }
      case Engine::kExactImprovement: {
        if (!run || run->optimal || !from_tour) break;
        SearchResult& first = run->result;
        // A first plan doing every task bounds the optimum, which then does every task too.
        const bool all_done = task.penalty_unit() == 0 || first.cost < task.penalty_unit();
        std::optional<SearchResult> best = detail::exact_tour_search(
            task, shape, stop, clock, clock.now_s(), static_cast<std::size_t>(stage.budget),
            all_done ? first.cost : domain::kInfiniteCost);
        if (best && best->status == SearchStatus::kSolved) {
          if (best->cost < first.cost) ++run->improvements;
          best->statistics.time_s += first.statistics.time_s;
          first = std::move(*best);
          run->optimal = true;
          exact_improved = true;
        }
        break;
      }
      case Engine::kImprovement: {
        if (!run || run->optimal) break;
        improve(task, stop, clock, stage.budget, *run);
        break;
      }
    }
  }
  if (!run) return failure.status(SearchStatus::kUnsolvable);
  if (run->improvements > 0) {
    run->algorithm +=
        exact_improved ? ", improved by the exact tour search" : ", improved by weighted A*";
  } else if (exact_improved) {
    run->algorithm += ", proven optimal by the exact tour search";
  }
  return std::move(*run);
}

}  // namespace sewerplan::search
