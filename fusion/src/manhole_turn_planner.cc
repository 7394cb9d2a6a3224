// SPDX-License-Identifier: MIT
// ManholeTurnPlanner: the analytic checks, the head path from the HeadPathPlanner given (OMPL's:
// head_path_planner.h), the
// follow-the-leader check of the whole chain, and the plan's duration and waypoints.
#include "sewerplan/fusion/manhole_turn_planner.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <optional>
#include <sstream>

#include "sewerplan/core/message_text.h"

#include "plan_numbers.h"

namespace sewerplan::fusion {
namespace {

using detail::kDegToRad;
using detail::rounded;

// Steps up to this height the wheels drive over without lifting a segment.
constexpr double kDriveOverStep_m = 0.05;
// Chain check: the head advances this far between two checks; a joint may exceed its yaw limit by
// this much (the curvature bound holds for the path, the chords only approximately).
constexpr double kChainStep_m = 0.02;
constexpr double kYawTolerance_deg = 0.5;
constexpr double kWaypointSpacing_m = 0.1;
constexpr double kPipeReach_m = 0.5;

std::string metres(double v) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << v << " m";
  return out.str();
}

double wrapped(double a) { return std::remainder(a, 2 * std::numbers::pi); }

// A polyline of head poses with its cumulative arc length.
struct Polyline {
  std::vector<HeadPose> poses;
  std::vector<double> arc;

  void add_line_to(double x, double y, double heading) {
    if (poses.empty()) {
      poses.push_back({x, y, heading});
      arc.push_back(0);
      return;
    }
    const HeadPose a = poses.back();
    const double d = std::hypot(x - a.x_m, y - a.y_m);
    const auto n = static_cast<std::size_t>(std::ceil(d / 0.01));
    for (std::size_t i = 1; i <= n; ++i) {
      const double t = static_cast<double>(i) / static_cast<double>(n);
      add({a.x_m + t * (x - a.x_m), a.y_m + t * (y - a.y_m), heading});
    }
  }
  void add(const HeadPose& p) {
    const HeadPose& a = poses.back();
    arc.push_back(arc.back() + std::hypot(p.x_m - a.x_m, p.y_m - a.y_m));
    poses.push_back(p);
  }
  double length() const { return arc.back(); }
  // The point at arc length s (clamped).
  std::pair<double, double> at(double s) const {
    if (s <= 0) return {poses.front().x_m, poses.front().y_m};
    if (s >= arc.back()) return {poses.back().x_m, poses.back().y_m};
    const auto it = std::upper_bound(arc.begin(), arc.end(), s);
    const std::size_t j = static_cast<std::size_t>(it - arc.begin());
    const double t = (s - arc[j - 1]) / std::max(arc[j] - arc[j - 1], 1e-12);
    return {poses[j - 1].x_m + t * (poses[j].x_m - poses[j - 1].x_m),
            poses[j - 1].y_m + t * (poses[j].y_m - poses[j - 1].y_m)};
  }
  double heading_at(double s) const {
    const auto it = std::upper_bound(arc.begin(), arc.end(), s);
    const std::size_t j = std::min(static_cast<std::size_t>(it - arc.begin()), poses.size()) - 1;
    return poses[j].heading_rad;
  }
};

// Moves the chain along the path with the head from arc `from_s` to the end; the first problem
// found, or empty. `stop` is asked at every head position; when it fires the answer is a problem
// ("stopped"), and the caller asks `stop` again.
std::optional<std::string> chain_problem(const Polyline& path, const PassageGeometry& g,
                                         const RobotBody& body, double from_s,
                                         const StopCondition& stop) {
  const double seg = body.segment_length_m;
  for (double head = from_s; head <= path.length() + 1e-9; head += kChainStep_m) {
    if (stop.interrupted()) return "stopped";
    std::vector<std::pair<double, double>> joints{path.at(head)};
    double s = head;
    for (int k = 0; k < body.segment_count; ++k) {
      // The joint one segment length (as a chord) behind the previous one.
      const auto [px, py] = joints.back();
      double lo = s - 2 * seg;
      double hi = s;
      for (int it = 0; it < 40; ++it) {
        const double mid = (lo + hi) / 2;
        const auto [mx, my] = path.at(mid);
        if (std::hypot(mx - px, my - py) > seg) {
          lo = mid;
        } else {
          hi = mid;
        }
      }
      s = hi;
      joints.push_back(path.at(s));
    }
    for (std::size_t k = 0; k + 1 < joints.size(); ++k) {
      for (int i = 0; i <= 4; ++i) {
        const double t = i / 4.0;
        const double x = joints[k].first + t * (joints[k + 1].first - joints[k].first);
        const double y = joints[k].second + t * (joints[k + 1].second - joints[k].second);
        if (!in_free_space(g, x, y, body.width_m / 2)) {
          return "segment " + std::to_string(k + 1) + " would touch the wall at (" + metres(x) +
                 ", " + metres(y) + ")";
        }
      }
      if (k + 2 < joints.size()) {
        const double a1 = std::atan2(joints[k].second - joints[k + 1].second,
                                     joints[k].first - joints[k + 1].first);
        const double a2 = std::atan2(joints[k + 1].second - joints[k + 2].second,
                                     joints[k + 1].first - joints[k + 2].first);
        const double bend = std::abs(wrapped(a1 - a2)) / kDegToRad;
        if (bend > body.yaw_max_deg + kYawTolerance_deg) {
          std::ostringstream out;
          out << "joint " << k + 1 << " would bend " << std::fixed << std::setprecision(1) << bend
              << " deg, more than " << body.yaw_max_deg;
          return out.str();
        }
      }
    }
  }
  return std::nullopt;
}

// The arc length where the path first comes within radius r of the axis (the from-mouth).
double first_arc_inside(const Polyline& path, double r) {
  for (std::size_t i = 0; i < path.poses.size(); ++i) {
    if (std::hypot(path.poses[i].x_m, path.poses[i].y_m) <= r + 1e-9) return path.arc[i];
  }
  return path.length();
}

// The arc length where the path last leaves radius r of the axis (the to-mouth).
double last_arc_inside(const Polyline& path, double r) {
  for (std::size_t i = path.poses.size(); i-- > 0;) {
    if (std::hypot(path.poses[i].x_m, path.poses[i].y_m) <= r + 1e-9) return path.arc[i];
  }
  return 0;
}

// A feasible plan's length, turning and waypoints (from the from-mouth at arc mouth_s to the end):
// z above the floor (the lower invert), down over the first run below the from-mouth, up over the
// last run before the to-mouth (at arc to_mouth_s), at the mouth itself for a step driven over.
TurnPlan described(const Polyline& path, double mouth_s, double to_mouth_s,
                   const PassageGeometry& g, double run_from, double run_to) {
  TurnPlan plan;
  plan.feasible = true;
  plan.path_length_m = path.length() - mouth_s;
  // All the turning, also where the head moves sideways in the from-pipe before the mouth.
  for (std::size_t i = 1; i < path.poses.size(); ++i) {
    plan.heading_change_deg +=
        std::abs(wrapped(path.poses[i].heading_rad - path.poses[i - 1].heading_rad)) / kDegToRad;
  }
  const double h = std::abs(g.step_m);
  auto share = [](double s, double from, double run) {
    return run > 0 ? std::clamp((s - from) / run, 0.0, 1.0) : (s > from ? 1.0 : 0.0);
  };
  auto z_at = [&](double s) {
    if (g.step_m < 0) return h * (1 - share(s, mouth_s, run_from));
    if (g.step_m > 0) return h * share(s, to_mouth_s - run_to, run_to);
    return 0.0;
  };
  for (double s = mouth_s;; s += kWaypointSpacing_m) {
    const bool last = s >= path.length() - 1e-9;
    if (last) s = path.length();
    const auto [x, y] = path.at(s);
    plan.waypoints.push_back(Waypoint{rounded(x, 1e4), rounded(y, 1e4), rounded(z_at(s), 1e4),
                                      rounded(path.heading_at(s) / kDegToRad, 1e2)});
    if (last) break;
  }
  return plan;
}

TurnPlan infeasible(std::string reason, std::uint32_t iterations = 0) {
  TurnPlan p;
  p.reason = std::move(reason);
  p.iterations = iterations;
  return p;
}

// Positive diameters, a finite turn and step.
Result<void> check_numbers(const PassageGeometry& g) {
  for (double v : {g.manhole_diameter_m, g.from_diameter_m, g.to_diameter_m}) {
    if (!(std::isfinite(v) && v > 0)) {
      return Error{ErrorCode::kInvalidArgument, "passage geometry: diameters must be positive"};
    }
  }
  if (!std::isfinite(g.step_m) || !std::isfinite(g.turn_deg)) {
    return Error{ErrorCode::kInvalidArgument, "passage geometry: turn and step must be finite"};
  }
  return {};
}

// The whole path of the head: the body's length behind it in the from-pipe, the straight run
// before a step, the planned part (`head`, which begins at `start`), the run after a step, and
// the body's length into the to-pipe at azimuth `alpha`.
Polyline whole_path(const HeadPose& start, const std::vector<HeadPose>& head, double r,
                    double run_from, double run_to, double alpha, double body_length) {
  const double cx = std::cos(alpha);
  const double cy = std::sin(alpha);
  Polyline path;
  path.add_line_to(std::min(start.x_m, -r) - body_length, 0, 0);
  if (run_from > 0) path.add_line_to(-r, 0, 0);
  path.add_line_to(start.x_m, start.y_m, 0);
  for (std::size_t i = 1; i < head.size(); ++i) path.add(head[i]);
  if (run_to > 0) path.add_line_to(r * cx, r * cy, alpha);
  path.add_line_to((r + body_length) * cx, (r + body_length) * cy, alpha);
  return path;
}

// Planning with no HeadPathPlanner given.
Error no_head_path_planner() {
  return Error{ErrorCode::kUnsupportedFormat,
               "a manhole motion needs the OMPL motion planner (a HeadPathPlanner), but none was "
               "given; the angle and step rules apply"};
}

}  // namespace

ManholeTurnPlanner::ManholeTurnPlanner(const HeadPathPlanner* head_paths, RobotBody body,
                                       const RobotProfile& profile, TurnPlannerOptions options)
    : head_paths_(head_paths),
      body_(body),
      speed_mps_(profile.manoeuvre_speed_mps),
      turn_s_per_deg_(profile.turn_s_per_deg),
      step_s_per_m_(profile.step_s_per_m),
      options_(options) {}

Result<void> ManholeTurnPlanner::check_state_space(const PassageGeometry& geometry) const {
  if (head_paths_ == nullptr) return no_head_path_planner();
  return head_paths_->check_space({.geometry = quantised(geometry),
                                   .turn_radius_m = body_.min_turn_radius_m(),
                                   .clearance_m = body_.width_m / 2 + body_.bend_margin_m()},
                                  options_);
}

Result<TurnPlan> ManholeTurnPlanner::plan(const PassageGeometry& geometry,
                                          const StopCondition& stop) const {
  const PassageGeometry g = quantised(geometry);
  if (Result<void> ok = check_numbers(g); !ok.has_value()) return ok.error();
  if (head_paths_ == nullptr) return no_head_path_planner();
  const double w = body_.width_m;
  if (g.from_diameter_m < w || g.to_diameter_m < w) {
    const LimitText t = limit_text_fixed(std::min(g.from_diameter_m, g.to_diameter_m), w);
    return infeasible("the " + std::string(g.from_diameter_m < w ? "from" : "to") + "-pipe (" +
                      t.value + " m) is narrower than the body (" + t.limit + " m)");
  }
  const double h = std::abs(g.step_m);
  if (h > body_.max_climb_m() + 1e-9) {
    std::ostringstream out;
    const LimitText t = limit_text_fixed(h, body_.max_climb_m());
    out << "the step of " << t.value << " m exceeds the " << t.limit << " m"
        << " that two lifted segments reach (joint pitch <= " << body_.pitch_max_deg << " deg)";
    return infeasible(out.str());
  }
  // The straight run before the higher mouth: the horizontal reach of the lifted segment, raised
  // as steeply as its joint allows (then the head clears any step up to max_climb_m()).
  const double run = h > kDriveOverStep_m
                         ? body_.segment_length_m * std::cos(body_.pitch_max_deg * kDegToRad)
                         : 0.0;
  const double run_from = g.step_m < 0 ? run : 0.0;
  const double run_to = g.step_m > 0 ? run : 0.0;
  const double r = g.manhole_diameter_m / 2;
  const double alpha = g.turn_deg * kDegToRad;
  const double cx = std::cos(alpha);
  const double cy = std::sin(alpha);
  // Where no step is climbed, the planned part begins (ends) kPipeReach_m inside the pipe, so the
  // head may move sideways in the pipe before the mouth (after it).
  const double start_x = run_from > 0 ? -r + run_from : -r - kPipeReach_m;
  const double goal_d = run_to > 0 ? r - run_to : r + kPipeReach_m;
  const HeadPose start{start_x, 0, 0};
  const HeadPose goal{goal_d * cx, goal_d * cy, alpha};
  // Room to bend in the manhole; in a pipe the head mostly runs straight, and the chain check
  // below verifies the body wherever it does bend.
  const double clearance = w / 2 + body_.bend_margin_m();
  const double pipe_clearance = w / 2;

  // The body must fit where it cannot bend: the straight runs at both mouths.
  for (double t = 0; t <= 1.0; t += 0.05) {
    if (!in_free_space(g, -r + t * run_from, 0, clearance, pipe_clearance)) {
      const LimitText n = limit_text_fixed(g.from_diameter_m, 2 * clearance);
      return infeasible("no room to bend leaving the from-pipe (" + n.value +
                        " m): the body needs " + n.limit + " m");
    }
    const double d = r - run_to * t;
    if (!in_free_space(g, d * cx, d * cy, clearance, pipe_clearance)) {
      const LimitText n = limit_text_fixed(g.to_diameter_m, 2 * clearance);
      return infeasible("no room to bend entering the to-pipe (" + n.value +
                        " m): the body needs " + n.limit + " m");
    }
  }
  // First with the pipes' room relaxed; if the body then touches a wall, once more with the
  // manhole's room to bend everywhere (a stricter space: no need if the first found nothing).
  const double body_length = body_.length_m();
  Polyline path;
  double mouth_s = 0;
  std::uint32_t iterations = 0;
  std::optional<std::string> problem;
  for (double pipe_room : {pipe_clearance, clearance}) {
    if (auto stopped = stop.interrupted()) return stopped_error(*stopped, "the motion planner");
    Result<HeadPath> head = head_paths_->plan({.geometry = g,
                                               .start = start,
                                               .goal = goal,
                                               .turn_radius_m = body_.min_turn_radius_m(),
                                               .clearance_m = clearance,
                                               .pipe_clearance_m = pipe_room,
                                               .pipe_reach_m = kPipeReach_m},
                                              options_, stop);
    if (!head.has_value()) return head.error();
    iterations += head->iterations;
    if (!head->found) {
      if (problem) break;  // keep the body check's reason
      std::ostringstream out;
      out << "no collision-free motion found in " << options_.max_iterations << " iterations (turn "
          << g.turn_deg << " deg in a " << metres(g.manhole_diameter_m)
          << " manhole, radius >= " << metres(body_.min_turn_radius_m()) << ")";
      return infeasible(out.str(), iterations);
    }
    path = whole_path(start, head->poses, r, run_from, run_to, alpha, body_length);
    // Where the manoeuvre begins: the head at the from-pipe's mouth.
    mouth_s = first_arc_inside(path, r);
    problem = chain_problem(path, g, body_, mouth_s, stop);
    if (auto stopped = stop.interrupted()) return stopped_error(*stopped, "the motion planner");
    if (!problem) break;
  }
  if (problem) {
    return infeasible("the planned path fails the body check: " + *problem, iterations);
  }

  TurnPlan plan = described(path, mouth_s, last_arc_inside(path, r), g, run_from, run_to);
  plan.iterations = iterations;
  plan.duration_s = rounded(plan.path_length_m / speed_mps_ +
                                plan.heading_change_deg * turn_s_per_deg_ + h * step_s_per_m_,
                            1e3);
  return plan;
}

}  // namespace sewerplan::fusion
