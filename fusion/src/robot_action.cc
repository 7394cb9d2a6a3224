// SPDX-License-Identifier: MIT
#include "sewerplan/fusion/robot_action.h"

#include <iomanip>
#include <type_traits>

namespace sewerplan::fusion {
namespace {

std::ostream& operator<<(std::ostream& os, const PipeDrive& drive) {
  return os << drive.direction << ' ' << drive.distance_m << " m at " << drive.speed_mps << " m/s";
}

void print(std::ostream& os, const DriveToManhole& a) {
  os << "DriveToManhole(pipe " << a.pipe << " -> manhole " << a.manhole << ", "
     << PipeDrive{a.direction, a.distance_m, a.speed_mps} << ", type " << a.manhole_type;
  if (a.manhole_variant) os << *a.manhole_variant;
  os << ", pipe " << a.pipe_diameter_m << " m)";
}

void print(std::ostream& os, const PassManhole& a) {
  os << "PassManhole(manhole " << a.manhole << ", slot " << to_paper_number(a.from_slot) << " -> "
     << to_paper_number(a.to_slot) << ", turn " << std::setprecision(1) << a.turn_deg
     << " deg, step " << std::setprecision(2) << a.step_m << " m, manhole " << a.manhole_diameter_m
     << " m)";
}

void print(std::ostream& os, const EnterPipe& a) {
  os << "EnterPipe(manhole " << a.manhole << ", slot " << to_paper_number(a.slot) << ", pipe "
     << a.pipe << ")";
}

void print(std::ostream& os, const TakeWaterSample& a) {
  os << "TakeWaterSample(pipe " << a.pipe << " at " << a.offset_m << " m, task " << a.task << ", "
     << a.drive << ", sample " << a.sample_s << " s)";
}

void print(std::ostream& os, const InspectPipe& a) {
  os << "InspectPipe(pipe " << a.pipe << ", task " << a.task << ", end " << +a.start_end << " -> "
     << +a.finish_end << ", scan " << a.scan_direction << ' ' << a.length_m << " m at "
     << a.speed_mps << " m/s, approach " << a.approach << ")";
}

void print(std::ostream& os, const GoToPoint& a) {
  os << "GoToPoint(pipe " << a.pipe << " at " << a.offset_m << " m, task " << a.task << ", "
     << a.drive << ")";
}

void print(std::ostream& os, const GoToManhole& a) {
  os << "GoToManhole(manhole " << a.manhole << ", task " << a.task << ")";
}

}  // namespace

std::string_view to_string(Direction direction) {
  switch (direction) {
    case Direction::kForward:
      return "forward";
    case Direction::kBackward:
      return "backward";
  }
  return "?";
}

std::ostream& operator<<(std::ostream& os, Direction direction) {
  return os << to_string(direction);
}

std::string_view action_kind(const RobotAction& action) {
  return std::visit(
      [](const auto& a) -> std::string_view {
        using T = std::decay_t<decltype(a)>;
        if constexpr (std::is_same_v<T, DriveToManhole>) {
          return "drive_to_manhole";
        } else if constexpr (std::is_same_v<T, PassManhole>) {
          return "pass_manhole";
        } else if constexpr (std::is_same_v<T, EnterPipe>) {
          return "enter_pipe";
        } else if constexpr (std::is_same_v<T, TakeWaterSample>) {
          return "take_water_sample";
        } else if constexpr (std::is_same_v<T, InspectPipe>) {
          return "inspect_pipe";
        } else if constexpr (std::is_same_v<T, GoToPoint>) {
          return "go_to_point";
        } else {
          static_assert(std::is_same_v<T, GoToManhole>);
          return "go_to_manhole";
        }
      },
      action);
}

std::size_t plan_step(const RobotAction& action) {
  return std::visit([](const auto& a) { return a.plan_step; }, action);
}

double duration_s(const RobotAction& action) {
  return std::visit([](const auto& a) { return a.duration_s; }, action);
}

std::ostream& operator<<(std::ostream& os, const RobotAction& action) {
  const auto flags = os.flags();
  const auto precision = os.precision();
  os << std::fixed << std::setprecision(2);
  std::visit([&os](const auto& a) { print(os, a); }, action);
  os << " [" << std::setprecision(1) << duration_s(action) << " s]";
  os.flags(flags);
  os.precision(precision);
  return os;
}

double FusedPlan::total_duration_s() const {
  double total = 0;
  for (const RobotAction& action : actions) total += duration_s(action);
  return total;
}

std::ostream& operator<<(std::ostream& os, const FusedPlan& plan) {
  for (const RobotAction& action : plan.actions) {
    os << "step " << plan_step(action) + 1 << ": " << action << '\n';
  }
  return os;
}

}  // namespace sewerplan::fusion
