// SPDX-License-Identifier: MIT
// The sewer compiler: keys, routes between them, and the compiled task (compile.h).
#include "sewerplan/domain/compile.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <iomanip>
#include <map>
#include <mutex>
#include <span>
#include <sstream>
#include <string_view>
#include <tuple>
#include <unordered_map>

#include "sewerplan/core/clock.h"

#include "compile_reasons.h"
#include "graph_search.h"
#include "position_graph.h"
#include "route_index_internal.h"
#include "route_memo.h"
#include "route_store.h"
#include "sewer_task_compiler.h"

namespace sewerplan::domain {

struct CompileCache::State {
  std::mutex mutex;
  std::shared_ptr<detail::GraphCore> core;
  RoutingIndex index = RoutingIndex::kAuto;
};

CompileCache::CompileCache(RoutingIndex index) : state_(std::make_unique<State>()) {
  state_->index = index;
}
CompileCache::~CompileCache() = default;
CompileCache::RoutingIndex CompileCache::routing_index() const { return state_->index; }
Result<void> CompileCache::use_route_index(RouteIndex index, const SewerMap& map,
                                           const RobotProfile& profile,
                                           std::shared_ptr<const PassageMotionTable> motion,
                                           const StopCondition& stop) {
  const auto stopped = [&] {
    return stopped_error(stop.interrupted().value_or(SearchStatus::kCancelled),
                         "loading the routing index");
  };
  const std::lock_guard lock(state_->mutex);
  std::shared_ptr<detail::GraphCore> core = state_->core;
  // The cache's core if it serves this map and robot and no compile holds it; else a new one, as
  // the next compile would build.
  if (core != nullptr && core.use_count() > 2) core = nullptr;
  core = detail::core_with_adjacency(std::move(core), map, profile, std::move(motion), stop);
  if (core == nullptr) return stopped();
  const std::uint64_t fingerprint = detail::adjacency_fingerprint(*core);
  if (fingerprint != index.fingerprint() ||
      index.statistics().nodes + 1 != core->adjacency_begin.size()) {
    return Error{
        ErrorCode::kInvalidArgument,
        "the routing index " + (index.source().empty() ? std::string("given") : index.source()) +
            " is stale: it was built for another map, robot profile or motion table "
            "(its fingerprint " +
            fingerprint_hex(index.fingerprint()) + ", this one's " + fingerprint_hex(fingerprint) +
            "); remake it with 'sewerplan index build' for this map and profile"};
  }
  core->hierarchy = index.impl().hierarchy;
  core->hierarchy_query = std::make_shared<detail::ChQuery>(*core->hierarchy);
  core->hierarchy_failed = false;
  state_->core = std::move(core);
  return Result<void>{};
}

SewerTask::SewerTask() = default;
SewerTask::SewerTask(SewerTask&&) noexcept = default;
SewerTask& SewerTask::operator=(SewerTask&&) noexcept = default;
SewerTask::~SewerTask() = default;

Plan SewerTask::expand(std::span<const ActionId> plan) const {
  Plan out;
  for (ActionId a : plan) {
    for (std::uint32_t i = route_begin_[a.index()]; i + 1 < route_begin_[a.index() + 1]; ++i) {
      out.steps.push_back(graph_->step(route_nodes_[i], route_nodes_[i + 1]));
    }
    if (task_step_[a.index()]) out.steps.push_back(*task_step_[a.index()]);
  }
  return out;
}

Result<SewerTask> SewerTaskCompiler::run() {
  SteadyClock clock;
  const double start_s = clock.now_s();
  PositionGraph& graph = *result_.graph_;
  if (!graph.core().complete) return stop_error();
  select_tasks();
  collect_keys(graph);
  if (auto stopped = options_.stop.interrupted()) return stopped_error(*stopped, "the compile");
  // The arrays over every node, grown before the searches with checks between slices (on a
  // large map, one fill was the longest stretch without a check: issue 14).
  if (!GraphSearch::grow(graph.core().scratch, graph.size(), &options_.stop) ||
      !detail::grow_in_slices(graph.core().exit_marks, graph.size(), &options_.stop)) {
    return stop_error();
  }
  GraphSearch search(graph, &graph.core().scratch);
  if (options_.stop.can_interrupt()) {
    search.set_interrupt([this] { return options_.stop.interrupted().has_value(); });
  }
  route(search);
  if (search.interrupted()) return stop_error();
  detail::CompileReasons reasons(graph, mission_, progress_, bound_, keys_[0]);
  if (options_.select_goals) {
    if (auto why = select_goals(reasons); !why.empty()) {
      return Error{ErrorCode::kNoPlan, "the mission cannot be ended:" + why};
    }
  } else if (auto why = reasons.explain(keys_, pending_, dist_, exit_dist_, ends_at_exit_);
             !why.empty()) {
    return Error{ErrorCode::kNoPlan, "the mission cannot be completed:" + why};
  }
  for (const Hazard& h : mission_.hazards) {
    result_.hazard_probability_.push_back(std::clamp(h.probability, 0.0, 1.0));
  }
  contingency_ = options_.contingency && ends_at_exit_ && graph.has_hazards();
  if (contingency_) {
    if (!GraphSearch::grow(contingency_scratch_, graph.size(), &options_.stop)) return stop_error();
    contingency_search_ = std::make_unique<GraphSearch>(graph, &contingency_scratch_);
    if (options_.stop.can_interrupt()) {
      contingency_search_->set_interrupt(
          [this] { return options_.stop.interrupted().has_value(); });
    }
  }
  build_task();
  if (build_stopped_) return stopped_error(*build_stopped_, "the compile");
  // Issue 30: a task cut off by a blockage or a closure is named with its cause before any
  // search, rather than the search's "no plan within the battery" blaming the battery.
  if (auto why = undoable_reasons(); !why.empty()) {
    return Error{ErrorCode::kNoPlan, (options_.select_goals ? "the mission cannot be ended:"
                                                            : "the mission cannot be completed:") +
                                         why};
  }
  if (contingency_search_ && contingency_search_->interrupted()) return stop_error();
  result_.statistics_.keys = keys_.size();
  result_.statistics_.graph_nodes = graph.size();
  result_.statistics_.settled_nodes =
      search.settled_total() + (contingency_search_ ? contingency_search_->settled_total() : 0);
  result_.statistics_.actions = result_.task_.action_count();
  result_.statistics_.adjacency = graph.has_adjacency();
  result_.statistics_.time_s = clock.now_s() - start_s;
  return std::move(result_);
}

std::shared_ptr<detail::GraphCore> SewerTaskCompiler::cached_core() const {
  if (options_.cache == nullptr) return nullptr;
  CompileCache::State& state = *options_.cache->state_;
  const std::lock_guard lock(state.mutex);
  const auto& core = state.core;
  const PassageMotionTable* motion = mission_.passage_motion.get();
  if (core != nullptr && core->serves(map_, mission_.profile, motion)) {
    if (core.use_count() == 1) return core;
    return nullptr;
  }
  state.core = std::make_shared<detail::GraphCore>(map_, mission_.profile, mission_.passage_motion,
                                                   &options_.stop);
  return state.core;
}

std::string SewerTaskCompiler::select_goals(const detail::CompileReasons& reasons) {
  std::string why = reasons.fatal(exit_dist_, ends_at_exit_);
  if (!why.empty()) return why;
  std::vector<TaskId> kept;
  for (TaskId t : pending_) {
    const Task& task = mission_.task(t);
    std::string reason = reasons.task_reason(task, keys_, dist_, exit_dist_, ends_at_exit_);
    if (reason.empty()) {
      kept.push_back(t);
    } else if (task.final) {
      why += "\n  - the final task '" + task.name + "': " + reason;
    } else {
      result_.dropped_.push_back({t, std::move(reason)});
    }
  }
  pending_ = std::move(kept);
  return why;
}

void SewerTaskCompiler::select_tasks() {
  for (TaskId t : mission_.task_ids()) {
    if (!progress_.done[t.index()]) pending_.push_back(t);
  }
  const auto final_task = mission_.final_task_id();
  ends_at_exit_ = !final_task.has_value();
  const double budget_wh = mission_.profile.battery_wh * (1 - mission_.battery_reserve_fraction) -
                           progress_.energy_used_wh;
  bound_ = budget_wh < 0 ? -1 : to_cost(mission_.profile.seconds_for(budget_wh));
}

std::string SewerTaskCompiler::blocked_reason(const Task& task) const {
  if (const auto* spot = std::get_if<PipeSpot>(&task.place)) {
    for (const Blockage& b : mission_.blockages) {
      if (b.pipe == spot->pipe) {
        std::ostringstream out;
        out << "pipe " << map_.pipe(b.pipe).name << " is blocked at " << std::fixed
            << std::setprecision(2) << b.offset_m << " m";
        return out.str();
      }
    }
  }
  return "no way there within the robot's limits, the mission's closures and the battery left";
}

}  // namespace sewerplan::domain

namespace sewerplan::domain {
namespace {

// The name of a move between keys ("go key 3 -> 7", "exit from key 3"), written into one buffer
// (issue 16: k^2 such names, each joined by operator+ from std::to_string's, were a sixth of
// building a 10-manhole task).
std::string key_name(std::string_view head, std::uint32_t a, std::string_view middle = {},
                     std::optional<std::uint32_t> b = std::nullopt) {
  std::array<char, 64> text;  // the heads are short words, the numbers 10 digits at most
  SEWER_CHECK(head.size() + middle.size() + 20 <= text.size(), "key_name: a head too long");
  char* end = std::copy(head.begin(), head.end(), text.data());
  end = std::to_chars(end, text.data() + text.size(), a).ptr;
  end = std::copy(middle.begin(), middle.end(), end);
  if (b) end = std::to_chars(end, text.data() + text.size(), *b).ptr;
  return std::string(text.data(), end);
}

}  // namespace

ActionId SewerTaskCompiler::add_action(std::span<const Fact> pre, std::span<const Fact> eff,
                                       Cost cost, std::string name, std::span<const Node> route,
                                       std::optional<PlanStep> step, Cost risk, Cost need) {
  const ActionId id = builder_.add_action(pre, eff, cost, std::move(name));
  need = std::max(need, route_need(route));
  if (need > cost) builder_.set_reserve(id, need - cost);
  result_.risk_.push_back(risk);
  if (result_.pass_begin_.empty()) result_.pass_begin_.push_back(0);
  for (std::size_t i = 0; i < noted_.size(); ++i) {
    // A route's own drives were noted from its start; a task action's drive from where the
    // action starts it too (in_pipe_need's prefix).
    result_.passes_.push_back({noted_[i].first, covered_[i], noted_need_[i]});
  }
  result_.pass_begin_.push_back(static_cast<std::uint32_t>(result_.passes_.size()));
  noted_.clear();
  covered_.clear();
  noted_need_.clear();
  if (result_.route_begin_.empty()) result_.route_begin_.push_back(0);
  result_.route_nodes_.insert(result_.route_nodes_.end(), route.begin(), route.end());
  result_.route_begin_.push_back(static_cast<std::uint32_t>(result_.route_nodes_.size()));
  result_.task_step_.push_back(std::move(step));
  return id;
}

std::vector<Fact> SewerTaskCompiler::task_preconditions(std::size_t index, VarId pos,
                                                        std::uint32_t key) const {
  std::vector<Fact> pre{{pos, static_cast<std::int32_t>(key)}, {task_vars_[index], 0}};
  if (mission_.task(pending_[index]).final) {
    for (std::size_t j = 0; j < pending_.size(); ++j) {
      if (j != index) pre.push_back({task_vars_[j], 1});
    }
  }
  return pre;
}

void SewerTaskCompiler::add_task_actions(std::size_t index, VarId pos) {
  if (task_moves_.size() <= index) task_moves_.resize(index + 1);
  for (std::uint32_t y = 0; y < k(); ++y) add_task_actions_from(index, pos, y);
}

std::vector<std::size_t> SewerTaskCompiler::cut_off_tasks() const {
  std::vector<bool> reached(k(), false);
  const auto reach_from = [&](std::uint32_t from) {
    for (std::uint32_t b = 0; b < k(); ++b) {
      if (dist_[from * k() + b] <= bound_) reached[b] = true;
    }
  };
  reached[0] = true;
  reach_from(0);
  for (bool grew = true; grew;) {
    grew = false;
    for (const auto& moves : task_moves_) {
      for (const auto& [from, to] : moves) {
        if (!reached[from] || reached[to]) continue;
        reached[to] = true;
        reach_from(to);
        grew = true;
      }
    }
  }
  std::vector<std::size_t> cut_off;
  for (std::size_t i = 0; i < task_moves_.size(); ++i) {
    const auto& moves = task_moves_[i];
    if (std::none_of(moves.begin(), moves.end(), [&](const auto& m) { return reached[m.first]; })) {
      cut_off.push_back(i);
    }
  }
  return cut_off;
}

std::string SewerTaskCompiler::undoable_reasons() const {
  std::string out;
  for (std::size_t i : undoable_) {
    const Task& task = mission_.task(pending_[i]);
    if (options_.select_goals && !task.final) continue;
    out += "\n  - " + std::string(task.final ? "the final task '" : "task '") + task.name + "' (" +
           std::string(to_string(task.kind)) +
           "): no position the robot can reach lets it do the task: " + blocked_reason(task);
  }
  return out;
}

void SewerTaskCompiler::add_task_actions_from(std::size_t index, VarId pos, std::uint32_t y) {
  PositionGraph& graph = *result_.graph_;
  const TaskId t = pending_[index];
  const Task& task = mission_.task(t);
  const VarId var = task_vars_[index];
  const RobotProfile& profile = mission_.profile;
  const std::string label = "'" + task.name + "' from key ";
  const Fact done[] = {{var, 1}};
  auto& moves = task_moves_[index];
  if (const auto* m = std::get_if<ManholeId>(&task.place)) {
    if (manhole_of(graph.position(keys_[y])) != *m) return;
    std::optional<PlanStep> step;
    if (!task.final) step = GoToManhole{*m, t};
    add_action(task_preconditions(index, pos, y), done, 0,
               (task.final ? "finish " : "go-to ") + label + std::to_string(y), {}, step);
    moves.emplace_back(y, y);
    return;
  }
  const auto& spot = std::get<PipeSpot>(task.place);
  if (graph.pipe_of(keys_[y]) != spot.pipe) return;
  const double at = graph.offset_of(keys_[y]);
  const auto pre = task_preconditions(index, pos, y);
  auto blocked = [&](double x) { return graph.blocked_between(spot.pipe, at, x); };
  auto move_to = [&](double x, std::vector<Fact> eff) {
    const std::uint32_t to = x != at ? key_of_.at(graph.spot(spot.pipe, x)) : y;
    if (x != at) eff.push_back({pos, static_cast<std::int32_t>(to)});
    moves.emplace_back(y, to);
    return eff;
  };
  switch (task.kind) {
    case TaskKind::kTakeWaterSample: {
      const double x = spot.offset_m.value_or(at);
      if (blocked(x)) break;
      add_action(pre, move_to(x, {{var, 1}}),
                 to_cost(std::abs(x - at) / profile.speed_mps + profile.sample_s),
                 "sample " + label + std::to_string(y), {}, TakeWaterSample{spot.pipe, t}, 0,
                 in_pipe_need(spot.pipe, keys_[y], at, x, 0, profile.speed_mps));
      break;
    }
    case TaskKind::kGoTo: {
      if (task.final && !spot.offset_m) {
        add_action(pre, done, 0, "finish " + label + std::to_string(y), {}, std::nullopt);
        moves.emplace_back(y, y);
        break;
      }
      const double x = spot.offset_m.value_or(at);
      if (blocked(x)) break;
      add_action(pre, move_to(x, {{var, 1}}), to_cost(std::abs(x - at) / profile.speed_mps),
                 "go-to " + label + std::to_string(y), {}, GoToPoint{spot.pipe, t}, 0,
                 in_pipe_need(spot.pipe, keys_[y], at, x, 0, profile.speed_mps));
      break;
    }
    case TaskKind::kInspectPipe: {
      const Pipe& pipe = map_.pipe(spot.pipe);
      if (!graph.fully_open(spot.pipe)) break;
      for (std::uint8_t e = 0; e < 2; ++e) {
        const double start_end = end_offset_m(pipe, 1U - e);
        const Node finish = graph.pipe_end(spot.pipe, e);
        std::optional<std::uint8_t> finish_end;
        if (keys_[y] != graph.pipe_end(spot.pipe, 1U - e)) finish_end = e;
        // The inspection drives the whole pipe, past every hazard in it.
        const Cost risk =
            graph.risk_cost(spot.pipe, -1.0, pipe.length_m + 1.0, options_.risk.blockage_s);
        const Fact eff[] = {{var, 1}, {pos, static_cast<std::int32_t>(key_of_.at(finish))}};
        moves.emplace_back(y, key_of_.at(finish));
        add_action(pre, eff,
                   to_cost(std::abs(at - start_end) / profile.speed_mps +
                           pipe.length_m / profile.inspection_speed_mps) +
                       risk,
                   "inspect " + label + std::to_string(y) + " to end " + std::to_string(e), {},
                   InspectPipe{spot.pipe, t, finish_end}, risk,
                   in_pipe_need(spot.pipe, graph.pipe_end(spot.pipe, 1U - e), start_end,
                                end_offset_m(pipe, e),
                                to_cost(std::abs(at - start_end) / profile.speed_mps),
                                profile.inspection_speed_mps));
      }
      break;
    }
  }
}

void SewerTaskCompiler::build_task() {
  const auto exit_value = static_cast<std::int32_t>(k());
  const VarId pos =
      builder_.add_variable(static_cast<std::int32_t>(k()) + (ends_at_exit_ ? 1 : 0), "position");
  for (TaskId t : pending_) {
    task_vars_.push_back(builder_.add_variable(2, "task '" + mission_.task(t).name + "'"));
  }
  result_.goal_tasks_ = pending_;
  builder_.set_initial(std::vector<std::int32_t>(1 + pending_.size(), 0));
  for (VarId v : task_vars_) builder_.add_goal({v, 1});
  if (ends_at_exit_) builder_.add_goal({pos, exit_value});
  builder_.set_cost_bound(bound_);
  // Issue 14: growing the route table by doubling copied it whole (millions of nodes on 10,000
  // manholes), a stretch of several milliseconds between two stop checks; sized once instead.
  std::size_t nodes = 0;
  for (const RouteRef& r : routes_) nodes += r.size;
  for (const RouteRef& r : exit_routes_) nodes += r.size;
  result_.route_nodes_.reserve(nodes + nodes / 8 + 4096);  // and the tasks' own
  result_.route_begin_.reserve(routes_.size() + exit_routes_.size() + 1);
  // The actions' arrays sized once too: the moves and exits within the bound, the forgo actions
  // and (a guess, they may grow) two actions per task, two facts each.
  std::size_t actions = 2 * pending_.size() + (options_.select_goals ? pending_.size() : 0);
  for (std::uint32_t a = 0; a < k(); ++a) {
    for (std::uint32_t b = 0; b < k(); ++b) actions += a != b && dist_[a * k() + b] <= bound_;
    actions += ends_at_exit_ && exit_dist_[a] <= bound_;
  }
  builder_.reserve(actions, 2 * actions);
  result_.risk_.reserve(actions);
  result_.pass_begin_.reserve(actions + 1);
  result_.task_step_.reserve(actions);
  for (std::uint32_t a = 0; a < k(); ++a) {
    for (std::uint32_t b = 0; b < k(); ++b) {
      const Cost d = dist_[a * k() + b];
      if (a == b || d > bound_) continue;
      if (build_interrupted()) return;
      const std::span<const Node> route = this->route(routes_[a * k() + b]);
      const Fact pre[] = {{pos, static_cast<std::int32_t>(a)}};
      const Fact eff[] = {{pos, static_cast<std::int32_t>(b)}};
      add_action(pre, eff, d, key_name("go key ", a, " -> ", b), route, std::nullopt,
                 result_.graph_->route_risk(route, options_.risk.blockage_s));
    }
  }
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    if (build_interrupted()) return;
    // A task that no action can do from where the robot can get (a blockage in the way) is
    // dropped with that reason (goal selection) or named as the cause (issue 30), rather than
    // forgone or failed as if for the battery.
    add_task_actions(i, pos);
  }
  undoable_ = cut_off_tasks();
  if (options_.select_goals) {
    // Forgoing a task costs more than any plan within the bound (CompiledTask::penalty_unit()).
    const Cost penalty = 2 * (bound_ + 1);
    builder_.set_penalty_unit(penalty);
    for (std::size_t i = 0; i < pending_.size(); ++i) {
      const Task& task = mission_.task(pending_[i]);
      if (task.final) continue;
      if (std::find(undoable_.begin(), undoable_.end(), i) != undoable_.end()) {
        result_.dropped_.push_back(
            {pending_[i],
             "no position the robot can reach lets it do the task: " + blocked_reason(task)});
      }
      result_.forgo_actions_.emplace_back(
          ActionId{static_cast<std::uint32_t>(result_.task_step_.size())}, pending_[i]);
      const Fact pre[] = {{task_vars_[i], 0}};
      const Fact eff[] = {{task_vars_[i], 1}};
      add_action(pre, eff, penalty, "forgo '" + task.name + "'", {}, std::nullopt);
    }
  }
  for (std::uint32_t a = 0; ends_at_exit_ && a < k(); ++a) {
    if (exit_dist_[a] > bound_) continue;
    if (build_interrupted()) return;
    const Fact pre[] = {{pos, static_cast<std::int32_t>(a)}};
    const Fact eff[] = {{pos, exit_value}};
    add_action(pre, eff, exit_dist_[a], key_name("exit from key ", a), route(exit_routes_[a]),
               std::nullopt,
               result_.graph_->route_risk(route(exit_routes_[a]), options_.risk.return_s));
  }
  result_.task_ = std::move(builder_).build();
}

Result<SewerTask> compile_sewer_task(const SewerMap& map, const Mission& mission,
                                     const MissionProgress& progress,
                                     const CompileOptions& options) {
  SEWER_CHECK(progress.done.size() == mission.tasks.size(), "progress does not fit the mission");
  return SewerTaskCompiler(map, mission, progress, options).run();
}

Cost SewerTask::risk_cost(std::span<const ActionId> plan) const {
  Cost total = 0;
  for (ActionId a : plan) total += risk_[a.index()];
  return total;
}

StrandRisk SewerTask::strand_risk(std::span<const ActionId> plan,
                                  std::optional<Cost> budget) const {
  const Cost bound = budget.value_or(task_.cost_bound());
  struct Seen {
    std::uint32_t hazard = 0;
    double risk = 0;  // of being stranded by it
  };
  std::vector<Seen> seen;  // each hazard once, as its first drive past it leaves it
  Cost spent = 0;          // the plan's true cost before the action
  for (ActionId a : plan) {
    if (pass_begin_.empty()) break;
    for (std::uint32_t i = pass_begin_[a.index()]; i < pass_begin_[a.index() + 1]; ++i) {
      const HazardPass& pass = passes_[i];
      auto it = std::find_if(seen.begin(), seen.end(),
                             [&](const Seen& s) { return s.hazard == pass.hazard; });
      if (it != seen.end()) continue;
      const double p = hazard_probability_[pass.hazard];
      const WayBack& way = pass.way_back;
      // Insured, or the battery left backs out from it and on along a way out whose own hazards
      // it could back out of too: none; the battery for the way out but not for its hazards:
      // the chance that one of them blocks it as well; no battery for the way out: p.
      double risk = p;
      if (pass.covered || (way.full < kInfiniteCost && spent + way.full <= bound)) {
        risk = 0;
      } else if (way.plain < kInfiniteCost && spent + way.plain <= bound) {
        risk = p * way.risk;
      }
      seen.push_back({pass.hazard, risk});
    }
    const Cost cost = task_.real_cost(task_.cost(a));
    // A forgo action's cost is its penalty only (real cost 0); the expected cost of stops is
    // not battery.
    spent += cost - std::min(cost, risk_[a.index()]);
  }
  StrandRisk risk;
  double none = 1;
  for (const Seen& s : seen) {
    if (!(s.risk > 0)) continue;
    risk.uninsured.push_back(s.hazard);
    none *= 1 - s.risk;
  }
  std::sort(risk.uninsured.begin(), risk.uninsured.end());
  risk.probability = 1 - none;
  return risk;
}

std::vector<TaskId> SewerTask::forgone(std::span<const ActionId> plan) const {
  std::vector<TaskId> tasks;
  for (ActionId a : plan) {
    auto it = std::lower_bound(forgo_actions_.begin(), forgo_actions_.end(), a,
                               [](const auto& entry, ActionId id) { return entry.first < id; });
    if (it == forgo_actions_.end() || it->first != a) continue;
    // Tasks dropped already (no action does them) are forgone with the reason given then.
    const bool dropped = std::any_of(dropped_.begin(), dropped_.end(),
                                     [&](const DroppedTask& d) { return d.task == it->second; });
    if (!dropped) tasks.push_back(it->second);
  }
  std::sort(tasks.begin(), tasks.end());
  return tasks;
}

}  // namespace sewerplan::domain
