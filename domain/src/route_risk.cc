// SPDX-License-Identifier: MIT
#include "sewerplan/domain/route_risk.h"

#include <algorithm>
#include <optional>

#include "sewerplan/domain/validator.h"

namespace sewerplan::domain {
namespace {

// Where the robot is in `pipe` after a step, if it is in it or at one of its ends.
std::optional<double> offset_in(const RobotPosition& position, PipeId pipe, const SewerMap& map) {
  if (const auto* in = std::get_if<InPipe>(&position)) {
    if (in->pipe == pipe) return in->offset_m;
    return std::nullopt;
  }
  if (const auto* at = std::get_if<AtSlot>(&position)) {
    const Slot& slot = map.slot(at->manhole, at->slot);
    if (slot.pipe == pipe) return end_offset_m(map.pipe(pipe), slot.pipe_end);
  }
  return std::nullopt;
}

}  // namespace

RouteRisk route_risk(const Plan& plan, const SewerMap& map, const Mission& mission,
                     const MissionProgress& start) {
  RouteRisk risk;
  if (mission.hazards.empty() || start_problem(map, mission, start)) return risk;
  PlanReplay replay(map, mission, start);
  for (std::size_t i = 0; i < plan.steps.size(); ++i) {
    const RobotPosition before = replay.position();
    if (!replay.apply(plan.steps[i]).has_value()) break;
    const auto* in = std::get_if<InPipe>(&before);
    if (in == nullptr) continue;
    double a = in->offset_m;
    const std::optional<double> after = offset_in(replay.position(), in->pipe, map);
    if (!after) continue;
    double b = *after;
    // An inspection drives the whole pipe, from one end to the other.
    if (std::holds_alternative<InspectPipe>(plan.steps[i])) {
      a = -1;
      b = map.pipe(in->pipe).length_m + 1;
    }
    if (a > b) std::swap(a, b);
    std::vector<std::size_t> crossed;
    for (std::size_t h = 0; h < mission.hazards.size(); ++h) {
      const Hazard& hazard = mission.hazards[h];
      if (hazard.pipe == in->pipe && hazard.offset_m > a && hazard.offset_m < b)
        crossed.push_back(h);
    }
    // In the order of driving.
    const bool forward = in->offset_m <= *after;
    std::stable_sort(crossed.begin(), crossed.end(), [&](std::size_t x, std::size_t y) {
      return forward ? mission.hazards[x].offset_m < mission.hazards[y].offset_m
                     : mission.hazards[x].offset_m > mission.hazards[y].offset_m;
    });
    for (std::size_t h : crossed) {
      risk.passed.push_back({h, i});
      risk.unobstructed *= 1 - std::clamp(mission.hazards[h].probability, 0.0, 1.0);
    }
  }
  return risk;
}

}  // namespace sewerplan::domain
