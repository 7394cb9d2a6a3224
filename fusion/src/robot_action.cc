// SPDX-License-Identifier: MIT
#include "sewerplan/fusion/robot_action.h"

#include <iomanip>
#include <sstream>
#include <string>
#include <type_traits>

#include "sewerplan/fusion/action_text.h"

namespace sewerplan::fusion {
namespace {

// How an action names its objects: by the map's and the mission's names when it has them
// (describe(), the event log), else by their IDs ("#11", operator<<).
struct Names {
  const SewerMap* map = nullptr;
  const Mission* mission = nullptr;
  std::string operator()(PipeId id) const {
    return map != nullptr && id.value() < map->pipe_count() ? map->pipe(id).name : id_text(id);
  }
  std::string operator()(ManholeId id) const {
    return map != nullptr && id.value() < map->manhole_count() ? map->manhole(id).name
                                                               : id_text(id);
  }
  std::string operator()(TaskId id) const {
    return mission != nullptr && id.index() < mission->tasks.size() ? mission->task(id).name
                                                                    : id_text(id);
  }
  template <class Id>
  static std::string id_text(Id id) {
    std::ostringstream out;
    out << id;
    return out.str();
  }
};

std::ostream& operator<<(std::ostream& os, const PipeDrive& drive) {
  return os << drive.direction << ' ' << drive.distance_m << " m at " << drive.speed_mps << " m/s";
}

void print(std::ostream& os, const DriveToManhole& a, const Names& n) {
  os << "DriveToManhole(pipe " << n(a.pipe) << " -> manhole " << n(a.manhole) << ", "
     << PipeDrive{a.direction, a.distance_m, a.speed_mps} << ", type " << a.manhole_type;
  if (a.manhole_variant) os << *a.manhole_variant;
  os << ", pipe " << a.pipe_diameter_m << " m)";
}

void print(std::ostream& os, const PassManhole& a, const Names& n) {
  os << "PassManhole(manhole " << n(a.manhole) << ", slot " << to_paper_number(a.from_slot)
     << " -> " << to_paper_number(a.to_slot) << ", turn " << std::setprecision(1) << a.turn_deg
     << " deg, step " << std::setprecision(2) << a.step_m << " m, manhole " << a.manhole_diameter_m
     << " m)";
}

void print(std::ostream& os, const EnterPipe& a, const Names& n) {
  os << "EnterPipe(manhole " << n(a.manhole) << ", slot " << to_paper_number(a.slot) << ", pipe "
     << n(a.pipe) << ")";
}

void print(std::ostream& os, const TakeWaterSample& a, const Names& n) {
  os << "TakeWaterSample(pipe " << n(a.pipe) << " at " << a.offset_m << " m, task " << n(a.task)
     << ", " << a.drive << ", sample " << a.sample_s << " s)";
}

void print(std::ostream& os, const InspectPipe& a, const Names& n) {
  os << "InspectPipe(pipe " << n(a.pipe) << ", task " << n(a.task) << ", end " << +a.start_end
     << " -> " << +a.finish_end << ", scan " << a.scan_direction << ' ' << a.length_m << " m at "
     << a.speed_mps << " m/s, approach " << a.approach << ")";
}

void print(std::ostream& os, const GoToPoint& a, const Names& n) {
  os << "GoToPoint(pipe " << n(a.pipe) << " at " << a.offset_m << " m, task " << n(a.task) << ", "
     << a.drive << ")";
}

void print(std::ostream& os, const GoToManhole& a, const Names& n) {
  os << "GoToManhole(manhole " << n(a.manhole) << ", task " << n(a.task) << ")";
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

namespace {

void print_action(std::ostream& os, const RobotAction& action, const Names& names) {
  const auto flags = os.flags();
  const auto precision = os.precision();
  os << std::fixed << std::setprecision(2);
  std::visit([&](const auto& a) { print(os, a, names); }, action);
  os << " [" << std::setprecision(1) << duration_s(action) << " s]";
  os.flags(flags);
  os.precision(precision);
}

}  // namespace

std::ostream& operator<<(std::ostream& os, const RobotAction& action) {
  print_action(os, action, Names{});
  return os;
}

std::string describe(const RobotAction& action, const SewerMap& map, const Mission& mission) {
  std::ostringstream out;
  print_action(out, action, Names{&map, &mission});
  return out.str();
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
