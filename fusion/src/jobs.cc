// SPDX-License-Identifier: MIT
#include "sewerplan/fusion/jobs.h"

#include <type_traits>

namespace sewerplan::fusion {
namespace {

// A drive along the pipe; nothing for a distance of 0 unless `onto_mouth`.
// A drive onto a mouth is one `to_manhole` (core/job.h): it ends where the robot sees the manhole.
void add_drive(std::vector<Job>& jobs, const PipeDrive& drive, bool onto_mouth = false) {
  if (drive.distance_m == 0 && !onto_mouth) return;
  switch (drive.direction) {
    case Direction::kForward:
      jobs.emplace_back(DriveForward{
          .speed_mps = drive.speed_mps, .distance_m = drive.distance_m, .to_manhole = onto_mouth});
      return;
    case Direction::kBackward:
      jobs.emplace_back(DriveBackward{
          .speed_mps = drive.speed_mps, .distance_m = drive.distance_m, .to_manhole = onto_mouth});
      return;
  }
}

}  // namespace

std::vector<Job> expand(const RobotAction& action, const RobotProfile& /*profile*/) {
  std::vector<Job> jobs;
  std::visit(
      [&jobs](const auto& a) {
        using T = std::decay_t<decltype(a)>;
        if constexpr (std::is_same_v<T, DriveToManhole>) {
          // Also of 0 m: a robot right at the pipe's end (as a pass into the pipe leaves it)
          // still drives onto the mouth; at the mouth already, a robot does nothing.
          add_drive(jobs, {a.direction, a.distance_m, a.speed_mps}, /*onto_mouth=*/true);
        } else if constexpr (std::is_same_v<T, PassManhole>) {
          jobs.emplace_back(TurnInManhole{.from_slot = a.from_slot.value(),
                                          .to_slot = a.to_slot.value(),
                                          .turn_deg = a.turn_deg,
                                          .step_m = a.step_m,
                                          .manhole_diameter_m = a.manhole_diameter_m,
                                          .duration_s = a.duration_s,
                                          .waypoints = a.waypoints});
        } else if constexpr (std::is_same_v<T, EnterPipe>) {
          jobs.emplace_back(
              EnterPipeFromManhole{.slot = a.slot.value(), .duration_s = a.duration_s});
        } else if constexpr (std::is_same_v<T, TakeWaterSample>) {
          add_drive(jobs, a.drive);
          jobs.emplace_back(Stop{});
          jobs.emplace_back(TakeSample{.duration_s = a.sample_s});
        } else if constexpr (std::is_same_v<T, InspectPipe>) {
          add_drive(jobs, a.approach);
          jobs.emplace_back(Scan{.speed_mps = a.speed_mps,
                                 .distance_m = a.length_m,
                                 .backward = a.scan_direction == Direction::kBackward});
        } else if constexpr (std::is_same_v<T, GoToPoint>) {
          add_drive(jobs, a.drive);
        } else {
          static_assert(std::is_same_v<T, GoToManhole>);
        }
      },
      action);
  return jobs;
}

std::ostream& operator<<(std::ostream& os, const PlannedJob& job) {
  return os << "action " << job.action_index << " job " << job.job_index << ": " << job.job;
}

std::vector<PlannedJob> expand_plan(const FusedPlan& plan, const RobotProfile& profile) {
  std::vector<PlannedJob> all;
  for (std::size_t a = 0; a < plan.actions.size(); ++a) {
    std::vector<Job> jobs = expand(plan.actions[a], profile);
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      all.push_back(PlannedJob{.action_index = a, .job_index = j, .job = std::move(jobs[j])});
    }
  }
  return all;
}

}  // namespace sewerplan::fusion
