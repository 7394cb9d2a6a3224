// SPDX-License-Identifier: MIT
// NetworkImport: what the importers of foreign sewer databases (SWMM, ISYBAU) share. Private to
// core/src.
//
// Foreign formats describe a sewer as nodes with a position and links between two named nodes,
// each link end with its own invert and, optionally, a polyline of intermediate vertices. sewerplan
// needs slots: for each manhole, one per pipe end, with the azimuth at which the pipe leaves the
// manhole. An importer fills ImportNode and ImportLink records and calls assemble_network(), which
// computes each slot's azimuth from the direction of the pipe's first segment leaving the node
// (through the vertices, skipping points inside the manhole's shaft, within its radius of the
// node's position: a line ending at the floor point, centimetres off the cover point, gives no
// direction; counted in a warning) and hands everything to MapBuilder, so the result is
// validated like any other map.
//
// A slot whose direction cannot be known (the node or the far end has no position) gets a fallback
// azimuth: the manhole's such slots are spread evenly around it (0, 360/k, ...). Each one is
// counted and reported in one warning.
//
//   NetworkImport net;
//   net.nodes.push_back({.name = "J1", .position = {0, 0, 10}, .diameter_m = 1.0, .line = 12});
//   net.links.push_back({.name = "C1", .from = "J1", .to = "J2", ...});
//   Result<SewerMap> map = assemble_network(std::move(net), "net", line_locator(file), file, d);
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/map_builder.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::detail {

struct ImportNode {
  std::string name;
  Position position;      // z: the node's invert
  bool has_xy = false;    // the file gave x and y
  double diameter_m = 0;  // > 0
  bool exit = false;
  std::optional<double> shaft_length_m;  // a rectangular shaft
  std::optional<double> shaft_width_m;
  std::optional<double> depth_m;
  std::optional<char> variant;  // the paper's TYPE_B: 'A'..'Z'
  std::uint32_t line = 0;       // for the Locator
};

struct ImportLink {
  std::string name;
  std::optional<std::string> from;  // upstream node; none: a blind end
  std::optional<std::string> to;    // downstream node
  double length_m = 0;
  double diameter_m = 0;  // clear size: the smaller of width and height
  double height_m = 0;
  PipeShape shape = PipeShape::kCircular;
  double from_invert_z_m = 0;  // absolute invert of the pipe end at `from`
  double to_invert_z_m = 0;
  std::vector<std::array<double, 2>> vertices;  // intermediate points, from `from` to `to`
  // The vertices begin and end where the pipe meets its nodes (ISYBAU lines), which may be a floor
  // point a few centimetres off the node's position; else they are only the points between.
  bool vertices_include_ends = false;
  // Where the pipe proper begins at each end (ISYBAU 2017: the Rohranfangspunkte, RAP, at the shaft
  // wall), when the line marks it: the slot's direction is the pipe's axis from there, not the
  // channel in the manhole's floor that leads to it. The vertices then begin and end there.
  std::array<bool, 2> starts_at_mouth{false, false};
  // The slot's azimuth at each end when the source gives it (a GIS layer that carries the
  // map's own slot directions, as export-geojson writes them): it wins over the line's direction.
  std::array<std::optional<double>, 2> azimuth_deg;
  // The slot's number in its manhole at each end (0 first), when the source gives it (a GIS layer
  // from export-geojson): a manhole whose every slot has one, each once, keeps that order (the
  // planner's slot numbers); else its slots are in the order of the links.
  std::array<std::optional<double>, 2> slot_index;
  std::optional<float> blockage_risk;
  std::uint32_t line = 0;
};

struct NetworkImport {
  std::vector<ImportNode> nodes;
  std::vector<ImportLink> links;
  std::vector<FindingRecord> findings;  // inspection findings, by pipe name
  std::vector<PointRecord> points;      // inspection points, by pipe name
  std::optional<Crs> crs;               // the coordinate reference system, if the file names one
};

// The direction, in degrees counter-clockwise from +x in (-180, 180], from (x0, y0) to (x1, y1).
double azimuth_deg(double x0, double y0, double x1, double y1);

// Reports a fallback applied `count` times as one warning at `where`: "<count> <what>"; nothing if
// `count` is 0.
void warn_counted(Diagnostics& diagnostics, const std::string& where, std::size_t count,
                  const std::string& what);

// "1 m", "0.8 m": a length in a message, in its shortest form.
std::string metres_text(double metres);

// Builds the map: one manhole per node, one pipe per link, slots in link order. `where` names the
// file for the warning about fallback azimuths.
Result<SewerMap> assemble_network(NetworkImport network, std::string map_name, Locator locator,
                                  const std::string& where, Diagnostics& diagnostics);

}  // namespace sewerplan::detail
