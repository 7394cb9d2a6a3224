// SPDX-License-Identifier: MIT
// GeoJSON out: a sewer network and what happened on it, for QGIS over a street map, and the
// route graph Nav2's Route Server reads.
//
// to_geojson writes one RFC 7946 FeatureCollection in WGS84 longitude and latitude (through
// Wgs84Projection; no "crs" member, which RFC 7946 removed). Every feature has a "layer" property
// so that a GIS can style and filter them:
//   manhole          Point: name, type (slot count), diameter_m, z_m, depth_m, exit
//   pipe             LineString from the upstream to the downstream manhole (a blind end: along
//                    its slot's azimuth for its length): name, from, to, length_m, diameter_m,
//                    shape, height_m, blockage_risk; with a driveability report also driveable
//                    and why_not ("too narrow", "too wide", "unreachable", "cut off by a closure")
//   inspection_point Point on its pipe: name, pipe, offset_m
//   finding          Point on its pipe: code, characterisation, pipe, offset_m
//   start, task      Point: the mission's start and tasks (name, kind, final)
//   planned_route    LineString through the places a plan passes, from the mission's start
//   driven_route     LineString of the steps an event log says were driven
//   blocked          Point: where the robot found a pipe blocked
//   discrepancy      Point: where the sewer differs from its map (core/map_measurements.h): at the
//                    manhole, at the middle of the pipe (a length or size), or at the offset (a
//                    junction the map lacks): kind, description, value, map_value, sigma, pipe,
//                    manhole, slot
// Pipes are straight between their manholes, as in every sewerplan map. Coordinates keep 8
// decimals (about a millimetre).
//
// to_nav2_route_graph writes the graph file of Nav2's Route Server (nav2_route, its GeoJSON graph
// loader): each manhole a Point with a unique unsigned "id" and "frame", each pipe between two
// manholes two directed MultiLineString edges with "id", "startid", "endid", "cost" (the length,
// metres) and "metadata" (the pipe's name and diameter). Nav2 plans in its own frame, so these
// coordinates are the map's x and y in metres, less `origin` (Nav2 keeps them in float: give an
// origin near the network when its coordinates are large, as UTM's are).
//
//   Result<std::string> text = gis::to_geojson({.map = &map, .mission = &m, .plan = &plan}, wgs84);
//
// Thread safety: free functions over values they only read (the projection: one per thread).
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/map_measurements.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/driveability.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/gis/wgs84_projection.h"

namespace sewerplan::gis {

struct GeoJsonInput {
  const SewerMap* map = nullptr;       // required
  const Mission* mission = nullptr;    // its start and tasks; needed by plan and driven
  const domain::Plan* plan = nullptr;  // the planned route
  const std::vector<domain::PlanStep>* driven = nullptr;  // the route an event log drove
  std::span<const Blockage> blocked;                      // pipes an event log found blocked
  const domain::DriveabilityReport* driveability = nullptr;
  std::span<const FoundDiscrepancy> discrepancies;  // measured (merge-measurements, simulate)
};

// An error (kInvalidArgument) when a point lies outside what the projection transforms.
Result<std::string> to_geojson(const GeoJsonInput& input, const Wgs84Projection& wgs84);

std::string to_nav2_route_graph(const SewerMap& map, MapXY origin = {},
                                std::string_view frame = "map");

}  // namespace sewerplan::gis
