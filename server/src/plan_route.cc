// SPDX-License-Identifier: MIT
#include "plan_route.h"

#include <optional>
#include <type_traits>
#include <variant>

#include "sewerplan/domain/plan_text.h"

namespace sewerplan::server {

Json plan_route_json(const domain::Plan& plan, const SewerMap& map, const Mission& mission) {
  Json steps = Json::array();
  Json pipes = Json::array();
  for (const domain::PlanStep& step : plan.steps) {
    steps.push_back(domain::format_step(step, map, mission));
    std::visit(
        [&](const auto& s) {
          std::optional<PipeId> pipe;
          if constexpr (requires { s.pipe; }) pipe = s.pipe;
          // A passage enters the pipe of its `to` slot (the end "in P9" is reached so).
          if constexpr (std::is_same_v<std::decay_t<decltype(s)>, domain::DriveManhole>) {
            pipe = map.slot(s.manhole, s.to).pipe;
          }
          if (!pipe) return;
          const std::string& name = map.pipe(*pipe).name;
          if (pipes.empty() || pipes.back() != name) pipes.push_back(name);
        },
        step);
  }
  return {{"steps", std::move(steps)}, {"pipes", std::move(pipes)}};
}

}  // namespace sewerplan::server
