// SPDX-License-Identifier: MIT
// fuse(): replays the plan with PlanReplay and resolves each step into a RobotAction.
#include "sewerplan/fusion/fuse.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>

#include "sewerplan/core/check.h"
#include "sewerplan/core/map_queries.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"

namespace sewerplan::fusion {
namespace {

using domain::end_offset_m;
using domain::InPipe;

std::string metres(double v) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << v << " m";
  return out.str();
}

// Direction of a drive from offset x to offset y for a robot facing end `heading_end`. No motion
// counts as forward.
Direction drive_direction(double x_m, double y_m, std::uint8_t heading_end) {
  if (x_m == y_m) return Direction::kForward;
  return (heading_end == 1) == (y_m > x_m) ? Direction::kForward : Direction::kBackward;
}

// Turns one plan step after another into actions, keeping the robot's heading in its pipe.
class Fuser {
 public:
  Fuser(const SewerMap& map, const Mission& mission, const domain::MissionProgress& start,
        const FuseOptions& options)
      : map_(map), mission_(mission), profile_(mission.profile), replay_(map, mission, start) {
    if (std::holds_alternative<InPipe>(start.position)) heading_end_ = options.start_heading_end;
  }

  Result<RobotAction> next(std::size_t index, const domain::PlanStep& step) {
    const domain::RobotPosition before = replay_.position();
    Result<double> cost = replay_.apply(step);
    if (!cost.has_value()) return step_error(index, step, cost.error().code, cost.error().message);
    const domain::RobotPosition& after = replay_.position();
    Result<RobotAction> action =
        std::visit([&](const auto& s) { return resolve(index, s, before, after); }, step);
    if (!action.has_value()) {
      return step_error(index, step, action.error().code, action.error().message);
    }
    // Both sides compute docs/domain.md's cost with the same expression: the same bits.
    SEWER_CHECK(duration_s(*action) == *cost, "fusion: an action's duration differs from its cost");
    return action;
  }

 private:
  Error step_error(std::size_t index, const domain::PlanStep& step, ErrorCode code,
                   const std::string& message) const {
    return Error{code, "step " + std::to_string(index + 1) + " (" +
                           domain::format_step(step, map_, mission_) + "): " + message};
  }

  // The replay has checked the step: the robot was in the pipe, the task pending, and so on.
  static double offset(const domain::RobotPosition& position) {
    return std::get<InPipe>(position).offset_m;
  }

  Result<RobotAction> resolve(std::size_t index, const domain::DrivePipeToManhole& s,
                              const domain::RobotPosition& before, const domain::RobotPosition&) {
    if (auto bad = pipe_problem(s.pipe)) return *bad;
    const Pipe& pipe = map_.pipe(s.pipe);
    const Manhole& manhole = map_.manhole(s.manhole);
    const std::size_t end = *end_in_manhole(map_, s.pipe, s.manhole);
    const double x = offset(before);
    const double y = end_offset_m(pipe, end);
    const double distance = std::abs(x - y);
    const Direction direction = end == heading() ? Direction::kForward : Direction::kBackward;
    heading_end_.reset();
    return RobotAction{DriveToManhole{.plan_step = index,
                                      .pipe = s.pipe,
                                      .manhole = s.manhole,
                                      .direction = direction,
                                      .distance_m = distance,
                                      .manhole_type = manhole.slot_count,
                                      .manhole_variant = manhole.variant,
                                      .pipe_diameter_m = pipe.diameter_m,
                                      .speed_mps = profile_.speed_mps,
                                      .from_offset_m = x,
                                      .to_offset_m = y,
                                      .duration_s = distance / profile_.speed_mps}};
  }

  Result<RobotAction> resolve(std::size_t index, const domain::DriveManhole& s,
                              const domain::RobotPosition&, const domain::RobotPosition&) {
    const Slot& from = map_.slot(s.manhole, s.from);
    const Slot& into = map_.slot(s.manhole, s.to);
    if (auto bad = manhole_problem(s.manhole, {from.pipe, into.pipe})) return *bad;
    for (const Slot* slot : {&from, &into}) {
      if (!std::isfinite(slot->azimuth_deg) || !std::isfinite(slot->invert_z_m)) {
        return invalid_map("manhole " + map_.manhole(s.manhole).name + ": the slot of pipe " +
                           map_.pipe(slot->pipe).name +
                           " has no usable azimuth or invert height for the turn");
      }
    }
    if (auto bad = pipe_problem(into.pipe)) return *bad;
    const PassageVerdict verdict =
        judge_passage(map_, profile_, mission_.passage_motion.get(), s.manhole, s.from, s.to);
    heading_end_ = static_cast<std::uint8_t>(1 - into.pipe_end);
    return RobotAction{PassManhole{.plan_step = index,
                                   .manhole = s.manhole,
                                   .from_slot = s.from,
                                   .to_slot = s.to,
                                   .from_pipe = from.pipe,
                                   .to_pipe = into.pipe,
                                   .turn_deg = verdict.turn_deg,
                                   .step_m = verdict.step_m,
                                   .manhole_diameter_m = map_.manhole(s.manhole).diameter_m,
                                   .duration_s = verdict.duration_s,
                                   .waypoints = verdict.motion != nullptr
                                                    ? verdict.motion->waypoints
                                                    : std::vector<Waypoint>{}}};
  }

  Result<RobotAction> resolve(std::size_t index, const domain::EnterPipe& s,
                              const domain::RobotPosition&, const domain::RobotPosition&) {
    if (auto bad = manhole_problem(s.manhole, {s.pipe})) return *bad;
    if (auto bad = pipe_problem(s.pipe)) return *bad;
    const std::size_t end = *end_in_manhole(map_, s.pipe, s.manhole);
    heading_end_ = static_cast<std::uint8_t>(1 - end);
    return RobotAction{EnterPipe{.plan_step = index,
                                 .manhole = s.manhole,
                                 .slot = map_.pipe(s.pipe).ends[end].slot,
                                 .pipe = s.pipe,
                                 .duration_s = profile_.manhole_pass_s}};
  }

  Result<RobotAction> resolve(std::size_t index, const domain::TakeWaterSample& s,
                              const domain::RobotPosition& before,
                              const domain::RobotPosition& after) {
    if (auto bad = pipe_problem(s.pipe)) return *bad;
    const PipeDrive drive = drive_to(offset(before), offset(after));
    return RobotAction{
        TakeWaterSample{.plan_step = index,
                        .pipe = s.pipe,
                        .offset_m = offset(after),
                        .task = s.task,
                        .drive = drive,
                        .sample_s = profile_.sample_s,
                        .duration_s = drive.distance_m / profile_.speed_mps + profile_.sample_s}};
  }

  Result<RobotAction> resolve(std::size_t index, const domain::InspectPipe& s,
                              const domain::RobotPosition& before,
                              const domain::RobotPosition& after) {
    if (auto bad = pipe_problem(s.pipe)) return *bad;
    const Pipe& pipe = map_.pipe(s.pipe);
    const std::uint8_t finish =
        s.finish_end.value_or(offset(after) == end_offset_m(pipe, 1) ? 1 : 0);
    const auto start = static_cast<std::uint8_t>(1 - finish);
    const PipeDrive approach = drive_to(offset(before), end_offset_m(pipe, start));
    return RobotAction{InspectPipe{
        .plan_step = index,
        .pipe = s.pipe,
        .task = s.task,
        .length_m = pipe.length_m,
        .speed_mps = profile_.inspection_speed_mps,
        .start_end = start,
        .finish_end = finish,
        .scan_direction = finish == heading() ? Direction::kForward : Direction::kBackward,
        .approach = approach,
        .duration_s = approach.distance_m / profile_.speed_mps +
                      pipe.length_m / profile_.inspection_speed_mps}};
  }

  Result<RobotAction> resolve(std::size_t index, const domain::GoToPoint& s,
                              const domain::RobotPosition& before,
                              const domain::RobotPosition& after) {
    if (auto bad = pipe_problem(s.pipe)) return *bad;
    const PipeDrive drive = drive_to(offset(before), offset(after));
    return RobotAction{GoToPoint{.plan_step = index,
                                 .pipe = s.pipe,
                                 .offset_m = offset(after),
                                 .task = s.task,
                                 .drive = drive,
                                 .duration_s = drive.distance_m / profile_.speed_mps}};
  }

  Result<RobotAction> resolve(std::size_t index, const domain::GoToManhole& s,
                              const domain::RobotPosition&, const domain::RobotPosition&) {
    return RobotAction{GoToManhole{.plan_step = index, .manhole = s.manhole, .task = s.task}};
  }

  // The end the robot faces in its pipe. Set whenever the robot is in a pipe (checked).
  std::uint8_t heading() const {
    SEWER_CHECK(heading_end_.has_value(), "fusion: the robot's heading in its pipe is unknown");
    return *heading_end_;
  }

  PipeDrive drive_to(double x_m, double y_m) const {
    return PipeDrive{.direction = drive_direction(x_m, y_m, heading()),
                     .distance_m = std::abs(x_m - y_m),
                     .speed_mps = profile_.speed_mps};
  }

  std::optional<Error> pipe_problem(PipeId id) const {
    const Pipe& pipe = map_.pipe(id);
    if (!(std::isfinite(pipe.length_m) && pipe.length_m > 0)) {
      return invalid_map("pipe " + pipe.name + " has no usable length (" + metres(pipe.length_m) +
                         ")");
    }
    if (!(std::isfinite(pipe.diameter_m) && pipe.diameter_m > 0)) {
      return invalid_map("pipe " + pipe.name + " has no usable diameter (" +
                         metres(pipe.diameter_m) + ")");
    }
    return std::nullopt;
  }

  // A manhole the robot turns in must be known to be at least as wide as the pipes it joins.
  std::optional<Error> manhole_problem(ManholeId id, std::initializer_list<PipeId> pipes) const {
    const Manhole& manhole = map_.manhole(id);
    if (!(std::isfinite(manhole.diameter_m) && manhole.diameter_m > 0)) {
      return invalid_map("manhole " + manhole.name + " has no usable diameter (" +
                         metres(manhole.diameter_m) + ")");
    }
    for (PipeId p : pipes) {
      const Pipe& pipe = map_.pipe(p);
      if (manhole.diameter_m < pipe.diameter_m) {
        return invalid_map("manhole " + manhole.name + " (" + metres(manhole.diameter_m) +
                           ") is narrower than pipe " + pipe.name + " (" + metres(pipe.diameter_m) +
                           ") that opens into it: its diameter cannot be right");
      }
    }
    return std::nullopt;
  }

  static Error invalid_map(std::string message) {
    return Error{ErrorCode::kInvalidMap, std::move(message)};
  }

  const SewerMap& map_;
  const Mission& mission_;
  const RobotProfile& profile_;
  domain::PlanReplay replay_;
  std::optional<std::uint8_t> heading_end_;  // the end the robot faces, while in a pipe
};

}  // namespace

Result<FusedPlan> fuse(const domain::Plan& plan, const SewerMap& map, const Mission& mission,
                       const domain::MissionProgress& start, const FuseOptions& options) {
  if (auto problem = domain::start_problem(map, mission, start)) {
    return Error{ErrorCode::kInvalidArgument, "invalid start: " + *problem};
  }
  if (options.start_heading_end > 1) {
    return Error{
        ErrorCode::kInvalidArgument,
        "start_heading_end is " + std::to_string(+options.start_heading_end) + ", neither 0 nor 1"};
  }
  if (Result<void> ok = validate_profile(mission.profile); !ok.has_value()) return ok.error();
  Fuser fuser(map, mission, start, options);
  FusedPlan fused;
  fused.actions.reserve(plan.steps.size());
  for (std::size_t i = 0; i < plan.steps.size(); ++i) {
    Result<RobotAction> action = fuser.next(i, plan.steps[i]);
    if (!action.has_value()) return action.error();
    fused.actions.push_back(std::move(*action));
  }
  return fused;
}

}  // namespace sewerplan::fusion
