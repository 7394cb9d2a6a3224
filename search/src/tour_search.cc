// SPDX-License-Identifier: MIT
// Tour search (tour_search.h): the task's shape, the dynamic programme over an order of goals,
// cheapest insertion, local search, and goals left out for the bound.
#include "sewerplan/search/tour_search.h"

#include <algorithm>
#include <limits>
#include <span>
#include <unordered_map>

#include "sewerplan/core/clock.h"

#include "tour_costs.h"
#include "tour_shape.h"

namespace sewerplan::search {
namespace {

using detail::Goal;
using detail::kStays;
using detail::Option;
using detail::read_shape;
using detail::Shape;
using domain::CompiledTask;
using domain::Fact;
using domain::kInfiniteCost;
using domain::VarId;

// The best choices for one order of goals, by dynamic programming over positions.
class Evaluator {
 public:
  explicit Evaluator(const Shape& shape) : s_(shape) {}

  // The real cost of doing `order` (goal indices) from the start, and ending as the goal asks;
  // kInfiniteCost if impossible. With `plan`, also the actions.
  Cost cost(const std::vector<std::size_t>& order, std::vector<ActionId>* plan = nullptr) {
    // The layers' buffers are kept from one order to the next (issue 16: the tour search
    // evaluates thousands of orders, and allocating a layer per goal for each was a third of it).
    used_ = 1;
    layer(0).assign(1, {s_.start, {0, -1, -1}});
    for (std::size_t k = 0; k < order.size(); ++k) {
      const Goal& g = s_.goals[order[k]];
      auto& next = layer(used_);  // first: it may move the layers
      next.clear();
      const auto& prev = layers_[used_ - 1];
      for (std::size_t o = 0; o < g.options.size(); ++o) {
        const Option& opt = g.options[o];
        for (std::size_t p = 0; p < prev.size(); ++p) {
          const Cost d = s_.move_cost(prev[p].first, opt.at);
          const Cost spent = prev[p].second.cost;
          if (d >= kInfiniteCost || spent >= kInfiniteCost) continue;
          // The contingency reserves (CompiledTask::reserve): feasibility only gets easier with
          // less spent, so the cheapest entry per place stays the one to keep.
          if (!s_.fits(spent, d, s_.move_reserve(prev[p].first, opt.at)) ||
              !s_.fits(spent + d, opt.cost, opt.reserve)) {
            continue;
          }
          const Cost c = spent + d + opt.cost;
          const std::int32_t where = opt.to == kStays ? opt.at : opt.to;
          auto it = std::find_if(next.begin(), next.end(),
                                 [&](const auto& e) { return e.first == where; });
          const Entry e{c, static_cast<std::int32_t>(p), static_cast<std::int32_t>(o)};
          if (it == next.end()) {
            next.emplace_back(where, e);
          } else if (c < it->second.cost) {
            it->second = e;
          }
        }
      }
      if (next.empty()) return kInfiniteCost;
      ++used_;
    }
    Cost best = kInfiniteCost;
    std::int32_t best_p = -1;
    const auto& last = layers_[used_ - 1];
    for (std::size_t p = 0; p < last.size(); ++p) {
      const Cost tail = s_.end ? s_.move_cost(last[p].first, *s_.end) : 0;
      if (tail >= kInfiniteCost) continue;
      if (s_.end && !s_.fits(last[p].second.cost, tail, s_.move_reserve(last[p].first, *s_.end))) {
        continue;
      }
      if (last[p].second.cost + tail < best) {
        best = last[p].second.cost + tail;
        best_p = static_cast<std::int32_t>(p);
      }
    }
    if (plan != nullptr && best_p >= 0) reconstruct(order, best_p, *plan);
    return best;
  }

 private:
  struct Entry {
    Cost cost;
    std::int32_t from;    // index in the previous layer
    std::int32_t option;  // of the goal
  };

  void add_move(std::int32_t a, std::int32_t b, std::vector<ActionId>& plan) const {
    if (a != b) plan.push_back(s_.move_action(a, b));
  }

  void reconstruct(const std::vector<std::size_t>& order, std::int32_t p,
                   std::vector<ActionId>& plan) const {
    std::vector<const Option*> chosen(order.size());
    std::vector<std::int32_t> before(order.size());
    const std::int32_t final_place = layers_[used_ - 1][static_cast<std::size_t>(p)].first;
    for (std::size_t k = order.size(); k > 0; --k) {
      const Entry& e = layers_[k][static_cast<std::size_t>(p)].second;
      chosen[k - 1] = &s_.goals[order[k - 1]].options[static_cast<std::size_t>(e.option)];
      p = e.from;
      before[k - 1] = layers_[k - 1][static_cast<std::size_t>(p)].first;
    }
    for (std::size_t k = 0; k < order.size(); ++k) {
      add_move(before[k], chosen[k]->at, plan);
      plan.push_back(chosen[k]->action);
    }
    if (s_.end) add_move(final_place, *s_.end, plan);
  }

  std::vector<std::pair<std::int32_t, Entry>>& layer(std::size_t i) {
    if (layers_.size() <= i) layers_.resize(i + 1);
    return layers_[i];
  }

  const Shape& s_;
  std::vector<std::vector<std::pair<std::int32_t, Entry>>> layers_;  // the first used_ in use
  std::size_t used_ = 0;
};

class Tour {
 public:
  // `local_search`: false for cheapest insertion alone (greedy_tour).
  Tour(const Shape& shape, const StopCondition& stop, bool local_search = true)
      : s_(shape),
        eval_(shape),
        costs_(shape),
        whole_(shape.has_reserves()),
        local_search_(local_search),
        stop_(stop) {}

  // The reason the stop condition gave, once it fired; then build() returns nothing more.
  std::optional<SearchStatus> stopped() const { return stopped_; }

  // An order of the goals in `goals` (the last-goal, if any, at the end). Where contingency
  // reserves leave no feasible place for any goal still to insert, and all of those can be forgone
  // and `left_out` is given, the order of the others is kept and those goals go into `left_out`
  // (more goals only spend more before each reserve, so none of them would fit later either);
  // else the answer is empty.
  std::vector<std::size_t> build(const std::vector<std::size_t>& goals,
                                 std::vector<std::size_t>* left_out = nullptr) {
    if (left_out != nullptr) left_out->clear();
    std::vector<std::size_t> order;
    std::optional<std::size_t> last;
    std::vector<std::size_t> todo;
    for (std::size_t g : goals) {
      if (s_.goals[g].last) {
        last = g;
      } else {
        todo.push_back(g);
      }
    }
    while (!todo.empty()) {  // cheapest insertion
      Cost best = kInfiniteCost;
      std::size_t best_goal = 0, best_at = 0;
      std::vector<std::size_t> full = order;
      if (last) full.push_back(*last);
      prepare(full);
      for (std::size_t i = 0; i < todo.size(); ++i) {
        if (check_stop()) return {};
        for (std::size_t at = 0; at <= order.size(); ++at) {
          const Cost c = inserted(at, todo[i]);
          if (c < best) {
            best = c;
            best_goal = i;
            best_at = at;
          }
        }
      }
      if (best >= kInfiniteCost) {
        // Issue 14: giving up here left the tour search without an answer whenever the reserves
        // called for dropping more than one goal, and the engines took seconds instead.
        const bool can_leave =
            left_out != nullptr && std::all_of(todo.begin(), todo.end(), [&](std::size_t g) {
              return s_.goals[g].forgo.has_value();
            });
        if (!can_leave || !fits_whole(order, last)) return {};
        *left_out = todo;
        break;
      }
      order.insert(order.begin() + static_cast<std::ptrdiff_t>(best_at), todo[best_goal]);
      todo.erase(todo.begin() + static_cast<std::ptrdiff_t>(best_goal));
    }
    // Stopped in the local search, the order is complete: the best one found by then (a caller
    // that needs a finished search asks stopped()).
    if (local_search_) improve(order, last);
    if (last) order.push_back(*last);
    return order;
  }

  Cost cost(const std::vector<std::size_t>& order) { return eval_.cost(order); }

  // Whether `order` followed by `last` (if any) can be done at all, reserves included.
  bool fits_whole(const std::vector<std::size_t>& order, std::optional<std::size_t> last) {
    std::vector<std::size_t> full = order;
    if (last) full.push_back(*last);
    return eval_.cost(full) < kInfiniteCost;
  }

  // `order` with goal g at its cheapest place (before the last-goal, if any); empty if none.
  std::vector<std::size_t> insert(const std::vector<std::size_t>& order, std::size_t g) {
    const bool has_last = !order.empty() && s_.goals[order.back()].last;
    const std::size_t places = order.size() - (has_last ? 1 : 0);
    Cost best = kInfiniteCost;
    std::optional<std::size_t> best_at;
    prepare(order);
    for (std::size_t at = 0; at <= places; ++at) {
      const Cost c = inserted(at, g);
      if (c < best) {
        best = c;
        best_at = at;
      }
    }
    if (!best_at) return {};
    std::vector<std::size_t> best_order = order;
    best_order.insert(best_order.begin() + static_cast<std::ptrdiff_t>(*best_at), g);
    return best_order;
  }

  // `order` improved by local search (the last-goal, if any, kept at the end).
  std::vector<std::size_t> polish(std::vector<std::size_t> order) {
    std::optional<std::size_t> last;
    if (!order.empty() && s_.goals[order.back()].last) {
      last = order.back();
      order.pop_back();
    }
    if (local_search_) improve(order, last);
    if (last) order.push_back(*last);
    return order;
  }

  // Checked once per row of trial orders, and within a row by check_after.
  bool check_stop() {
    work_ = 0;
    if (!stopped_) stopped_ = stop_.interrupted();
    return stopped_.has_value();
  }
  // Counts `work` (goals advanced over, OrderCosts' unit) and asks the stop condition once
  // kCheckWork of it has been done since the last check: a 2-opt row on 200 goals prices 20,000
  // advances, 0.5 to 1.2 ms between two checks (issue 14), and asking the clock at every trial
  // would cost more than the short trials themselves.
  bool check_after(std::size_t work) {
    work_ += work;
    if (work_ < kCheckWork) return stopped_.has_value();
    return check_stop();
  }
  Cost cost(const std::vector<std::size_t>& order, std::vector<ActionId>& plan) {
    return eval_.cost(order, &plan);
  }

 private:
  // Trial orders around the current one (`full`, set by prepare): priced from its costs
  // (tour_costs.h), or evaluated whole where contingency reserves make a move's feasibility depend
  // on what was spent before it, which those costs do not keep. Both price a trial as evaluating it
  // whole would.
  void prepare(const std::vector<std::size_t>& full) {
    current_ = full;
    if (!whole_) costs_.prepare(full);
  }
  Cost inserted(std::size_t at, std::size_t g) {
    if (!whole_) return costs_.inserted(at, g);
    trial_ = current_;
    trial_.insert(trial_.begin() + static_cast<std::ptrdiff_t>(at), g);
    return eval_.cost(trial_);
  }
  // out[j]: the goal at i moved to place j (j < places); the rest kInfiniteCost after a stop.
  void moved(std::size_t i, std::size_t places, std::vector<Cost>& out) {
    if (!whole_) {
      costs_.moved(i, places, out);
      check_after(2 * places);
      return;
    }
    out.assign(places, kInfiniteCost);
    for (std::size_t j = 0; j < places; ++j) {
      if (j == i) continue;
      if (check_after(current_.size())) return;
      trial_ = current_;
      trial_.erase(trial_.begin() + static_cast<std::ptrdiff_t>(i));
      trial_.insert(trial_.begin() + static_cast<std::ptrdiff_t>(j), current_[i]);
      out[j] = eval_.cost(trial_);
    }
  }
  // The stretch [i, j) reversed.
  Cost reversed(std::size_t i, std::size_t j) {
    if (!whole_) return costs_.reversed(i, j);
    trial_ = current_;
    std::reverse(trial_.begin() + static_cast<std::ptrdiff_t>(i),
                 trial_.begin() + static_cast<std::ptrdiff_t>(j));
    return eval_.cost(trial_);
  }

  // Or-opt (move one goal) and 2-opt (reverse a stretch) until neither helps, at most 50 rounds.
  // Trial orders are priced as above, and their costs read again after every change, so the moves
  // tried and taken are those of evaluating each trial whole.
  void improve(std::vector<std::size_t>& order, std::optional<std::size_t> last) {
    const std::size_t n = order.size();
    std::vector<std::size_t> full = order;
    if (last) full.push_back(*last);
    Cost best = eval_.cost(full);
    std::vector<Cost> moved_costs;
    for (int round = 0; round < 50; ++round) {
      bool better = false;
      prepare(full);
      for (std::size_t i = 0; i < n; ++i) {
        if (check_stop()) return write_back(full, order);
        moved(i, n, moved_costs);
        for (std::size_t j = 0; j < n; ++j) {
          if (i == j || moved_costs[j] >= best) continue;
          best = moved_costs[j];
          const std::size_t g = full[i];
          full.erase(full.begin() + static_cast<std::ptrdiff_t>(i));
          full.insert(full.begin() + static_cast<std::ptrdiff_t>(j), g);
          better = true;
          // Each accepted move re-prices the whole order: a row may accept many (issue 14).
          if (check_stop()) return write_back(full, order);
          prepare(full);
          moved(i, n, moved_costs);
        }
      }
      for (std::size_t i = 0; i + 1 < n; ++i) {
        if (check_stop()) return write_back(full, order);
        for (std::size_t j = i + 2; j <= n; ++j) {
          if (check_after(whole_ ? full.size() : j - i)) return write_back(full, order);
          const Cost c = reversed(i, j);
          if (c >= best) continue;
          best = c;
          std::reverse(full.begin() + static_cast<std::ptrdiff_t>(i),
                       full.begin() + static_cast<std::ptrdiff_t>(j));
          better = true;
          if (check_stop()) return write_back(full, order);
          prepare(full);
        }
      }
      if (!better) break;
    }
    write_back(full, order);
  }

  static void write_back(const std::vector<std::size_t>& full, std::vector<std::size_t>& order) {
    std::copy(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(order.size()),
              order.begin());
  }

  const Shape& s_;
  Evaluator eval_;
  detail::OrderCosts costs_;
  const bool whole_;
  const bool local_search_;
  std::vector<std::size_t> current_, trial_;
  const StopCondition& stop_;
  std::optional<SearchStatus> stopped_;
  static constexpr std::size_t kCheckWork = 2048;  // about 0.1 ms
  std::size_t work_ = 0;                           // since the last check
};

}  // namespace

std::optional<SearchResult> tour_search(const CompiledTask& task, const StopCondition& stop,
                                        const Clock* clock, TourReport* report) {
  const SteadyClock steady;
  const Clock& time = clock != nullptr ? *clock : steady;
  TourReport unused;
  const double start_s = time.now_s();
  return detail::tour_search(task, read_shape(task, &stop), stop, time, start_s,
                             report != nullptr ? *report : unused);
}

std::optional<SearchResult> detail::tour_search(const CompiledTask& task,
                                                const std::optional<Shape>& shape,
                                                const StopCondition& stop, const Clock& time,
                                                double start_s, TourReport& out,
                                                bool local_search) {
  out = {};
  // Reading the shape goes over every action, and asks the stop condition (issue 14).
  if (auto stopped = stop.interrupted()) {
    out.stopped = stopped;
    return std::nullopt;
  }
  if (!shape) return std::nullopt;
  out.has_shape = true;
  std::vector<std::size_t> goals(shape->goals.size());
  for (std::size_t i = 0; i < goals.size(); ++i) goals[i] = i;
  Tour tour(*shape, stop, local_search);
  std::vector<std::size_t> left_out;
  std::vector<std::size_t> order = tour.build(goals, &left_out);
  // The plan of an order of every goal, checked on the task; empty if it does not fit the bound.
  const auto plan_of = [&](const std::vector<std::size_t>& o,
                           const std::vector<std::size_t>& forgone) -> std::optional<SearchResult> {
    const Cost c = tour.cost(o);
    if (c >= kInfiniteCost || c > task.cost_bound()) return std::nullopt;
    SearchResult result;
    for (std::size_t g : forgone) result.plan.push_back(*shape->goals[g].forgo);
    tour.cost(o, result.plan);
    if (!task.solves(result.plan, &result.cost)) return std::nullopt;
    result.status = SearchStatus::kSolved;
    result.statistics.time_s = time.now_s() - start_s;
    return result;
  };
  if (tour.stopped()) {
    out.stopped = tour.stopped();
    // Stopped in the local search after the insertion gave an order of every goal: that order,
    // as far as the local search got, if it fits (the anytime answer, TourReport::best_so_far).
    if ((!order.empty() || goals.empty()) && left_out.empty()) {
      if (auto best = plan_of(order, {})) {
        out.best_so_far = true;
        return best;
      }
    }
    return std::nullopt;
  }
  if ((!order.empty() || goals.empty()) && left_out.empty()) out.cheapest_order = tour.cost(order);
  // Goals the reserves left no place for are forgone (build() lists only goals that can be); they
  // are offered again below once the order is final.
  std::vector<std::size_t> forgone = left_out;
  const auto forgo = [&](const std::vector<std::size_t>& gone) {
    for (std::size_t g : gone) goals.erase(std::find(goals.begin(), goals.end(), g));
  };
  forgo(left_out);
  bool put_back = !left_out.empty();
  // Over the bound (or no order at all): leave out, one at a time, the goal whose absence saves
  // the most, where goals can be forgone.
  auto fits = [&](const std::vector<std::size_t>& o) {
    const Cost c = tour.cost(o);
    return c < kInfiniteCost && c <= task.cost_bound();
  };
  // Up to kRebuildGoals goals, each candidate's tour is rebuilt without it; beyond, the candidate
  // is cut from the current tour, which is polished once the dropping is over (issue 16: a
  // rebuild per candidate and drop made 50 uniform tasks take minutes).
  constexpr std::size_t kRebuildGoals = 12;
  bool cut = false;
  while ((order.empty() && !goals.empty()) || !fits(order)) {
    std::optional<std::size_t> drop;
    // The fewest goals left out with it (by the reserves, in a rebuild), then the lowest cost.
    std::pair<std::size_t, Cost> best{0, kInfiniteCost};
    std::vector<std::size_t> best_order, best_left;
    const bool rebuild = order.empty() || goals.size() <= kRebuildGoals;
    for (std::size_t g : goals) {
      if (!shape->goals[g].forgo) continue;
      std::vector<std::size_t> rest;
      for (std::size_t h : rebuild ? goals : order) {
        if (h != g) rest.push_back(h);
      }
      std::vector<std::size_t> o = rebuild ? tour.build(rest, &left_out) : rest;
      if (!rebuild) left_out.clear();
      if (!rebuild && tour.check_stop()) break;
      if (tour.stopped()) {
        out.stopped = tour.stopped();
        return std::nullopt;
      }
      const bool none = o.empty() && rest.size() > left_out.size();
      const std::pair<std::size_t, Cost> c{left_out.size(), none ? kInfiniteCost : tour.cost(o)};
      if (c.second < kInfiniteCost && (!drop || c < best)) {
        best = c;
        drop = g;
        best_order = std::move(o);
        best_left = left_out;
      }
    }
    if (tour.stopped()) {
      out.stopped = tour.stopped();
      return std::nullopt;
    }
    if (!drop) return std::nullopt;
    cut = cut || !rebuild;
    put_back = put_back || !best_left.empty();
    best_left.push_back(*drop);
    forgo(best_left);
    forgone.insert(forgone.end(), best_left.begin(), best_left.end());
    order = std::move(best_order);
    if (goals.empty()) break;
  }
  if (cut || put_back) {
    order = tour.polish(std::move(order));
    // Cutting can leave room: put back, cheapest first, each forgone goal that still fits.
    for (bool added = true; added && !forgone.empty();) {
      added = false;
      Cost best = kInfiniteCost;
      std::size_t best_goal = 0;
      std::vector<std::size_t> best_order;
      for (std::size_t i = 0; i < forgone.size(); ++i) {
        if (tour.check_stop()) break;
        std::vector<std::size_t> trial = tour.insert(order, forgone[i]);
        const Cost c = trial.empty() ? kInfiniteCost : tour.cost(trial);
        if (c <= task.cost_bound() && c < best) {
          best = c;
          best_goal = i;
          best_order = std::move(trial);
        }
      }
      if (best < kInfiniteCost) {
        order = std::move(best_order);
        forgone.erase(forgone.begin() + static_cast<std::ptrdiff_t>(best_goal));
        added = true;
      }
    }
    if (tour.stopped()) {
      out.stopped = tour.stopped();
      return std::nullopt;
    }
  }
  // Checked on the task itself.
  return plan_of(order, forgone);
}

std::optional<SearchResult> greedy_tour(const CompiledTask& task, const StopCondition& stop,
                                        const Clock* clock) {
  const SteadyClock steady;
  const Clock& time = clock != nullptr ? *clock : steady;
  TourReport report;
  const double start_s = time.now_s();
  return detail::tour_search(task, read_shape(task, &stop), stop, time, start_s, report,
                             /*local_search=*/false);
}

std::optional<SearchResult> ordered_tour(const CompiledTask& task, std::span<const VarId> order,
                                         const StopCondition& stop) {
  const std::optional<Shape> shape = read_shape(task, &stop);
  if (!shape || stop.interrupted()) return std::nullopt;
  const std::size_t n = shape->goals.size();
  std::vector<bool> chosen(n, false);
  std::vector<std::size_t> goals;
  std::optional<std::size_t> last;
  for (VarId v : order) {
    if (v.index() == 0 || v.index() > n || chosen[v.index() - 1]) return std::nullopt;
    const std::size_t g = v.index() - 1;
    chosen[g] = true;
    if (shape->goals[g].last) {
      last = g;  // it needs every other goal done: at the end wherever it was given
    } else {
      goals.push_back(g);
    }
  }
  std::vector<std::size_t> forgone;
  for (std::size_t g = 0; g < n; ++g) {
    if (chosen[g]) continue;
    if (!shape->goals[g].forgo) return std::nullopt;
    forgone.push_back(g);
  }
  Tour tour(*shape, stop, /*local_search=*/false);
  const auto with_last = [&](std::vector<std::size_t> o) {
    if (last) o.push_back(*last);
    return o;
  };
  const auto fits = [&](const std::vector<std::size_t>& o) {
    const Cost c = tour.cost(with_last(o));
    return c < kInfiniteCost && c <= task.cost_bound();
  };
  // Over the bound: leave out, one at a time, the goal whose absence costs the least, keeping the
  // order of the rest.
  while (!fits(goals)) {
    std::optional<std::size_t> drop;
    Cost best = kInfiniteCost;
    for (std::size_t i = 0; i < goals.size(); ++i) {
      if (!shape->goals[goals[i]].forgo) continue;
      std::vector<std::size_t> rest = goals;
      rest.erase(rest.begin() + static_cast<std::ptrdiff_t>(i));
      const Cost c = tour.cost(with_last(rest));
      if (!drop || c < best) {
        best = c;
        drop = i;
      }
    }
    if (!drop) return std::nullopt;
    forgone.push_back(goals[*drop]);
    goals.erase(goals.begin() + static_cast<std::ptrdiff_t>(*drop));
  }
  SearchResult result;
  for (std::size_t g : forgone) result.plan.push_back(*shape->goals[g].forgo);
  tour.cost(with_last(goals), result.plan);
  if (!task.solves(result.plan, &result.cost)) return std::nullopt;
  result.status = SearchStatus::kSolved;
  return result;
}

}  // namespace sewerplan::search
