// SPDX-License-Identifier: MIT
// Route geometry: where on the map (x east, y north, metres in the map's CRS) the places of a
// network, a mission and a plan lie, for everything that draws them (render's pictures, gis's
// GeoJSON).
//
// Pipes are straight between their manholes, as in every sewerplan map. A blind end (a pipe with
// a manhole at one end only) lies along its slot's azimuth, the pipe's length away. A point on a
// pipe is `offset_m` from its ends[0] (clamped to the pipe; the middle of a pipe of no length).
// route_points follows a sequence of plan steps from the mission's start: a drive ends at its
// manhole, a task step at its task's place, and an inspection at the end of the pipe it finishes
// at (the far end from the manhole the robot stood in, unless the step names one).
//
//   std::vector<MapXY> line = route_points(map, mission, plan.steps);
//
// Thread safety: free functions over values they only read.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <vector>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/plan.h"

namespace sewerplan::domain {

// A point in the map's CRS: x east, y north.
struct MapXY {
  double x = 0;
  double y = 0;
  friend bool operator==(const MapXY&, const MapXY&) = default;
};

MapXY manhole_point(const SewerMap& map, ManholeId id);
// The two ends of a pipe's line; empty for a pipe with no manhole at all.
std::optional<std::array<MapXY, 2>> pipe_line(const SewerMap& map, PipeId id);
std::optional<MapXY> pipe_point(const SewerMap& map, PipeId id, double offset_m);
// A manhole, or a spot on a pipe (its offset, else its inspection point's, else the middle).
std::optional<MapXY> place_point(const SewerMap& map, const Place& place);
// The places a sequence of plan steps passes, from the mission's start (places that have no
// position, on a pipe with no manhole, are left out).
std::vector<MapXY> route_points(const SewerMap& map, const Mission& mission,
                                std::span<const PlanStep> steps);

}  // namespace sewerplan::domain
