// SPDX-License-Identifier: MIT
// render_map_svg: a sewer network drawn to scale as SVG, with what happened on it.
//
// Manholes at their positions (exits marked), pipes as straight lines between their manholes with
// a stroke width by diameter (pipes the mission's robot cannot drive in grey), the mission's start
// and tasks (inspections along their pipe, samples and points at their offset, manholes), the
// planned route, the route driven, blocked pipes and closed passages, hidden faults if given, a
// scale bar, a legend and a title. The output depends only on the inputs (fixed number formats),
// so it can be compared in tests and kept under version control.
//
//   RenderInput in{.map = &map, .mission = &mission, .plan = &plan, .trace = &trace};
//   std::ofstream("mission.svg") << render_map_svg(in);
//
// Thread safety: render_map_svg is a pure function of its input: call it from any number of
// threads.
#pragma once

#include <string>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/render/event_trace.h"

namespace sewerplan::render {

struct RenderInput {
  const SewerMap* map = nullptr;  // required
  const Mission* mission = nullptr;
  const domain::Plan* plan = nullptr;  // needs the mission
  const EventTrace* trace = nullptr;   // needs the mission
  const hal::FaultScenario* faults = nullptr;
  std::string title;  // default: the map's (and mission's) name
  double width_px = 1000;
  // Show only the area of the mission (start, tasks, routes, pipes found blocked), with 10 m
  // around it at least; the rest of the network is cut off at the picture's edge.
  bool focus = false;
};

std::string render_map_svg(const RenderInput& input);

}  // namespace sewerplan::render
