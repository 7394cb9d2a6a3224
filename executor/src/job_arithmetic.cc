// SPDX-License-Identifier: MIT
#include "job_arithmetic.h"

#include <algorithm>
#include <sstream>

#include "sewerplan/core/overloaded.h"

namespace sewerplan::executor::detail {

std::optional<Job> rest_of(const Job& job, double done_m) {
  return std::visit(
      Overloaded{
          [&](const DriveForward& j) -> std::optional<Job> {
            return DriveForward{j.speed_mps, std::max(0.0, j.distance_m - done_m), j.to_manhole};
          },
          [&](const DriveBackward& j) -> std::optional<Job> {
            return DriveBackward{j.speed_mps, std::max(0.0, j.distance_m - done_m), j.to_manhole};
          },
          [&](const Push& j) -> std::optional<Job> {
            return Push{j.speed_mps, std::max(0.0, j.distance_m - done_m), j.backward};
          },
          [&](const Scan& j) -> std::optional<Job> {
            return Scan{j.speed_mps, std::max(0.0, j.distance_m - done_m), j.backward};
          },
          [](const auto&) -> std::optional<Job> { return std::nullopt; }},
      job);
}

Job reversed(const Job& job) {
  return std::visit(Overloaded{[](const DriveForward& j) -> Job {
                                 return DriveBackward{j.speed_mps, j.distance_m, j.to_manhole};
                               },
                               [](const DriveBackward& j) -> Job {
                                 return DriveForward{j.speed_mps, j.distance_m, j.to_manhole};
                               },
                               [](const Push& j) -> Job {
                                 return Push{j.speed_mps, j.distance_m, !j.backward};
                               },
                               [](const Scan& j) -> Job {
                                 return Scan{j.speed_mps, j.distance_m, !j.backward};
                               },
                               [](const auto& j) -> Job { return j; }},
                    job);
}

double distance_left_m(const Job& job) {
  return std::visit(
      [](const auto& j) {
        if constexpr (requires { j.distance_m; }) {
          return j.distance_m;
        } else {
          return 0.0;
        }
      },
      job);
}

Job lengthened(const Job& job, double extra_m) {
  return std::visit(
      [&](auto j) -> Job {
        if constexpr (requires { j.distance_m; }) j.distance_m += extra_m;
        return j;
      },
      job);
}

Job back_off(const Job& job, double distance_m) {
  return std::visit(Overloaded{[&](const DriveBackward& j) -> Job {
                                 return DriveForward{j.speed_mps, distance_m};
                               },
                               [&](const Push& j) -> Job {
                                 if (j.backward) return DriveForward{j.speed_mps, distance_m};
                                 return DriveBackward{j.speed_mps, distance_m};
                               },
                               [&](const Scan& j) -> Job {
                                 if (j.backward) return DriveForward{j.speed_mps, distance_m};
                                 return DriveBackward{j.speed_mps, distance_m};
                               },
                               [&](const auto& j) -> Job {
                                 if constexpr (requires { j.speed_mps; }) {
                                   return DriveBackward{j.speed_mps, distance_m};
                                 }
                                 return DriveBackward{0.1, distance_m};
                               }},
                    job);
}

std::optional<Job> push_for(const Job& job) {
  return std::visit(Overloaded{[](const DriveForward& j) -> std::optional<Job> {
                                 return Push{j.speed_mps, j.distance_m, false};
                               },
                               [](const DriveBackward& j) -> std::optional<Job> {
                                 return Push{j.speed_mps, j.distance_m, true};
                               },
                               [](const Push& j) -> std::optional<Job> { return j; },
                               [](const Scan& j) -> std::optional<Job> {
                                 return Push{j.speed_mps, j.distance_m, j.backward};
                               },
                               [](const auto&) -> std::optional<Job> { return std::nullopt; }},
                    job);
}

hal::Approach approach_of(const Job& job) {
  const bool backward = std::visit(
      Overloaded{[](const DriveBackward&) { return true; },
                 [](const Push& j) { return j.backward; }, [](const Scan& j) { return j.backward; },
                 [](const auto&) { return false; }},
      job);
  return backward ? hal::Approach::kRear : hal::Approach::kFront;
}

std::string job_text(const Job& job) {
  std::ostringstream out;
  out << job;
  return out.str();
}

bool ends_at_manhole(const Job& job) {
  if (const auto* f = std::get_if<DriveForward>(&job)) return f->to_manhole;
  if (const auto* b = std::get_if<DriveBackward>(&job)) return b->to_manhole;
  return false;
}

}  // namespace sewerplan::executor::detail
