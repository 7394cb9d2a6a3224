// SPDX-License-Identifier: MIT
// The exact tour search (tour_search.h): dynamic programming over subsets of goals, after Held and
// Karp (1962, "A dynamic programming approach to sequencing problems", J. SIAM 10(1)).
//
// best[S][e]: the cheapest way from the start to do exactly the goals in S, the last of them
// leaving the robot at its e-th leave place (each goal's few leave places are flattened into one
// index). Each entry extends by every goal not in S and every action that does it; an entry
// beyond the bound is dropped (costs are not negative). The optimum is then the best S (all
// goals, or with optional goals the most that fit and then the cheapest) closed by the move to
// the end position. The table holds for each S only the leave places of the goals in S (issue
// 16: the others are never reached, and a table twice the size cost a fifth of the whole
// process's page faults on 10 manholes). Memory: 2^(K-1) x (leave places) x 12 bytes; time:
// that x K x options.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <memory>

#include "sewerplan/search/tour_search.h"

#include "tour_shape.h"

namespace sewerplan::search {
namespace {

using detail::kStays;
using detail::Shape;
using domain::kInfiniteCost;

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

class SubsetProgramme {
 public:
  // `upper`: only plans doing every goal within this cost are wanted (kInfiniteCost: any).
  // Reads the goals' leave places only: run() allocates the rest (memory_bytes()).
  SubsetProgramme(const Shape& shape, Cost bound, Cost upper)
      : s_(shape), bound_(bound), upper_(upper) {
    const std::size_t k = s_.goals.size();
    leave_begin_.push_back(0);
    for (std::size_t g = 0; g < k; ++g) {
      for (const detail::Option& o : s_.goals[g].options) {
        const std::int32_t at = leave(o);
        const auto first = leave_place_.begin() + leave_begin_[g];
        if (std::find(first, leave_place_.end(), at) == leave_place_.end()) {
          leave_place_.push_back(at);
          leave_goal_.push_back(static_cast<std::uint32_t>(g));
        }
      }
      leave_begin_.push_back(static_cast<std::uint32_t>(leave_place_.size()));
      leave_count_.push_back(leave_begin_[g + 1] - leave_begin_[g]);
    }
    width_ = leave_place_.size();
    for (std::size_t g = 0; g < k; ++g) options_ += s_.goals[g].options.size();
    all_ = k == 0 ? 0U : static_cast<std::uint32_t>((std::uint64_t{1} << k) - 1);
    for (std::size_t g = 0; g < k; ++g) {
      if (s_.goals[g].last) last_mask_ |= 1U << g;
    }
  }

  // What run() allocates: the table (a cost and a parent for each subset and leave place of a
  // goal in it: each leave place is in half the subsets), the table's offsets, the limits and
  // marks by subset, the moves between places and the steps (one per leave place or the start,
  // and option).
  std::size_t memory_bytes() const {
    const std::size_t subsets = std::size_t{1} << s_.goals.size();
    const auto places = static_cast<std::size_t>(s_.places);
    return subsets / 2 * width_ * (sizeof(Cost) + sizeof(std::uint32_t)) +
           (subsets + 1) * sizeof(std::size_t) + subsets * (sizeof(Cost) + sizeof(std::uint8_t)) +
           places * places * sizeof(Cost) + (width_ + 1) * options_ * sizeof(Step) +
           ((width_ + 1) * s_.goals.size() + 1) * sizeof(std::uint32_t);
  }

  // Fills the table; returns the stop condition's reason if it fired.
  std::optional<SearchStatus> run(const StopCondition& stop, std::uint64_t* entries) {
    fill_moves();
    const std::size_t subsets = std::size_t{1} << s_.goals.size();
    if (upper_ < kInfiniteCost) {
      if (auto why = fill_rest_bounds(stop)) return why;
    } else {
      limit_.assign(subsets, bound_);
    }
    fill_steps();
    fill_offsets();
    reached_.assign(subsets, 0);
    cost_.assign(offset_.back(), kInfiniteCost);
    // A parent is written with its entry's cost and read only where that is finite: left as the
    // allocator gives it, the pages of entries never reached are never touched.
    parent_ = std::make_unique_for_overwrite<std::uint32_t[]>(offset_.back());
    extend(0, width_, kNone, 0);
    for (std::uint32_t set = 1; set < subsets; ++set) {
      if ((set & 0xffU) == 1) {
        if (auto why = stop.interrupted()) return why;
      }
      if (reached_[set] == 0) continue;           // no entry of it
      const bool last = (set & last_mask_) != 0;  // nothing follows a last goal
      // The entries of `set`: its goals' leave places, in order.
      std::size_t index = offset_[set];
      for (std::uint32_t in = set; in != 0; in &= in - 1) {
        const auto g = static_cast<std::size_t>(std::countr_zero(in));
        for (std::uint32_t e = leave_begin_[g]; e < leave_begin_[g + 1]; ++e, ++index) {
          const Cost c = cost_[index];
          if (c >= kInfiniteCost) continue;
          ++*entries;
          if (!last) extend(set, e, e, c);
        }
      }
    }
    return std::nullopt;
  }

  // The cost of ending after exactly the goals in `set` (kInfiniteCost: impossible), and the
  // leave index it ends from (kNone: the start, for the empty set).
  std::pair<Cost, std::uint32_t> close(std::uint32_t set) const {
    auto tail = [&](std::int32_t at) {
      return s_.end ? moves_[static_cast<std::size_t>(at) * static_cast<std::size_t>(s_.places) +
                             static_cast<std::size_t>(*s_.end)]
                    : Cost{0};
    };
    // The way to the end needs its contingency reserve too (CompiledTask::reserve).
    auto reserve = [&](std::int32_t at) { return s_.end ? s_.move_reserve(at, *s_.end) : 0; };
    if (set == 0) {
      const Cost t = tail(s_.start);
      return {t < kInfiniteCost && s_.fits(0, t, reserve(s_.start)) ? t : kInfiniteCost, kNone};
    }
    Cost best = kInfiniteCost;
    std::uint32_t from = kNone;
    std::size_t index = offset_[set];
    for (std::uint32_t in = set; in != 0; in &= in - 1) {
      const auto g = static_cast<std::size_t>(std::countr_zero(in));
      for (std::uint32_t e = leave_begin_[g]; e < leave_begin_[g + 1]; ++e, ++index) {
        const Cost c = cost_[index];
        const Cost t = tail(leave_place_[e]);
        if (c >= kInfiniteCost || t >= kInfiniteCost || c + t > bound_) continue;
        if (!s_.fits(c, t, reserve(leave_place_[e]))) continue;
        if (c + t < best) {
          best = c + t;
          from = e;
        }
      }
    }
    return {best, from};
  }

  // The actions of the best way to do `set`, ending from leave index `e`.
  void plan(std::uint32_t set, std::uint32_t e, std::vector<ActionId>& out) const {
    std::vector<ActionId> reversed;
    std::int32_t after = s_.end.value_or(e == kNone ? s_.start : leave_place_[e]);
    while (e != kNone) {
      const std::uint32_t packed = parent_[entry(set, e)];
      const std::uint32_t g = leave_goal_[e];
      const detail::Option& o = s_.goals[g].options[packed & 0xffU];
      const std::uint32_t prev = packed >> 8U;
      const std::int32_t place = leave(o);
      add_move(place, after, reversed);
      reversed.push_back(o.action);
      after = o.at;
      set &= ~(1U << g);
      e = prev == (kNone >> 8U) ? kNone : prev;
    }
    add_move(s_.start, after, reversed);
    out.insert(out.end(), reversed.rbegin(), reversed.rend());
  }

 private:
  // One way to do a goal from where the robot is (a leave place or the start): the move to the
  // option's place and the option. Sorted cheapest first, so extend() stops at the first beyond
  // its limit.
  struct Step {
    Cost cost = 0;  // the move's and the option's
    // The most that may be spent before it for its reserves (and the move's) to fit the battery
    // (Shape::fits); the largest Cost where there are none.
    Cost most_spent = 0;
    std::uint32_t slot = 0;    // the option's leave index
    std::uint32_t option = 0;  // the option's index in its goal
  };

  static std::int32_t leave(const detail::Option& o) { return o.to == kStays ? o.at : o.to; }

  void add_move(std::int32_t a, std::int32_t b, std::vector<ActionId>& reversed) const {
    if (a != b) reversed.push_back(s_.move_action(a, b));
  }

  // Where the table holds leave index `e` of `set` (its goal in `set`): after the leave places of
  // the goals of `set` before it.
  std::size_t entry(std::uint32_t set, std::uint32_t e) const {
    const std::uint32_t g = leave_goal_[e];
    std::size_t index = offset_[set] + (e - leave_begin_[g]);
    for (std::uint32_t before = set & ((1U << g) - 1U); before != 0; before &= before - 1) {
      const auto h = static_cast<std::size_t>(std::countr_zero(before));
      index += leave_count_[h];
    }
    return index;
  }

  void fill_moves() {
    const auto places = static_cast<std::size_t>(s_.places);
    moves_.assign(places * places, kInfiniteCost);
    for (std::size_t a = 0; a < places; ++a) {
      for (std::size_t b = 0; b < places; ++b) {
        moves_[a * places + b] =
            s_.move_cost(static_cast<std::int32_t>(a), static_cast<std::int32_t>(b));
      }
    }
  }

  // offset_[set]: where the entries of `set` begin (each of its goals' leave places, in order).
  // A set holds the entries of itself without its lowest goal (a smaller set, counted already)
  // and that goal's leave places.
  void fill_offsets() {
    const std::size_t subsets = std::size_t{1} << s_.goals.size();
    offset_.assign(subsets + 1, 0);
    for (std::size_t set = 1; set < subsets; ++set) {
      const std::size_t rest = set & (set - 1);
      const std::size_t n = offset_[rest + 1] - offset_[rest] +
                            leave_count_[static_cast<std::size_t>(std::countr_zero(set))];
      offset_[set + 1] = offset_[set] + n;
    }
  }

  // The steps from each leave place (and from the start, row width_) to each goal. A step no
  // entry can take (no move, beyond the bound, reserves that never fit) is left out; what
  // extend() read from the moves and the reserves at each entry is read here once.
  void fill_steps() {
    const std::size_t k = s_.goals.size();
    const bool reserves = s_.has_reserves();
    step_begin_.assign(1, 0);
    steps_.clear();
    steps_.reserve((width_ + 1) * options_);
    for (std::size_t row = 0; row <= width_; ++row) {
      const std::int32_t at = row == width_ ? s_.start : leave_place_[row];
      for (std::size_t g = 0; g < k; ++g) {
        const std::size_t first = steps_.size();
        const auto& options = s_.goals[g].options;
        for (std::size_t o = 0; o < options.size(); ++o) {
          const detail::Option& opt = options[o];
          const Cost d = move(at, opt.at);
          if (d >= kInfiniteCost || d + opt.cost > bound_) continue;
          Step step{.cost = d + opt.cost,
                    .most_spent = std::numeric_limits<Cost>::max(),
                    .slot = slot(g, opt),
                    .option = static_cast<std::uint32_t>(o)};
          if (reserves && s_.bound < kInfiniteCost) {
            if (const Cost r = s_.move_reserve(at, opt.at); r > 0) {
              step.most_spent = std::min(step.most_spent, s_.bound - d - r);
            }
            if (opt.reserve > 0) {
              step.most_spent = std::min(step.most_spent, s_.bound - step.cost - opt.reserve);
            }
            if (step.most_spent < 0) continue;  // nothing spent is less than 0
          }
          steps_.push_back(step);
        }
        // Cheapest first; of equal costs the lower option first, as a loop over the options
        // would find them (the first of equal costs is kept: the same plan).
        std::stable_sort(steps_.begin() + static_cast<std::ptrdiff_t>(first), steps_.end(),
                         [](const Step& a, const Step& b) { return a.cost < b.cost; });
        step_begin_.push_back(static_cast<std::uint32_t>(steps_.size()));
      }
    }
  }
  std::uint32_t slot(std::size_t g, const detail::Option& o) const {
    std::uint32_t slot = leave_begin_[g];
    while (leave_place_[slot] != leave(o)) ++slot;
    return slot;
  }

  // Extends the entry of `set` at leave index `row` (width_: the start, for the empty set), of
  // cost `c`, by every goal outside `set`. A goal that needs all others first ends the plan:
  // nothing follows it (the others are done or forgone, and forgo actions come first).
  void extend(std::uint32_t set, std::size_t row, std::uint32_t e, Cost c) {
    const std::uint32_t from = (e == kNone ? (kNone >> 8U) : e) << 8U;
    const std::uint32_t* begin = step_begin_.data() + row * s_.goals.size();
    // The goals outside `set`, lowest first (as a loop over every goal skipping those in it).
    // `skipped`: the leave places of the goals outside `set` before g, which the entries of
    // set | g do not hold (entry()).
    std::size_t skipped = 0;
    for (std::uint32_t outside = all_ & ~set; outside != 0; outside &= outside - 1) {
      const auto g = static_cast<std::size_t>(std::countr_zero(outside));
      const std::uint32_t next = set | (1U << g);
      const Cost limit = limit_[next];
      Cost* costs = cost_.data() + (offset_[next] - skipped);
      std::uint32_t* parents = parent_.get() + (offset_[next] - skipped);
      skipped += leave_count_[g];
      const Step* end = steps_.data() + begin[g + 1];
      for (const Step* step = steps_.data() + begin[g]; step != end; ++step) {
        const Cost nc = c + step->cost;
        if (nc > limit) break;  // and every step after it
        if (c > step->most_spent) continue;
        if (nc < costs[step->slot]) {
          costs[step->slot] = nc;
          parents[step->slot] = from | step->option;
          reached_[next] = 1;
        }
      }
    }
  }
  // With an upper bound U on plans doing every goal (issue 16: the tour search's plan, when it
  // forgoes none), an entry for S costing c can only lead to a wanted plan if c plus the least
  // the goals outside S (call them O) still cost stays within U. Every goal of O is done by one
  // of its options after a move into the place it needs: the first from where the robot is (at
  // least least[g]: from the start or where any other goal leaves it), each later one from where
  // another goal of O left it (at least into[g]: pair[h][g] over h in O). So the rest costs at
  // least the sum of into[g] over O, less the largest into[f] - least[f] (f done first), plus
  // the cheapest way to the end from where a goal of O leaves the robot. Pruning with it keeps
  // every entry of a plan within U, and so the same plan. Fills limit_ with U less that bound.
  // Returns the stop condition's reason if it fired (2^k subsets: checked every 2^10).
  std::optional<SearchStatus> fill_rest_bounds(const StopCondition& stop) {
    const std::size_t k = s_.goals.size();
    std::vector<Cost> least(k, kInfiniteCost);
    std::vector<Cost> tail(k, kInfiniteCost);
    std::vector<Cost> pair(k * k, kInfiniteCost);  // [h * k + g]: from h's leave places into g
    for (std::size_t g = 0; g < k; ++g) {
      for (const detail::Option& o : s_.goals[g].options) {
        const Cost in = least_move_into(g, o.at);
        if (in < kInfiniteCost) least[g] = std::min(least[g], in + o.cost);
        tail[g] = std::min(tail[g], s_.end ? move(leave(o), *s_.end) : Cost{0});
        for (std::size_t h = 0; h < k; ++h) {
          if (h == g) continue;
          for (std::uint32_t e = leave_begin_[h]; e < leave_begin_[h + 1]; ++e) {
            const Cost d = move(leave_place_[e], o.at);
            if (d < kInfiniteCost) pair[h * k + g] = std::min(pair[h * k + g], d + o.cost);
          }
        }
      }
      if (least[g] >= kInfiniteCost) least[g] = 0;  // not wanted anyway; keep the sums finite
      if (tail[g] >= kInfiniteCost) tail[g] = 0;
    }
    // By goal g: the other goals, nearest first (pair[h][g] ascending), so that the nearest still
    // outside a subset is found in a step or two.
    std::vector<std::uint32_t> nearest;
    nearest.reserve(k * k);
    for (std::size_t g = 0; g < k; ++g) {
      const auto first = static_cast<std::ptrdiff_t>(nearest.size());
      for (std::uint32_t h = 0; h < k; ++h) {
        if (h != g) nearest.push_back(h);
      }
      std::stable_sort(
          nearest.begin() + first, nearest.end(),
          [&](std::uint32_t x, std::uint32_t y) { return pair[x * k + g] < pair[y * k + g]; });
    }
    const std::size_t others = k == 0 ? 0 : k - 1;
    const std::size_t subsets = std::size_t{1} << k;
    limit_.assign(subsets, std::min(bound_, upper_));  // all goals done: nothing rests
    const auto all = static_cast<std::uint32_t>(subsets - 1);
    for (std::uint32_t set = 0; set < all; ++set) {
      if ((set & 0x3ffU) == 0) {
        if (auto why = stop.interrupted()) return why;
      }
      const std::uint32_t outside = all & ~set;
      Cost sum = 0;
      Cost first_gain = 0;  // the largest into[f] - least[f]
      Cost last = kInfiniteCost;
      for (std::uint32_t gs = outside; gs != 0; gs &= gs - 1) {
        const auto g = static_cast<std::size_t>(std::countr_zero(gs));
        Cost into = kInfiniteCost;
        for (std::size_t i = g * others; i < (g + 1) * others; ++i) {
          if ((outside & (1U << nearest[i])) != 0) {
            into = pair[nearest[i] * k + g];
            break;
          }
        }
        into = std::max(least[g], into >= kInfiniteCost ? least[g] : into);
        sum += into;
        first_gain = std::max(first_gain, into - least[g]);
        last = std::min(last, tail[g]);
      }
      limit_[set] = std::min(bound_, upper_ - (sum - first_gain + last));
    }
    return std::nullopt;
  }
  // The cheapest move into `at` from where the robot can be before doing `goal`: the start or a
  // place another goal leaves it at (none if it is there already).
  Cost least_move_into(std::size_t goal, std::int32_t at) const {
    Cost in = move(s_.start, at);
    for (std::size_t h = 0; h < s_.goals.size(); ++h) {
      if (h == goal) continue;
      for (std::uint32_t e = leave_begin_[h]; e < leave_begin_[h + 1]; ++e) {
        in = std::min(in, move(leave_place_[e], at));
      }
    }
    return in;
  }
  Cost move(std::int32_t a, std::int32_t b) const {
    return a == b ? 0
                  : moves_[static_cast<std::size_t>(a) * static_cast<std::size_t>(s_.places) +
                           static_cast<std::size_t>(b)];
  }

  const Shape& s_;
  Cost bound_;
  Cost upper_;
  // By subset: the most an entry of it may cost (bound_; with an upper bound, less what the goals
  // outside it cost at least: fill_rest_bounds()).
  std::vector<Cost> limit_;
  std::vector<std::uint8_t> reached_;       // by subset: whether an entry of it was written
  std::uint32_t all_ = 0;                   // every goal's bit
  std::vector<std::uint32_t> leave_begin_;  // by goal, into leave_place_
  std::vector<std::int32_t> leave_place_;   // flattened leave places
  std::vector<std::uint32_t> leave_goal_;   // the goal of each
  std::vector<std::uint32_t> leave_count_;  // by goal
  std::size_t width_ = 0;
  std::size_t options_ = 0;  // all goals' options
  std::uint32_t last_mask_ = 0;
  std::vector<Cost> moves_;                  // places x places
  std::vector<Step> steps_;                  // by row (leave index, then the start) and goal
  std::vector<std::uint32_t> step_begin_;    // [row * goals + goal], into steps_
  std::vector<std::size_t> offset_;          // by subset, into the table (fill_offsets())
  std::vector<Cost> cost_;                   // the table's costs
  std::unique_ptr<std::uint32_t[]> parent_;  // beside cost_: (previous leave index << 8) | option
};

}  // namespace

std::optional<SearchResult> exact_tour_search(const domain::CompiledTask& task,
                                              const StopCondition& stop, const Clock* clock,
                                              std::size_t max_bytes, Cost upper) {
  const SteadyClock steady;
  const Clock& time = clock != nullptr ? *clock : steady;
  const double start_s = time.now_s();
  return detail::exact_tour_search(task, detail::read_shape(task, &stop), stop, time, start_s,
                                   max_bytes, upper);
}

std::optional<SearchResult> detail::exact_tour_search(const domain::CompiledTask& task,
                                                      const std::optional<Shape>& shape,
                                                      const StopCondition& stop, const Clock& time,
                                                      double start_s, std::size_t max_bytes,
                                                      Cost upper) {
  if (auto stopped = stop.interrupted(); stopped && !shape) {
    SearchResult r;
    r.status = *stopped;
    r.statistics.time_s = time.now_s() - start_s;
    return r;
  }
  if (!shape || shape->goals.size() > kMaxExactGoals) return std::nullopt;
  for (const auto& g : shape->goals) {
    if (g.options.size() > 0xff) return std::nullopt;
  }
  const Cost bound =
      task.cost_bound() >= domain::kInfiniteCost ? domain::kInfiniteCost / 2 : task.cost_bound();
  SubsetProgramme programme(*shape, bound, upper);
  if (programme.memory_bytes() > max_bytes) return std::nullopt;
  SearchResult result;
  if (auto why = programme.run(stop, &result.statistics.expanded)) {
    result.status = *why;
    result.statistics.time_s = time.now_s() - start_s;
    return result;
  }
  // The best subset: every goal that cannot be forgone, then the most goals, then the cheapest.
  const std::size_t k = shape->goals.size();
  std::uint32_t required = 0;
  for (std::size_t g = 0; g < k; ++g) {
    if (!shape->goals[g].forgo) required |= 1U << g;
  }
  std::optional<std::uint32_t> best_set;
  Cost best_total = kInfiniteCost;
  int best_count = -1;
  std::uint32_t best_from = 0;
  for (std::uint32_t set = 0; set < (std::uint32_t{1} << k); ++set) {
    if ((set & required) != required) continue;
    const auto [c, from] = programme.close(set);
    if (c >= kInfiniteCost) continue;
    const int count = std::popcount(set);
    if (count > best_count || (count == best_count && c < best_total)) {
      best_set = set;
      best_total = c;
      best_count = count;
      best_from = from;
    }
  }
  result.statistics.time_s = time.now_s() - start_s;
  if (!best_set) {
    result.status = SearchStatus::kUnsolvable;  // proven: no subset fits the bound
    return result;
  }
  for (std::size_t g = 0; g < k; ++g) {
    if ((*best_set & (1U << g)) == 0) result.plan.push_back(*shape->goals[g].forgo);
  }
  programme.plan(*best_set, best_from, result.plan);
  if (!task.solves(result.plan, &result.cost)) return std::nullopt;  // not of the shape after all
  result.status = SearchStatus::kSolved;
  return result;
}

}  // namespace sewerplan::search
