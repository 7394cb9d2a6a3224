// SPDX-License-Identifier: MIT
#include "sewerplan/executor/replanner.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "sewerplan/core/enum_names.h"
#include "sewerplan/domain/validator.h"

namespace sewerplan::executor {
namespace {

// The stable names of failures, decisions and rungs (replanner.h): the event log and every CLI
// --json output carry them.
constexpr detail::EnumNames<Failure::Kind, 4> kFailureKinds{{
    {Failure::Kind::kBlockage, "blockage"},
    {Failure::Kind::kDangerInPipe, "danger"},
    {Failure::Kind::kDangerousPassage, "dangerous passage"},
    {Failure::Kind::kStuck, "stuck"},
}};

constexpr detail::EnumNames<PlanResponse::Decision, 6> kDecisions{{
    {PlanResponse::Decision::kFollowPlan, "follow-plan"},
    {PlanResponse::Decision::kDegraded, "degraded"},
    {PlanResponse::Decision::kExitOnReserve, "exit-on-reserve"},
    {PlanResponse::Decision::kCallForRecovery, "call-for-recovery"},
    {PlanResponse::Decision::kStuck, "stuck"},
    {PlanResponse::Decision::kInvalidReport, "invalid-report"},
}};

constexpr detail::EnumNames<PlanResponse::Rung, 6> kRungs{{
    {PlanResponse::Rung::kSearch, "search"},
    {PlanResponse::Rung::kBestSoFar, "best-so-far"},
    {PlanResponse::Rung::kCurrentPlan, "current-plan"},
    {PlanResponse::Rung::kRepairedPlan, "repaired-plan"},
    {PlanResponse::Rung::kGreedy, "greedy"},
    {PlanResponse::Rung::kNearestExit, "nearest-exit"},
}};

static_assert(kRungs.size() == PlanResponse::kRungCount);
static_assert(detail::distinct(kFailureKinds) && detail::distinct(kDecisions) &&
              detail::distinct(kRungs));

std::string metres(double v) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << v << " m";
  return out.str();
}

// A planner's message on one line: "the mission cannot be ended:\n  - a\n  - b" -> "a; b".
std::string one_line(const std::string& message) {
  std::string out;
  std::size_t pos = message.find("\n  - ");
  if (pos == std::string::npos) return message;
  while (pos != std::string::npos) {
    const std::size_t next = message.find("\n  - ", pos + 5);
    out += (out.empty() ? "" : "; ") +
           message.substr(pos + 5, next == std::string::npos ? std::string::npos : next - pos - 5);
    pos = next;
  }
  return out;
}

bool has_task(const std::vector<domain::DroppedTask>& list, TaskId t) {
  return std::any_of(list.begin(), list.end(),
                     [&](const domain::DroppedTask& d) { return d.task == t; });
}

// The same place of the robot; offsets in a pipe within a micrometre (the executor's tracker
// computes them from the jobs' progress, the replay from the plan's steps).
bool same_place(const domain::RobotPosition& a, const domain::RobotPosition& b) {
  const auto* in_a = std::get_if<domain::InPipe>(&a);
  const auto* in_b = std::get_if<domain::InPipe>(&b);
  if (in_a != nullptr && in_b != nullptr) {
    return in_a->pipe == in_b->pipe && std::abs(in_a->offset_m - in_b->offset_m) < 1e-6;
  }
  return a == b;
}

// Beliefs about the same hazard: the same pipe and reason, the offset within a micrometre.
bool same_belief(const HazardBelief& a, const HazardBelief& b) {
  return same_hazard(a, Hazard{b.pipe, b.offset_m, b.probability, b.reason});
}

}  // namespace

std::string_view to_string(Failure::Kind kind) { return detail::name_of(kFailureKinds, kind); }
std::optional<Failure::Kind> parse_failure_kind(std::string_view name) {
  return detail::value_of(kFailureKinds, name);
}

std::string_view to_string(PlanResponse::Decision decision) {
  return detail::name_of(kDecisions, decision);
}
std::optional<PlanResponse::Decision> parse_decision(std::string_view name) {
  return detail::value_of(kDecisions, name);
}

std::string_view to_string(PlanResponse::Rung rung) { return detail::name_of(kRungs, rung); }
std::optional<PlanResponse::Rung> parse_rung(std::string_view name) {
  return detail::value_of(kRungs, name);
}

bool has_plan(PlanResponse::Decision decision) {
  return decision == PlanResponse::Decision::kFollowPlan ||
         decision == PlanResponse::Decision::kDegraded ||
         decision == PlanResponse::Decision::kExitOnReserve;
}

bool calls_beacon(PlanResponse::Decision decision) {
  return decision == PlanResponse::Decision::kCallForRecovery ||
         decision == PlanResponse::Decision::kStuck;
}

Replanner::Replanner(const SewerMap& map, Mission mission, ReplannerOptions options)
    : map_(map),
      mission_(std::move(mission)),
      options_(options),
      progress_(domain::initial_progress(mission_, map)),
      reserve_fraction_(mission_.battery_reserve_fraction) {
  options_.planner.select_goals = true;
}

Result<PlanResponse> Replanner::plan_cancellable(const std::optional<Failure>& failure,
                                                 const std::string& reason,
                                                 const std::atomic<bool>& cancel) {
  background_cancel_ = &cancel;
  cancelled_ = false;
  PlanResponse r = failure ? report_failure(*failure) : plan(reason);
  const bool cancelled = cancelled_;
  background_cancel_ = nullptr;
  cancelled_ = false;
  if (cancelled) return Error{ErrorCode::kCancelled, "the replan was cancelled"};
  return r;
}

Result<void> Replanner::use_route_index(domain::RouteIndex index) {
  return compile_cache_->use_route_index(std::move(index), map_, mission_.profile,
                                         mission_.passage_motion);
}

Result<void> Replanner::learn(const Learnt& learnt) {
  if (auto ok = localisation::check_memory(learnt.junctions, map_); !ok.has_value()) return ok;
  for (const HazardBelief& h : learnt.hazards) {
    if (auto ok = check_hazard_belief(h, map_); !ok.has_value()) return ok;
  }
  for (const Blockage& b : learnt.blockages) {
    if (auto ok = check_failure(
            {.kind = Failure::Kind::kBlockage, .pipe = b.pipe, .offset_m = b.offset_m}, map_);
        !ok.has_value()) {
      return ok;
    }
  }
  for (const Blockage& b : learnt.danger_spots) {
    if (auto ok = check_failure(
            {.kind = Failure::Kind::kDangerInPipe, .pipe = b.pipe, .offset_m = b.offset_m}, map_);
        !ok.has_value()) {
      return ok;
    }
  }
  for (const ClosedPassage& p : learnt.closed_passages) {
    if (auto ok = check_failure({.kind = Failure::Kind::kDangerousPassage,
                                 .manhole = p.manhole,
                                 .from = p.from,
                                 .to = p.to},
                                map_);
        !ok.has_value()) {
      return ok;
    }
  }
  mission_ = with_learnt(std::move(mission_), learnt);
  const auto append = [](auto& to, const auto& from) {
    to.insert(to.end(), from.begin(), from.end());
  };
  append(learnt_.blockages, learnt.blockages);
  append(learnt_.danger_spots, learnt.danger_spots);
  append(learnt_.closed_passages, learnt.closed_passages);
  for (const HazardBelief& h : learnt.hazards) {
    auto same = std::find_if(learnt_.hazards.begin(), learnt_.hazards.end(),
                             [&](const HazardBelief& b) { return same_belief(b, h); });
    if (same != learnt_.hazards.end()) {
      *same = h;
    } else {
      learnt_.hazards.push_back(h);
    }
  }
  if (!learnt.junctions.empty()) learnt_.junctions = learnt.junctions;
  return {};
}

Result<std::vector<HazardUpdate>> Replanner::observe_pass(PipeId pipe, double from_m, double to_m) {
  return observe_driven(pipe, from_m, to_m, 0);
}

Result<std::vector<HazardUpdate>> Replanner::observe_stop(PipeId pipe, double from_m,
                                                          double stop_m) {
  return observe_driven(pipe, from_m, stop_m, options_.hazard_learning.blockage_match_m);
}

namespace {

// A pass report's pipe and offsets on the map, or why not.
Result<void> check_driven(const SewerMap& map, PipeId pipe, double from_m, double to_m) {
  if (pipe.index() >= map.pipe_count()) {
    return Error{ErrorCode::kInvalidArgument,
                 "invalid pass report: unknown pipe #" + std::to_string(pipe.index())};
  }
  const Pipe& driven = map.pipe(pipe);
  for (double offset : {from_m, to_m}) {
    if (!std::isfinite(offset) || offset < 0 || offset > driven.length_m) {
      std::ostringstream out;
      out << "invalid pass report: offset " << offset << " m is outside pipe " << driven.name
          << " (0 to " << driven.length_m << " m)";
      return Error{ErrorCode::kInvalidArgument, out.str()};
    }
  }
  return {};
}

}  // namespace

Result<std::vector<Blockage>> Replanner::drove_through(PipeId pipe, double from_m, double to_m) {
  if (Result<void> ok = check_driven(map_, pipe, from_m, to_m); !ok.has_value()) return ok.error();
  const double lo = std::min(from_m, to_m) + kDroveThroughMarginM;
  const double hi = std::max(from_m, to_m) - kDroveThroughMarginM;
  const auto inside = [&](const Blockage& b) {
    return b.pipe == pipe && b.offset_m > lo && b.offset_m < hi;
  };
  std::vector<Blockage> dropped;
  std::copy_if(learnt_.blockages.begin(), learnt_.blockages.end(), std::back_inserter(dropped),
               inside);
  std::erase_if(learnt_.blockages, inside);
  for (const Blockage& b : dropped) {
    // The mission's copy of it (learnt ones are appended after the operator's).
    const auto same = std::find_if(
        mission_.blockages.rbegin(), mission_.blockages.rend(),
        [&](const Blockage& m) { return m.pipe == b.pipe && m.offset_m == b.offset_m; });
    if (same != mission_.blockages.rend()) mission_.blockages.erase(std::next(same).base());
    dropped_note_ += "; the blockage in " + map_.pipe(b.pipe).name + " at " + metres(b.offset_m) +
                     " is gone: the robot drove through it since";
  }
  return dropped;
}

bool Replanner::move_learnt(Failure::Kind kind, const Blockage& from, const Blockage& to,
                            const std::string& why) {
  if ((kind != Failure::Kind::kBlockage && kind != Failure::Kind::kDangerInPipe) ||
      to.pipe.index() >= map_.pipe_count() || !(to.offset_m >= 0) ||
      !(to.offset_m <= map_.pipe(to.pipe).length_m)) {
    return false;
  }
  const auto at_from = [&](const Blockage& b) {
    return b.pipe == from.pipe && b.offset_m == from.offset_m;
  };
  const bool danger = kind == Failure::Kind::kDangerInPipe;
  std::vector<Blockage>& list = danger ? learnt_.danger_spots : learnt_.blockages;
  const auto learnt = std::find_if(list.begin(), list.end(), at_from);
  if (learnt == list.end()) return false;
  *learnt = to;
  // The mission's copy of it (learnt ones are appended after the operator's).
  const auto copy = std::find_if(mission_.blockages.rbegin(), mission_.blockages.rend(), at_from);
  if (copy != mission_.blockages.rend()) *copy = to;
  dropped_note_ += std::string("; the ") + (danger ? "danger" : "blockage") + " in " +
                   map_.pipe(from.pipe).name + " at " + metres(from.offset_m) + " is in " +
                   map_.pipe(to.pipe).name + " at " + metres(to.offset_m) + ": " + why;
  return true;
}

Result<std::vector<HazardUpdate>> Replanner::observe_driven(PipeId pipe, double from_m, double to_m,
                                                            double margin_m) {
  if (Result<void> ok = check_driven(map_, pipe, from_m, to_m); !ok.has_value()) return ok.error();
  const double lo = std::min(from_m, to_m);
  const double hi = std::max(from_m, to_m);
  std::vector<std::size_t> passed;
  for (std::size_t h = 0; h < mission_.hazards.size(); ++h) {
    const Hazard& hazard = mission_.hazards[h];
    if (hazard.pipe == pipe && hazard.offset_m > lo && hazard.offset_m < hi &&
        !(std::abs(hazard.offset_m - to_m) <= margin_m)) {
      passed.push_back(h);
    }
  }
  // In the order of driving.
  std::stable_sort(passed.begin(), passed.end(), [&](std::size_t x, std::size_t y) {
    return from_m <= to_m ? mission_.hazards[x].offset_m < mission_.hazards[y].offset_m
                          : mission_.hazards[x].offset_m > mission_.hazards[y].offset_m;
  });
  std::vector<HazardUpdate> updates;
  for (std::size_t h : passed) {
    const auto belief =
        std::find_if(learnt_.hazards.begin(), learnt_.hazards.end(),
                     [&](const HazardBelief& b) { return same_hazard(b, mission_.hazards[h]); });
    // A blockage met there stays certain: the robot passed what a push cleared, or its report
    // was a place off.
    if (belief != learnt_.hazards.end() && belief->blocked) continue;
    updates.push_back(observe_hazard(h, false));
  }
  return updates;
}

HazardUpdate Replanner::observe_hazard(std::size_t h, bool blocked) {
  Hazard& hazard = mission_.hazards[h];
  auto belief = std::find_if(learnt_.hazards.begin(), learnt_.hazards.end(),
                             [&](const HazardBelief& b) { return same_hazard(b, hazard); });
  if (belief == learnt_.hazards.end()) {
    // The prior: the risk table's probability, with no pass observed yet.
    learnt_.hazards.push_back(
        {hazard.pipe, hazard.offset_m, hazard.reason, hazard.probability, 0, false});
    belief = std::prev(learnt_.hazards.end());
  }
  HazardUpdate update{.probability_before = belief->probability};
  if (blocked) {
    belief->blocked = true;
    belief->probability = 1;
  } else {
    belief->probability = hazard_probability_after_pass(belief->probability, belief->passes,
                                                        options_.hazard_learning.prior_strength);
    ++belief->passes;
  }
  hazard.probability = belief->probability;
  update.belief = *belief;
  return update;
}

Result<void> Replanner::update(const domain::MissionProgress& progress, std::uint8_t heading_end) {
  if (auto ok = check_progress(progress, heading_end, map_, mission_); !ok.has_value()) return ok;
  progress_ = progress;
  heading_end_ = heading_end;
  return {};
}

const Clock& Replanner::clock() const {
  return options_.clock != nullptr ? *options_.clock : steady_;
}

std::vector<ManholeId> Replanner::map_exits() const {
  std::vector<ManholeId> exits;
  for (ManholeId m : map_.manhole_ids()) {
    if (map_.manhole(m).exit) exits.push_back(m);
  }
  return exits;
}

search::PlannerOptions Replanner::bounded(double deadline_s) const {
  search::PlannerOptions options = options_.planner;
  options.clock = &clock();
  options.compile_cache = compile_cache_.get();
  if (background_cancel_ != nullptr) options.cancel = background_cancel_;
  if (std::isfinite(deadline_s)) {
    // At least a little: a limit of 0 means none to the planner.
    options.time_limit_s = std::max(deadline_s - clock().now_s(), 1e-12);
  }
  return options;
}

Result<search::PlanOutcome> Replanner::baseline_from_here(double deadline_s) {
  domain::MissionProgress start = progress_;
  for (const auto& d : dropped_) start.done[d.task.index()] = true;
  search::PlannerOptions same_goals = bounded(deadline_s);
  same_goals.select_goals = false;
  auto outcome = search::plan_mission(map_, mission_, start, same_goals);
  if (outcome.has_value() || outcome.error().code != ErrorCode::kNoPlan) return outcome;
  // The goal list cannot be done any more: straight to the nearest exit.
  const std::string why =
      "the baseline's goal list cannot be done: " + one_line(outcome.error().message);
  for (TaskId t : mission_.task_ids()) {
    if (start.done[t.index()]) continue;
    dropped_.push_back({t, why});
    start.done[t.index()] = true;
    mission_.tasks[t.index()].final = false;
  }
  mission_.exits = map_exits();
  return search::plan_mission(map_, mission_, start, bounded(deadline_s));
}

Result<search::PlanOutcome> Replanner::plan_from_here(double deadline_s) {
  const bool first = !planned_;
  planned_ = true;
  if (options_.goals == ReplannerOptions::Goals::kPaperBaseline && !first) {
    return baseline_from_here(deadline_s);
  }
  for (;;) {
    domain::MissionProgress start = progress_;
    for (const auto& d : dropped_) start.done[d.task.index()] = true;
    auto outcome = search::plan_mission(map_, mission_, start, bounded(deadline_s));
    if (outcome.has_value() || outcome.error().code != ErrorCode::kNoPlan) return outcome;
    // The end point cut off: end at the nearest reachable exit instead.
    if (auto final_task = mission_.final_task_id();
        final_task && !start.done[final_task->index()]) {
      dropped_.push_back({*final_task, "the mission's end point cannot be reached any more: " +
                                           one_line(outcome.error().message)});
      mission_.tasks[final_task->index()].final = false;
      if (mission_.exits.empty()) mission_.exits = map_exits();
      continue;
    }
    // The mission's exits cut off: any manhole the map marks as an exit will do.
    std::vector<ManholeId> all_exits = map_exits();
    if (all_exits.size() > mission_.exits.size()) {
      mission_.exits = std::move(all_exits);
      continue;
    }
    return outcome;
  }
}

Result<search::PlanOutcome> Replanner::exit_from_here(const std::string& why) {
  Mission to_exit = mission_;
  for (Task& t : to_exit.tasks) t.final = false;
  if (to_exit.exits.empty()) to_exit.exits = map_exits();
  domain::MissionProgress start = progress_;
  std::fill(start.done.begin(), start.done.end(), true);
  // No time limit and no cancel: this is the answer when the time ran out.
  const search::PlannerOptions options{.algorithm = search::Algorithm::kAstar,
                                       .clock = &clock(),
                                       .improvement_expansions = 0,
                                       .compile_cache = compile_cache_.get()};
  auto outcome = search::plan_mission(map_, to_exit, start, options);
  if (!outcome.has_value() && outcome.error().code == ErrorCode::kNoPlan) {
    std::vector<ManholeId> all_exits = map_exits();
    if (all_exits.size() > to_exit.exits.size()) {
      to_exit.exits = std::move(all_exits);
      outcome = search::plan_mission(map_, to_exit, start, options);
    }
  }
  if (!outcome.has_value()) return outcome;
  domain::MissionProgress now = progress_;
  for (const auto& d : dropped_) now.done[d.task.index()] = true;
  for (TaskId t : mission_.task_ids()) {
    if (!now.done[t.index()]) dropped_.push_back({t, why});
  }
  mission_ = std::move(to_exit);
  return outcome;
}

Result<search::PlanOutcome> Replanner::exit_on_reserve(const std::string& why) {
  const Error none{ErrorCode::kNoPlan, why};
  if (on_reserve_ || !(mission_.battery_reserve_fraction > 0) ||
      options_.goals == ReplannerOptions::Goals::kPaperBaseline) {
    return none;
  }
  const double fraction = mission_.battery_reserve_fraction;
  mission_.battery_reserve_fraction = 0;
  auto outcome = exit_from_here("no exit can be reached above the battery reserve: " + why);
  if (!outcome.has_value()) {
    mission_.battery_reserve_fraction = fraction;
    if (outcome.error().code != ErrorCode::kNoPlan) return outcome;
    return Error{ErrorCode::kNoPlan,
                 why + "; not even on the battery reserve: " + one_line(outcome.error().message)};
  }
  on_reserve_ = true;
  return outcome;
}

PlanResponse Replanner::plan(const std::string& reason_given) {
  const std::string reason = reason_given + dropped_note_;
  dropped_note_.clear();
  const double start_s = clock().now_s();
  const double deadline_s = options_.planner.time_limit_s > 0
                                ? start_s + options_.planner.time_limit_s
                                : std::numeric_limits<double>::infinity();
  const std::size_t dropped_before = dropped_.size();
  Result<search::PlanOutcome> outcome = plan_from_here(deadline_s);
  bool cut_short = false;
  if (!outcome.has_value() && background_cancel_ != nullptr && background_cancel_->load()) {
    cancelled_ = true;  // plan_cancellable answers kCancelled: no fallback
    return PlanResponse{.decision = PlanResponse::Decision::kDegraded, .reason = "cancelled"};
  }
  PlanResponse::Rung rung = PlanResponse::Rung::kSearch;
  if (outcome.has_value() && outcome->best_so_far) {
    // Stopped after a first plan: the best it had, if that is safe; else the rungs below.
    if (safe(*outcome)) {
      rung = PlanResponse::Rung::kBestSoFar;
    } else {
      outcome = Error{ErrorCode::kSearchLimit, "the best plan found in time is not safe"};
    }
  }
  std::string kept_because, ladder_note;
  if (!outcome.has_value() && outcome.error().code != ErrorCode::kNoPlan) {
    // A limit, a cancel or a planner error proves nothing: the first safe answer of the ladder
    // below the search (PlanResponse::Rung), the nearest exit when nothing else is.
    const ErrorCode code = outcome.error().code;
    const std::string why = code == ErrorCode::kSearchLimit ? "the planner's time ran out"
                            : code == ErrorCode::kCancelled
                                ? "the replan was cancelled"
                                : "the planner failed: " + one_line(outcome.error().message);
    if (auto rest = rest_of_current_plan()) {
      outcome = std::move(*rest);
      kept_because = why;
      rung = PlanResponse::Rung::kCurrentPlan;
    } else if (auto quick = quick_answer(why, rung)) {
      outcome = std::move(*quick);
      ladder_note = "; " + why + ": " +
                    (rung == PlanResponse::Rung::kRepairedPlan
                         ? "the current plan's tasks left, on routes around what was learnt"
                         : "the cheapest insertion of the tasks left");
    } else {
      outcome = exit_from_here(why);
      cut_short = true;
      rung = PlanResponse::Rung::kNearestExit;
    }
  }
  if (!outcome.has_value() && outcome.error().code == ErrorCode::kNoPlan) {
    // No exit above the reserve: the reserve is the last way out.
    outcome = exit_on_reserve(one_line(outcome.error().message));
  }
  const double seconds = clock().now_s() - start_s;
  if (!outcome.has_value()) {
    PlanResponse r;
    // kNoPlan: the search proved that no exit can be reached, not even on the reserve.
    r.decision = PlanResponse::Decision::kCallForRecovery;
    r.reason = reason + "; no way to end the mission: " + one_line(outcome.error().message);
    r.planning_time_s = seconds;
    r.newly_dropped.assign(dropped_.begin() + static_cast<std::ptrdiff_t>(dropped_before),
                           dropped_.end());
    last_start_.reset();
    return r;
  }
  PlanResponse r = respond(std::move(*outcome), reason, seconds);
  r.rung = rung;
  if (!kept_because.empty()) r.reason += "; " + kept_because + ": the current plan still holds";
  if (rung == PlanResponse::Rung::kBestSoFar) {
    r.reason += "; the planner's time ran out: the best plan it had found";
  }
  r.reason += ladder_note;
  r.newly_dropped.assign(dropped_.begin() + static_cast<std::ptrdiff_t>(dropped_before),
                         dropped_.end());
  if (r.decision == PlanResponse::Decision::kFollowPlan &&
      (cut_short || !r.newly_dropped.empty())) {
    r.decision = PlanResponse::Decision::kDegraded;
  }
  if (on_reserve_ && has_plan(r.decision)) {
    r.decision = PlanResponse::Decision::kExitOnReserve;
    const double left_wh = mission_.profile.battery_wh - progress_.energy_used_wh;
    const double reserve_wh = mission_.profile.battery_wh * reserve_fraction_;
    std::ostringstream out;
    out << std::fixed << std::setprecision(1)
        << "; no exit can be reached above the battery reserve: " << r.end << " on the reserve ("
        << r.energy_wh << " Wh of the " << left_wh << " Wh left; reserve " << reserve_wh << " Wh)";
    r.reason += out.str();
  }
  if (has_plan(r.decision)) {
    last_steps_ = r.plan.steps;
    last_start_ = progress_;
    for (const auto& d : dropped_) last_start_->done[d.task.index()] = true;
  } else {
    last_start_.reset();
  }
  return r;
}

std::optional<domain::ValidationReport> Replanner::safe(const search::PlanOutcome& outcome) const {
  domain::MissionProgress now = progress_;
  for (const auto& d : dropped_) now.done[d.task.index()] = true;
  for (const auto& d : outcome.dropped) now.done[d.task.index()] = true;
  domain::ValidationReport report = domain::validate_plan(outcome.plan, map_, mission_, now);
  const double budget_wh = mission_.profile.battery_wh * (1 - mission_.battery_reserve_fraction) -
                           progress_.energy_used_wh;
  if (!report.valid || report.energy_wh > budget_wh + 1e-9) return std::nullopt;
  return report;
}

std::vector<TaskId> Replanner::tasks_of_current_plan() const {
  std::vector<TaskId> order;
  if (!last_start_) return order;
  domain::MissionProgress now = progress_;
  for (const auto& d : dropped_) now.done[d.task.index()] = true;
  // Replayed as planned (what was learnt since may block the rest): only its order is wanted.
  Mission as_planned = mission_;
  as_planned.blockages.clear();
  as_planned.closed_passages.clear();
  for (Task& t : as_planned.tasks) t.final = false;
  if (domain::start_problem(map_, as_planned, *last_start_)) return order;
  domain::PlanReplay replay(map_, as_planned, *last_start_);
  std::vector<bool> done = last_start_->done;
  for (const auto& step : last_steps_) {
    if (!replay.apply(step).has_value()) break;
    for (TaskId t : mission_.task_ids()) {
      if (done[t.index()] || !replay.done()[t.index()]) continue;
      done[t.index()] = true;
      if (!now.done[t.index()]) order.push_back(t);
    }
  }
  return order;
}

std::optional<search::PlanOutcome> Replanner::quick_answer(const std::string& why,
                                                           PlanResponse::Rung& rung) {
  if (options_.goals == ReplannerOptions::Goals::kPaperBaseline) return std::nullopt;
  domain::MissionProgress start = progress_;
  for (const auto& d : dropped_) start.done[d.task.index()] = true;
  const search::PlannerOptions options = bounded(std::numeric_limits<double>::infinity());
  const auto accept = [&](Result<search::PlanOutcome> outcome,
                          PlanResponse::Rung answered) -> std::optional<search::PlanOutcome> {
    if (!outcome.has_value() || !safe(*outcome)) return std::nullopt;
    for (auto& d : outcome->dropped) {
      d.reason = why + "; the " + outcome->algorithm + " leaves it out: " + d.reason;
    }
    rung = answered;
    return std::move(*outcome);
  };
  if (const std::vector<TaskId> order = tasks_of_current_plan(); !order.empty()) {
    auto repaired = search::plan_in_order(map_, mission_, start, order, options);
    if (repaired.has_value()) repaired->algorithm = "current plan's order";
    if (auto ok = accept(std::move(repaired), PlanResponse::Rung::kRepairedPlan)) return ok;
  }
  return accept(search::plan_greedily(map_, mission_, start, options), PlanResponse::Rung::kGreedy);
}

std::optional<search::PlanOutcome> Replanner::rest_of_current_plan() const {
  if (!last_start_) return std::nullopt;
  domain::MissionProgress now = progress_;
  for (const auto& d : dropped_) now.done[d.task.index()] = true;
  // Where the robot is in the plan: the last state of its replay that is the robot's place and
  // tasks done. The part already driven is replayed without what was learnt since (the robot
  // drove it before).
  Mission as_planned = mission_;
  as_planned.blockages.clear();
  as_planned.closed_passages.clear();
  for (Task& t : as_planned.tasks) t.final = false;
  if (domain::start_problem(map_, as_planned, *last_start_)) return std::nullopt;
  domain::PlanReplay replay(map_, as_planned, *last_start_);
  std::optional<std::size_t> here;
  const auto at_now = [&] {
    if (!same_place(replay.position(), now.position)) return false;
    for (TaskId t : mission_.task_ids()) {
      if (replay.done()[t.index()] != now.done[t.index()] && !now.done[t.index()]) return false;
    }
    return true;
  };
  for (std::size_t k = 0;; ++k) {
    if (at_now()) here = k;
    if (k == last_steps_.size() || !replay.apply(last_steps_[k]).has_value()) break;
  }
  if (!here) return std::nullopt;
  domain::Plan rest;
  rest.steps.assign(last_steps_.begin() + static_cast<std::ptrdiff_t>(*here), last_steps_.end());
  // The rest on the world model as it is now, to the mission's end, within the battery left.
  search::PlanOutcome outcome;
  outcome.plan = std::move(rest);
  const std::optional<domain::ValidationReport> report = safe(outcome);
  if (!report) return std::nullopt;
  outcome.cost_s = report->total_cost_s;
  outcome.energy_wh = report->energy_wh;
  outcome.algorithm = "the current plan";
  return outcome;
}

PlanResponse Replanner::respond(search::PlanOutcome outcome, const std::string& reason,
                                double seconds) {
  PlanResponse r;
  r.reason = reason;
  r.planning_time_s = seconds;
  r.cost_s = outcome.cost_s;
  r.energy_wh = outcome.energy_wh;
  r.strand_probability = outcome.strand_probability;
  for (auto& d : outcome.dropped) {
    if (!has_task(dropped_, d.task)) dropped_.push_back(d);
  }
  domain::MissionProgress start = progress_;
  for (const auto& d : dropped_) start.done[d.task.index()] = true;
  for (TaskId t : mission_.task_ids()) {
    if (!start.done[t.index()]) r.goals.push_back(t);
  }
  Result<fusion::FusedPlan> fused =
      fusion::fuse(outcome.plan, map_, mission_, start, {.start_heading_end = heading_end_});
  if (!fused.has_value()) {
    r.decision = PlanResponse::Decision::kCallForRecovery;
    r.reason = reason + "; the plan cannot be carried out: " + fused.error().message;
    return r;
  }
  r.fused = std::move(*fused);
  r.plan = std::move(outcome.plan);

  if (const Task* final_task = mission_.final_task()) {
    r.end = describe(final_task->place, map_) + " (final task '" + final_task->name + "')";
  } else {
    domain::PlanReplay replay(map_, mission_, start);
    for (const auto& step : r.plan.steps) (void)replay.apply(step);
    const auto m = domain::manhole_of(replay.position());
    r.end = m ? "exit " + map_.manhole(*m).name : "exit";
  }
  return r;
}

PlanResponse Replanner::report_failure(const Failure& failure) {
  if (auto ok = check_failure(failure, map_); !ok.has_value()) {
    PlanResponse r;
    r.decision = PlanResponse::Decision::kInvalidReport;
    r.reason = ok.error().message;
    return r;
  }
  // Kept as the current plan: the safe answer if the replan runs out of time and it still holds.
  const std::vector<domain::PlanStep> failed_steps = last_steps_;
  std::string reason(to_string(failure.kind));
  std::vector<HazardUpdate> hazard_updates;
  if (failure.kind == Failure::Kind::kBlockage) {
    // The hazard met: the nearest of the pipe's within the match distance, if any.
    std::optional<std::size_t> met;
    for (std::size_t h = 0; h < mission_.hazards.size(); ++h) {
      const Hazard& hazard = mission_.hazards[h];
      const double distance = std::abs(hazard.offset_m - failure.offset_m);
      if (hazard.pipe != failure.pipe || !(distance <= options_.hazard_learning.blockage_match_m)) {
        continue;
      }
      if (!met || distance < std::abs(mission_.hazards[*met].offset_m - failure.offset_m)) met = h;
    }
    if (met) hazard_updates.push_back(observe_hazard(*met, true));
  }
  switch (failure.kind) {
    case Failure::Kind::kBlockage:
    case Failure::Kind::kDangerInPipe:
      (failure.kind == Failure::Kind::kBlockage ? learnt_.blockages : learnt_.danger_spots)
          .push_back({failure.pipe, failure.offset_m});
      mission_.blockages.push_back({failure.pipe, failure.offset_m});
      reason += " in " + map_.pipe(failure.pipe).name + " at " + metres(failure.offset_m);
      break;
    case Failure::Kind::kDangerousPassage:
      learnt_.closed_passages.push_back({failure.manhole, failure.from, failure.to});
      mission_.closed_passages.push_back({failure.manhole, failure.from, failure.to});
      reason += " at " + map_.manhole(failure.manhole).name + " from slot " +
                std::to_string(to_paper_number(failure.from)) + " to " +
                std::to_string(to_paper_number(failure.to));
      break;
    case Failure::Kind::kStuck: {
      PlanResponse r;
      r.decision = PlanResponse::Decision::kStuck;
      r.reason = "the robot cannot move: " + failure.detail;
      return r;
    }
  }
  PlanResponse r = plan(reason);
  r.hazard_updates = hazard_updates;
  // The plan that just failed, again: the robot would meet the same trouble at the same place
  // (a task a hair beyond where it stops for a danger). Drop the task it was heading for.
  while (!cancelled_ && has_plan(r.decision) && !failed_steps.empty() &&
         r.plan.steps == failed_steps) {
    const std::optional<TaskId> target = first_task_of(r.plan);
    if (!target) break;
    const std::size_t dropped_before = dropped_.size();
    dropped_.push_back({*target, "the robot cannot get there: the plan after " + reason +
                                     " was the plan that had just failed"});
    if (mission_.tasks[target->index()].final) {
      mission_.tasks[target->index()].final = false;
      if (mission_.exits.empty()) mission_.exits = map_exits();
    }
    std::vector<domain::DroppedTask> dropped_so_far = std::move(r.newly_dropped);
    dropped_so_far.push_back(dropped_[dropped_before]);
    r = plan(reason);
    r.hazard_updates = hazard_updates;
    dropped_so_far.insert(dropped_so_far.end(), r.newly_dropped.begin(), r.newly_dropped.end());
    r.newly_dropped = std::move(dropped_so_far);
    if (r.decision == PlanResponse::Decision::kFollowPlan) {
      r.decision = PlanResponse::Decision::kDegraded;
    }
  }
  return r;
}

std::optional<TaskId> Replanner::first_task_of(const domain::Plan& plan) const {
  domain::MissionProgress start = progress_;
  for (const auto& d : dropped_) start.done[d.task.index()] = true;
  domain::PlanReplay replay(map_, mission_, start);
  for (const auto& step : plan.steps) {
    if (!replay.apply(step).has_value()) return std::nullopt;
    for (TaskId t : mission_.task_ids()) {
      if (!start.done[t.index()] && replay.done()[t.index()]) return t;
    }
  }
  return std::nullopt;
}

}  // namespace sewerplan::executor
