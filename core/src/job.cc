// SPDX-License-Identifier: MIT
#include "sewerplan/core/job.h"

#include <iomanip>

#include "sewerplan/core/overloaded.h"

namespace sewerplan {

std::string_view job_kind(const Job& job) {
  return std::visit(Overloaded{
                        [](const DriveForward&) { return std::string_view("drive_forward"); },
                        [](const DriveBackward&) { return std::string_view("drive_backward"); },
                        [](const Push&) { return std::string_view("push"); },
                        [](const TurnInManhole&) { return std::string_view("turn_in_manhole"); },
                        [](const EnterPipeFromManhole&) { return std::string_view("enter_pipe"); },
                        [](const LiftHead&) { return std::string_view("lift_head"); },
                        [](const LowerHead&) { return std::string_view("lower_head"); },
                        [](const TakeSample&) { return std::string_view("take_sample"); },
                        [](const Scan&) { return std::string_view("scan"); },
                        [](const Stop&) { return std::string_view("stop"); },
                    },
                    job);
}

std::ostream& operator<<(std::ostream& os, const Job& job) {
  const auto flags = os.flags();
  const auto precision = os.precision();
  os << std::fixed << std::setprecision(2);
  std::visit(
      Overloaded{
          [&](const DriveForward& j) {
            os << "DriveForward(" << j.speed_mps << " m/s, " << j.distance_m << " m)";
          },
          [&](const DriveBackward& j) {
            os << "DriveBackward(" << j.speed_mps << " m/s, " << j.distance_m << " m)";
          },
          [&](const Push& j) {
            os << "Push(" << j.speed_mps << " m/s, " << j.distance_m << " m"
               << (j.backward ? ", backward)" : ")");
          },
          [&](const TurnInManhole& j) {
            if (j.from_slot == kBySighting) {
              os << "TurnInManhole(arrival -> mouth " << j.to_slot + 1 << " seen, ";
            } else {
              os << "TurnInManhole(slot " << j.from_slot + 1 << " -> " << j.to_slot + 1 << ", ";
            }
            os << std::setprecision(1) << j.turn_deg << " deg, step " << std::setprecision(2)
               << j.step_m << " m";
            if (!j.waypoints.empty()) os << ", " << j.waypoints.size() << " waypoints";
            os << ")";
          },
          [&](const EnterPipeFromManhole& j) { os << "EnterPipe(slot " << j.slot + 1 << ")"; },
          [&](const LiftHead&) { os << "LiftHead"; },
          [&](const LowerHead&) { os << "LowerHead"; },
          [&](const TakeSample& j) {
            os << "TakeSample(" << std::setprecision(0) << j.duration_s << " s)";
          },
          [&](const Scan& j) { os << "Scan(" << j.speed_mps << " m/s, " << j.distance_m << " m)"; },
          [&](const Stop&) { os << "Stop"; },
      },
      job);
  os.flags(flags);
  os.precision(precision);
  return os;
}

}  // namespace sewerplan
