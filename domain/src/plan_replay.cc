// SPDX-License-Identifier: MIT
// PlanReplay: the preconditions, effects and costs of docs/domain.md, one action at a time.
#include <algorithm>
#include <cmath>
#include <type_traits>

#include "sewerplan/core/check.h"
#include "sewerplan/core/map_queries.h"
#include "sewerplan/domain/validator.h"

#include "object_names.h"

namespace sewerplan::domain {
namespace {

using detail::fixed;
using detail::name_of;
using detail::shortest;

constexpr double kLimitTolerance = 1e-9;   // turns (deg) and steps (m), as docs/domain.md says
constexpr double kEnergyTolerance = 1e-9;  // Wh
constexpr double kEndTolerance = 1e-9;     // m: how close to an end "at the end" is

std::string robot_name(const Mission& mission) {
  return mission.profile.name.empty() ? std::string("the robot") : mission.profile.name;
}

// "passage M3 slot 1 -> 2 (P5 -> P2)"
std::string passage_text(const SewerMap& map, ManholeId m, SlotIndex from, SlotIndex to) {
  return "passage " + map.manhole(m).name + " slot " + std::to_string(to_paper_number(from)) +
         " -> " + std::to_string(to_paper_number(to)) + " (" +
         map.pipe(map.slot(m, from).pipe).name + " -> " + map.pipe(map.slot(m, to).pipe).name + ")";
}

}  // namespace

PlanReplay::PlanReplay(const SewerMap& map, const Mission& mission, MissionProgress start)
    : map_(&map), mission_(&mission), progress_(std::move(start)) {
  SEWER_CHECK(!start_problem(map, mission, progress_), "PlanReplay: invalid start");
  if (auto final = mission.final_task_id()) finished_ = progress_.done[final->index()];
}

bool PlanReplay::done(TaskId task) const {
  SEWER_CHECK(task.index() < progress_.done.size(), "PlanReplay::done: task out of range");
  return progress_.done[task.index()];
}

double PlanReplay::energy_wh() const { return mission_->profile.energy_wh(elapsed_s_); }

MissionProgress PlanReplay::progress() const {
  MissionProgress p = progress_;
  p.energy_used_wh += energy_wh();
  return p;
}

Result<double> PlanReplay::apply(const PlanStep& step) {
  if (finished_) {
    return invalid("step after the final task '" + mission_->final_task()->name + "'");
  }
  Result<Transition> t = transition(step);
  if (!t.has_value()) return t.error();
  const RobotProfile& profile = mission_->profile;
  const double elapsed = elapsed_s_ + t->cost_s;
  const double needed = profile.energy_wh(elapsed);
  const double available =
      profile.battery_wh * (1 - mission_->battery_reserve_fraction) - progress_.energy_used_wh;
  if (!(needed <= available + kEnergyTolerance)) {
    std::string why = robot_name(*mission_) + "'s " + shortest(profile.battery_wh) +
                      " Wh less the " + shortest(mission_->battery_reserve_fraction * 100) +
                      "% reserve";
    if (progress_.energy_used_wh > 0) {
      why += " and " + fixed(progress_.energy_used_wh, 2) + " Wh used before";
    }
    return invalid("battery: " + fixed(needed, 2) + " Wh needed, " + fixed(available, 2) +
                   " Wh available (" + why + ")");
  }
  elapsed_s_ = elapsed;
  progress_.position = t->next;
  if (t->task_done) {
    progress_.done[t->task_done->index()] = true;
    finished_ = mission_->task(*t->task_done).final;
  }
  return t->cost_s;
}

Result<PlanReplay::Transition> PlanReplay::transition(const PlanStep& step) const {
  return std::visit(
      [this](const auto& s) -> Result<Transition> {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, DrivePipeToManhole>) {
          return drive_pipe_to_manhole(s);
        } else if constexpr (std::is_same_v<T, DriveManhole>) {
          return drive_manhole(s);
        } else if constexpr (std::is_same_v<T, EnterPipe>) {
          return enter_pipe(s);
        } else if constexpr (std::is_same_v<T, TakeWaterSample>) {
          return take_water_sample(s);
        } else if constexpr (std::is_same_v<T, InspectPipe>) {
          return inspect_pipe(s);
        } else if constexpr (std::is_same_v<T, GoToPoint>) {
          return go_to_point(s);
        } else {
          static_assert(std::is_same_v<T, GoToManhole>);
          return go_to_manhole(s);
        }
      },
      step);
}

Result<PlanReplay::Transition> PlanReplay::drive_pipe_to_manhole(
    const DrivePipeToManhole& s) const {
  if (!detail::in_map(*map_, s.manhole))
    return invalid("manhole " + name_of(*map_, s.manhole) + " is not in the map");
  Result<double> x = offset_in(s.pipe);
  if (!x.has_value()) return x.error();
  const Pipe& pipe = map_->pipe(s.pipe);
  auto end = end_in_manhole(*map_, s.pipe, s.manhole);
  if (!end) {
    return invalid(map_->manhole(s.manhole).name + " is not at an end of pipe " + pipe.name);
  }
  if (auto blocked = blocked_between(s.pipe, *x, end_offset_m(pipe, *end))) return *blocked;
  const double distance = std::abs(*x - end_offset_m(pipe, *end));
  return Transition{distance / mission_->profile.speed_mps, AtSlot{s.manhole, pipe.ends[*end].slot},
                    std::nullopt};
}

Result<PlanReplay::Transition> PlanReplay::drive_manhole(const DriveManhole& s) const {
  if (!detail::in_map(*map_, s.manhole))
    return invalid("manhole " + name_of(*map_, s.manhole) + " is not in the map");
  const Manhole& m = map_->manhole(s.manhole);
  for (SlotIndex slot : {s.from, s.to}) {
    if (slot.value() >= m.slot_count) {
      return invalid(m.name + " has slots 1 to " + std::to_string(m.slot_count) + ", not " +
                     std::to_string(to_paper_number(slot)));
    }
  }
  if (s.from == s.to) {
    return invalid("FROM and TO are the same slot " + std::to_string(to_paper_number(s.from)) +
                   " of " + m.name);
  }
  if (progress_.position != RobotPosition{AtSlot{s.manhole, s.from}}) {
    return invalid("the robot is " + describe(progress_.position, *map_) + ", not " +
                   describe(AtSlot{s.manhole, s.from}, *map_));
  }
  if (auto problem = passage_problem(s.manhole, s.from, s.to)) return invalid(*problem);
  const PassageVerdict verdict = judge_passage(
      *map_, mission_->profile, mission_->passage_motion.get(), s.manhole, s.from, s.to);
  const Slot& into = map_->slot(s.manhole, s.to);
  return Transition{verdict.duration_s,
                    InPipe{into.pipe, end_offset_m(map_->pipe(into.pipe), into.pipe_end)},
                    std::nullopt};
}

Result<PlanReplay::Transition> PlanReplay::enter_pipe(const EnterPipe& s) const {
  if (!detail::in_map(*map_, s.manhole))
    return invalid("manhole " + name_of(*map_, s.manhole) + " is not in the map");
  if (!detail::in_map(*map_, s.pipe))
    return invalid("pipe " + name_of(*map_, s.pipe) + " is not in the map");
  if (progress_.position != RobotPosition{InManhole{s.manhole}}) {
    return invalid("the robot is " + describe(progress_.position, *map_) + ", not in manhole " +
                   map_->manhole(s.manhole).name +
                   " (ENTER_PIPE starts a mission lowered into a manhole)");
  }
  const Pipe& pipe = map_->pipe(s.pipe);
  auto end = end_in_manhole(*map_, s.pipe, s.manhole);
  if (!end) {
    return invalid("pipe " + pipe.name + " has no end in " + map_->manhole(s.manhole).name);
  }
  if (auto problem = undrivable(s.pipe)) return invalid(*problem);
  return Transition{mission_->profile.manhole_pass_s, InPipe{s.pipe, end_offset_m(pipe, *end)},
                    std::nullopt};
}

Result<PlanReplay::Transition> PlanReplay::take_water_sample(const TakeWaterSample& s) const {
  Result<double> x = offset_in(s.pipe);
  if (!x.has_value()) return x.error();
  const bool here =
      detail::in_mission(*mission_, s.task) && detail::task_pipe(mission_->task(s.task)) == s.pipe;
  Result<const Task*> task =
      pending_task(s.task, TaskKind::kTakeWaterSample, here, "pipe " + map_->pipe(s.pipe).name);
  if (!task.has_value()) return task.error();
  const double y = detail::task_offset_m(**task, *map_).value_or(*x);
  if (auto blocked = blocked_between(s.pipe, *x, y)) return *blocked;
  return Transition{std::abs(*x - y) / mission_->profile.speed_mps + mission_->profile.sample_s,
                    InPipe{s.pipe, y}, s.task};
}

Result<PlanReplay::Transition> PlanReplay::go_to_point(const GoToPoint& s) const {
  Result<double> x = offset_in(s.pipe);
  if (!x.has_value()) return x.error();
  const bool here =
      detail::in_mission(*mission_, s.task) && detail::task_pipe(mission_->task(s.task)) == s.pipe;
  Result<const Task*> task =
      pending_task(s.task, TaskKind::kGoTo, here, "pipe " + map_->pipe(s.pipe).name);
  if (!task.has_value()) return task.error();
  const double y = detail::task_offset_m(**task, *map_).value_or(*x);
  if (auto blocked = blocked_between(s.pipe, *x, y)) return *blocked;
  return Transition{std::abs(*x - y) / mission_->profile.speed_mps, InPipe{s.pipe, y}, s.task};
}

Result<PlanReplay::Transition> PlanReplay::inspect_pipe(const InspectPipe& s) const {
  Result<double> x = offset_in(s.pipe);
  if (!x.has_value()) return x.error();
  const Pipe& pipe = map_->pipe(s.pipe);
  const bool here =
      detail::in_mission(*mission_, s.task) && detail::task_pipe(mission_->task(s.task)) == s.pipe;
  Result<const Task*> task =
      pending_task(s.task, TaskKind::kInspectPipe, here, "pipe " + pipe.name);
  if (!task.has_value()) return task.error();
  std::size_t finish = 0;
  if (s.finish_end) {
    if (*s.finish_end > 1) {
      return invalid("INSPECT_PIPE " + pipe.name + ": finish end " + std::to_string(*s.finish_end) +
                     " is neither 0 nor 1");
    }
    finish = *s.finish_end;
  } else if (std::abs(*x) <= kEndTolerance) {
    finish = 1;
  } else if (std::abs(*x - pipe.length_m) <= kEndTolerance) {
    finish = 0;
  } else {
    return invalid("the robot is " + describe(progress_.position, *map_) +
                   ", not at an end: INSPECT_PIPE " + pipe.name +
                   " must name the manhole where the inspection finishes");
  }
  const double start_offset = end_offset_m(pipe, 1 - finish);
  // The inspection drives the whole pipe, from its start end (reached first) to the other.
  if (auto blocked = blocked_between(s.pipe, *x, start_offset)) return *blocked;
  if (auto blocked = blocked_between(s.pipe, -1, pipe.length_m + 1)) return *blocked;
  const RobotProfile& profile = mission_->profile;
  return Transition{std::abs(*x - start_offset) / profile.speed_mps +
                        pipe.length_m / profile.inspection_speed_mps,
                    InPipe{s.pipe, end_offset_m(pipe, finish)}, s.task};
}

Result<PlanReplay::Transition> PlanReplay::go_to_manhole(const GoToManhole& s) const {
  if (!detail::in_map(*map_, s.manhole))
    return invalid("manhole " + name_of(*map_, s.manhole) + " is not in the map");
  const std::string& name = map_->manhole(s.manhole).name;
  if (manhole_of(progress_.position) != s.manhole) {
    return invalid("the robot is " + describe(progress_.position, *map_) + ", not at manhole " +
                   name);
  }
  const bool here = detail::in_mission(*mission_, s.task) &&
                    detail::task_manhole(mission_->task(s.task)) == s.manhole;
  Result<const Task*> task = pending_task(s.task, TaskKind::kGoTo, here, "manhole " + name);
  if (!task.has_value()) return task.error();
  return Transition{0.0, progress_.position, s.task};
}

std::optional<Error> PlanReplay::blocked_between(PipeId pipe, double from, double to) const {
  const auto blockage = sewerplan::blockage_between(*mission_, pipe, from, to);
  if (!blockage) return std::nullopt;
  return Error{ErrorCode::kInvalidArgument, "pipe " + map_->pipe(pipe).name + " is blocked at " +
                                                detail::fixed(blockage->offset_m, 2) + " m"};
}

Result<double> PlanReplay::offset_in(PipeId pipe) const {
  if (!detail::in_map(*map_, pipe))
    return invalid("pipe " + name_of(*map_, pipe) + " is not in the map");
  const auto* in = std::get_if<InPipe>(&progress_.position);
  if (in == nullptr || in->pipe != pipe) {
    return invalid("the robot is " + describe(progress_.position, *map_) + ", not in pipe " +
                   map_->pipe(pipe).name);
  }
  // Only a start can put the robot in a pipe it does not fit: DRIVE_MANHOLE and ENTER_PIPE
  // check the pipe they drive into. A closure forbids entering a pipe, not leaving it.
  if (auto problem = does_not_fit(pipe)) {
    return invalid("the robot starts in pipe " + map_->pipe(pipe).name + ", which " +
                   robot_name(*mission_) + " cannot drive: " + *problem);
  }
  return in->offset_m;
}

Result<const Task*> PlanReplay::pending_task(TaskId id, TaskKind kind, bool at_place,
                                             const std::string& place) const {
  if (!detail::in_mission(*mission_, id)) {
    return invalid("task #" + std::to_string(id.value()) + " is not in the mission");
  }
  const Task& task = mission_->task(id);
  if (task.kind != kind) {
    return invalid("task '" + task.name + "' is of kind " + std::string(to_string(task.kind)) +
                   ", not " + std::string(to_string(kind)));
  }
  if (!at_place) {
    return invalid("task '" + task.name + "' is at " + describe(task.place, *map_) + ", not at " +
                   place);
  }
  if (progress_.done[id.index()])
    return invalid(detail::describe_task(*mission_, id) + " is already done");
  if (task.final) {
    for (TaskId other : mission_->task_ids()) {
      if (other != id && !progress_.done[other.index()]) {
        return invalid("the final task '" + task.name + "' must be done last, but " +
                       detail::describe_task(*mission_, other) + " is not done");
      }
    }
  }
  return &task;
}

std::optional<std::string> PlanReplay::passage_problem(ManholeId m, SlotIndex from,
                                                       SlotIndex to) const {
  if (auto problem = undrivable(map_->slot(m, to).pipe)) return problem;
  // Named only for a problem: a plan's replay passes thousands of passages.
  const auto passage = [&] { return passage_text(*map_, m, from, to); };
  for (const ClosedPassage& c : mission_->closed_passages) {
    if (c.manhole == m && ((c.from == from && c.to == to) || (c.from == to && c.to == from))) {
      return passage() + " is closed";
    }
  }
  const RobotProfile& profile = mission_->profile;
  const PassageVerdict verdict =
      judge_passage(*map_, profile, mission_->passage_motion.get(), m, from, to);
  if (verdict.by_motion) {
    if (verdict.allowed) return std::nullopt;
    return passage() + ": the motion planner found no motion for " + robot_name(*mission_) + " (" +
           verdict.motion->reason + ")";
  }
  const double turn = verdict.turn_deg;
  if (!(turn <= profile.max_turn_deg + kLimitTolerance)) {
    return passage() + ": turn of " + fixed(turn, 1) + " deg exceeds " + robot_name(*mission_) +
           "'s " + shortest(profile.max_turn_deg) + " deg";
  }
  const double step = verdict.step_m;
  if (!(std::abs(step) <= profile.max_step_m + kLimitTolerance)) {
    return passage() + ": step of " + fixed(step, 2) + " m exceeds " + robot_name(*mission_) +
           "'s " + fixed(profile.max_step_m, 2) + " m";
  }
  return std::nullopt;
}

std::optional<std::string> PlanReplay::does_not_fit(PipeId id) const {
  const Pipe& pipe = map_->pipe(id);
  const RobotProfile& profile = mission_->profile;
  if (!(pipe.diameter_m >= profile.min_pipe_diameter_m &&
        pipe.diameter_m <= profile.max_pipe_diameter_m)) {
    return "pipe " + pipe.name + " is " + fixed(pipe.diameter_m, 2) + " m, outside " +
           robot_name(*mission_) + "'s " + fixed(profile.min_pipe_diameter_m, 2) + "-" +
           fixed(profile.max_pipe_diameter_m, 2) + " m";
  }
  return std::nullopt;
}

std::optional<std::string> PlanReplay::undrivable(PipeId id) const {
  if (auto problem = does_not_fit(id)) return problem;
  const Pipe& pipe = map_->pipe(id);
  const auto& closed = mission_->closed_pipes;
  if (std::find(closed.begin(), closed.end(), id) != closed.end()) {
    return "pipe " + pipe.name + " is closed";
  }
  return std::nullopt;
}

Error PlanReplay::invalid(std::string message) const {
  return Error{ErrorCode::kInvalidArgument, std::move(message)};
}

}  // namespace sewerplan::domain
