// SPDX-License-Identifier: MIT
// Where places lie on the map (route_geometry.h).
#include "sewerplan/domain/route_geometry.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>

#include "sewerplan/core/overloaded.h"

namespace sewerplan::domain {

MapXY manhole_point(const SewerMap& map, ManholeId id) {
  const Position& p = map.manhole(id).position;
  return {.x = p.x_m, .y = p.y_m};
}

std::optional<std::array<MapXY, 2>> pipe_line(const SewerMap& map, PipeId id) {
  const Pipe& pipe = map.pipe(id);
  std::array<std::optional<MapXY>, 2> ends;
  for (std::size_t e = 0; e < 2; ++e) {
    if (const auto& m = pipe.ends[e].manhole) ends[e] = manhole_point(map, *m);
  }
  for (std::size_t e = 0; e < 2; ++e) {
    const std::size_t other = 1 - e;
    if (ends[e] || !ends[other]) continue;
    const PipeEnd& at = pipe.ends[other];
    const double azimuth = map.slot(*at.manhole, at.slot).azimuth_deg * std::numbers::pi / 180;
    ends[e] = MapXY{.x = ends[other]->x + pipe.length_m * std::cos(azimuth),
                    .y = ends[other]->y + pipe.length_m * std::sin(azimuth)};
  }
  if (!ends[0] || !ends[1]) return std::nullopt;
  return std::array<MapXY, 2>{*ends[0], *ends[1]};
}

std::optional<MapXY> pipe_point(const SewerMap& map, PipeId id, double offset_m) {
  const auto line = pipe_line(map, id);
  if (!line) return std::nullopt;
  const double length = map.pipe(id).length_m;
  const double t = length > 0 ? std::clamp(offset_m / length, 0.0, 1.0) : 0.5;
  return MapXY{.x = (*line)[0].x + t * ((*line)[1].x - (*line)[0].x),
               .y = (*line)[0].y + t * ((*line)[1].y - (*line)[0].y)};
}

std::optional<MapXY> place_point(const SewerMap& map, const Place& place) {
  return std::visit(Overloaded{[&](ManholeId m) { return std::optional(manhole_point(map, m)); },
                               [&](const PipeSpot& s) {
                                 double offset = map.pipe(s.pipe).length_m / 2;
                                 if (s.offset_m) {
                                   offset = *s.offset_m;
                                 } else if (s.point) {
                                   offset = map.point(*s.point).offset_m;
                                 }
                                 return pipe_point(map, s.pipe, offset);
                               }},
                    place);
}

std::vector<MapXY> route_points(const SewerMap& map, const Mission& mission,
                                std::span<const PlanStep> steps) {
  std::vector<MapXY> points;
  const auto push = [&](std::optional<MapXY> p) {
    if (p) points.push_back(*p);
  };
  push(place_point(map, mission.start));
  // The manhole the robot is in, if it is in one: an inspection leaves by the pipe's other end.
  bool in_manhole = false;
  ManholeId at{0};
  if (const auto* m = std::get_if<ManholeId>(&mission.start)) {
    in_manhole = true;
    at = *m;
  }
  const auto task_point = [&](TaskId t) { return place_point(map, mission.task(t).place); };
  for (const PlanStep& step : steps) {
    std::visit(Overloaded{[&](const DrivePipeToManhole& s) {
                            push(manhole_point(map, s.manhole));
                            in_manhole = true;
                            at = s.manhole;
                          },
                          [&](const DriveManhole&) {},
                          [&](const EnterPipe& s) {
                            push(manhole_point(map, s.manhole));
                            in_manhole = false;
                          },
                          [&](const TakeWaterSample& s) {
                            push(task_point(s.task));
                            in_manhole = false;
                          },
                          [&](const GoToPoint& s) {
                            push(task_point(s.task));
                            in_manhole = false;
                          },
                          [&](const GoToManhole& s) {
                            push(manhole_point(map, s.manhole));
                            in_manhole = true;
                            at = s.manhole;
                          },
                          [&](const InspectPipe& s) {
                            const Pipe& pipe = map.pipe(s.pipe);
                            std::uint8_t end = 1;
                            if (s.finish_end) {
                              end = *s.finish_end;
                            } else if (in_manhole && pipe.ends[1].manhole == at) {
                              end = 0;
                            }
                            push(pipe_point(map, s.pipe, end == 0 ? 0 : pipe.length_m));
                            in_manhole = false;
                          }},
               step);
  }
  return points;
}

}  // namespace sewerplan::domain
