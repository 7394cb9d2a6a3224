// SPDX-License-Identifier: MIT
#include "sewerplan/domain/plan_json.h"

#include <type_traits>

#include <nlohmann/json.hpp>

#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/route_risk.h"

#include "object_names.h"

namespace sewerplan::domain {
namespace {

using json = nlohmann::ordered_json;
using detail::name_of;

void add_task(json& j, const Mission& mission, TaskId task) { j["task"] = name_of(mission, task); }

// The step's objects by name.
void add_objects(json& j, const PlanStep& step, const SewerMap& map, const Mission& mission) {
  std::visit(
      [&](const auto& s) {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, DriveManhole>) {
          j["manhole"] = name_of(map, s.manhole);
          j["from_slot"] = to_paper_number(s.from);
          j["to_slot"] = to_paper_number(s.to);
          if (detail::in_map(map, s.manhole)) {
            const Manhole& m = map.manhole(s.manhole);
            if (s.from.value() < m.slot_count) {
              j["from_pipe"] = map.pipe(map.slot(s.manhole, s.from).pipe).name;
            }
            if (s.to.value() < m.slot_count) {
              j["to_pipe"] = map.pipe(map.slot(s.manhole, s.to).pipe).name;
            }
          }
        } else if constexpr (std::is_same_v<T, GoToManhole>) {
          j["manhole"] = name_of(map, s.manhole);
          add_task(j, mission, s.task);
        } else {
          j["pipe"] = name_of(map, s.pipe);
          if constexpr (std::is_same_v<T, DrivePipeToManhole> || std::is_same_v<T, EnterPipe>) {
            j["manhole"] = name_of(map, s.manhole);
          } else {
            add_task(j, mission, s.task);
          }
          if constexpr (std::is_same_v<T, InspectPipe>) {
            if (s.finish_end && *s.finish_end <= 1 && detail::in_map(map, s.pipe)) {
              const PipeEnd& end = map.pipe(s.pipe).ends[*s.finish_end];
              j["finish_manhole"] = end.manhole ? json(map.manhole(*end.manhole).name) : json();
            }
          }
        }
      },
      step);
}

}  // namespace

void write_plan_json(const Plan& plan, const ValidationReport& report, const SewerMap& map,
                     const Mission& mission, std::ostream& out) {
  json j;
  j["format"] = kPlanJsonFormat;
  j["version"] = kPlanJsonVersion;
  j["valid"] = report.valid;
  if (!report.valid) j["error"] = report.error;
  if (report.failed_step) j["failed_step"] = *report.failed_step + 1;
  j["cost_s"] = report.total_cost_s;
  j["energy_wh"] = report.energy_wh;
  j["steps"] = json::array();
  for (std::size_t i = 0; i < plan.steps.size(); ++i) {
    const PlanStep& step = plan.steps[i];
    json s = {{"action", format_step(step, map, mission)}, {"kind", step_kind(step)}};
    add_objects(s, step, map, mission);
    if (i < report.step_costs_s.size()) s["cost_s"] = report.step_costs_s[i];
    j["steps"].push_back(std::move(s));
  }
  if (!mission.hazards.empty()) {
    // Risk-aware planning (route_risk.h): the possible blockages along the route.
    const RouteRisk risk = route_risk(plan, map, mission, initial_progress(mission, map));
    json passed = json::array();
    for (const HazardPassed& h : risk.passed) {
      const Hazard& hazard = mission.hazards[h.hazard];
      passed.push_back({{"pipe", name_of(map, hazard.pipe)},
                        {"offset_m", hazard.offset_m},
                        {"probability", hazard.probability},
                        {"reason", hazard.reason},
                        {"step", h.step + 1}});
    }
    j["risk"] = {{"unobstructed_probability", risk.unobstructed}, {"hazards", std::move(passed)}};
  }
  out << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
}

}  // namespace sewerplan::domain
