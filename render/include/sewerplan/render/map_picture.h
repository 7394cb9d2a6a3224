// SPDX-License-Identifier: MIT
// A map picture: a sewer network drawn to scale, with what happened on it, as SVG or PNG.
//
// Manholes at their positions (exits marked), pipes as straight lines between their manholes with
// a stroke width by diameter (pipes the mission's robot cannot drive in grey; with a driveability
// report, coloured by why not), the mission's start and tasks (inspections along their pipe,
// samples and points at their offset, manholes), the planned route, the route driven, blocked
// pipes and closed passages, hidden faults if given, a scale bar, a legend and a title. The
// output depends only on the inputs (fixed number formats), so it can be compared in tests and
// kept under version control.
//
// Level of detail: a network of more than kFullDetailPipes pipes is thinned, except around the
// mission (its start, tasks, routes and blocked pipes, with a quarter of that area again and at
// least 50 m around it): there a pipe shorter than a pixel is left out, pipes drawn over the same
// pixels are drawn once, a manhole is drawn only where no other already covers its cell (exits
// first), and what lies outside the picture is skipped. Every mission element (start, tasks,
// routes, the manholes and pipes they use, blocked pipes, closed passages, faults) is always
// drawn. Names are written only where they fit: over no other name and no other manhole.
//
//   RenderInput in{.map = &map, .mission = &mission, .plan = &plan, .trace = &trace};
//   std::ofstream("mission.svg") << render_map_svg(in);
//   Result<std::string> png = draw_map(in, canvas);  // any Canvas: cairo's for a PNG
//
// The `sewerplan` command draws a PNG on the PNG module's cairo canvas (sewerplan/modules/png.h:
// render_map_png), which only a PNG picture loads; render itself never loads or links cairo.
//
// Thread safety: pure functions of their input: call them from any number of threads.
#pragma once

#include <cstddef>
#include <string>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/driveability.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/render/canvas.h"
#include "sewerplan/render/event_trace.h"

namespace sewerplan::render {

// Networks up to this many pipes are drawn in full.
inline constexpr std::size_t kFullDetailPipes = 2000;

struct RenderInput {
  const SewerMap* map = nullptr;  // required
  const Mission* mission = nullptr;
  const domain::Plan* plan = nullptr;  // needs the mission
  const EventTrace* trace = nullptr;   // needs the mission
  const hal::FaultScenario* faults = nullptr;
  // What a robot can drive (domain::analyse_driveability): pipes coloured by why not, passages
  // over the robot's limits ringed. Without it, pipes outside the mission's profile are grey.
  const domain::DriveabilityReport* driveability = nullptr;
  std::string title;  // default: the map's (and mission's) name
  double width_px = 1000;
  // Show only the area of the mission (start, tasks, routes, pipes found blocked), with 10 m
  // around it at least; the rest of the network is cut off at the picture's edge.
  bool focus = false;
};

// Draws the picture on `canvas` (begun and finished here): its error when it cannot hold it.
Result<std::string> draw_map(const RenderInput& input, Canvas& canvas);

std::string render_map_svg(const RenderInput& input);

}  // namespace sewerplan::render
