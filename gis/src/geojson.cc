// SPDX-License-Identifier: MIT
#include "sewerplan/gis/geojson.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <variant>

#include <nlohmann/json.hpp>

#include "sewerplan/domain/route_geometry.h"

namespace sewerplan::gis {
namespace {

using Json = nlohmann::ordered_json;
using domain::manhole_point;
using domain::pipe_line;
using domain::pipe_point;
using domain::place_point;
using domain::route_points;

double rounded(double degrees) { return std::round(degrees * 1e8) / 1e8; }

class Writer {
 public:
  explicit Writer(const Wgs84Projection& wgs84) : wgs84_(wgs84) {}

  // [lon, lat]; records the first point the projection rejects.
  Json position(MapXY p) {
    Result<LonLat> ll = wgs84_.to_wgs84(p.x, p.y);
    if (!ll.has_value()) {
      if (!error_) error_ = ll.error();
      return Json::array({0.0, 0.0});
    }
    return Json::array({rounded(ll->lon_deg), rounded(ll->lat_deg)});
  }

  void point(MapXY p, Json properties) {
    add({{"type", "Point"}, {"coordinates", position(p)}}, std::move(properties));
  }

  void line(std::span<const MapXY> points, Json properties) {
    Json coordinates = Json::array();
    for (const MapXY& p : points) coordinates.push_back(position(p));
    add({{"type", "LineString"}, {"coordinates", std::move(coordinates)}}, std::move(properties));
  }

  void add(Json geometry, Json properties) {
    features_.push_back({{"type", "Feature"},
                         {"geometry", std::move(geometry)},
                         {"properties", std::move(properties)}});
  }

  // `crs`: the map's own, as the foreign member "sewerplan_crs" (RFC 7946 6.1), so that reading
  // the file back (gdal_import.h) projects it into the CRS it came from.
  Result<std::string> finish(const std::string& name, const Crs& crs) {
    if (error_) return *error_;
    Json doc = {{"type", "FeatureCollection"},
                {"name", name},
                {"sewerplan_crs", crs.to_string()},
                {"features", std::move(features_)}};
    return doc.dump(1, ' ', false, Json::error_handler_t::replace) + "\n";
  }

 private:
  const Wgs84Projection& wgs84_;
  Json features_ = Json::array();
  std::optional<Error> error_;
};

Json optional_number(const std::optional<double>& v) { return v ? Json(*v) : Json(); }

void network(const SewerMap& map, const domain::DriveabilityReport* driveability, Writer& w) {
  for (ManholeId id : map.manhole_ids()) {
    const Manhole& m = map.manhole(id);
    w.point(manhole_point(map, id),
            {{"layer", "manhole"},
             {"name", m.name},
             {"type", m.slot_count},
             {"diameter_m", m.diameter_m},
             {"shaft_l_m", m.shaft_length_m.value_or(m.diameter_m)},
             {"shaft_w_m", m.shaft_width_m.value_or(m.diameter_m)},
             {"variant", m.variant ? Json(std::string(1, *m.variant)) : Json()},
             {"z_m", m.position.z_m},
             {"depth_m", optional_number(m.depth_m)},
             {"exit", m.exit}});
  }
  for (PipeId id : map.pipe_ids()) {
    const Pipe& p = map.pipe(id);
    const auto end_name = [&](std::size_t e) {
      return p.ends[e].manhole ? Json(map.manhole(*p.ends[e].manhole).name) : Json();
    };
    // The slot at an end: its invert and azimuth (what the planner's steps and turns come from).
    const auto slot_value = [&](std::size_t e, double Slot::*member) {
      return p.ends[e].manhole ? Json(map.slot(*p.ends[e].manhole, p.ends[e].slot).*member)
                               : Json();
    };
    Json properties = {{"layer", "pipe"},
                       {"name", p.name},
                       {"from", end_name(0)},
                       {"to", end_name(1)},
                       {"from_lvl_m", slot_value(0, &Slot::invert_z_m)},
                       {"to_lvl_m", slot_value(1, &Slot::invert_z_m)},
                       {"from_az", slot_value(0, &Slot::azimuth_deg)},
                       {"to_az", slot_value(1, &Slot::azimuth_deg)},
                       {"from_slot", p.ends[0].manhole ? Json(p.ends[0].slot.value()) : Json()},
                       {"to_slot", p.ends[1].manhole ? Json(p.ends[1].slot.value()) : Json()},
                       {"length_m", p.length_m},
                       {"diameter_m", p.diameter_m},
                       {"shape", std::string(to_string(p.shape))},
                       {"height_m", p.height_m},
                       {"blockage_risk", p.blockage_risk ? Json(*p.blockage_risk) : Json()}};
    if (driveability != nullptr) {
      const std::string_view why = domain::why_not_driveable(id, *driveability);
      properties["driveable"] = why.empty();
      properties["why_not"] = why.empty() ? Json() : Json(std::string(why));
    }
    if (const auto line = pipe_line(map, id)) {
      w.line(*line, std::move(properties));
    } else {
      w.add(Json(), std::move(properties));  // RFC 7946 3.2: an unlocated feature
    }
  }
  for (PointId id : map.point_ids()) {
    const InspectionPoint& p = map.point(id);
    if (const auto at = pipe_point(map, p.pipe, p.offset_m)) {
      w.point(*at, {{"layer", "inspection_point"},
                    {"name", p.name},
                    {"pipe", map.pipe(p.pipe).name},
                    {"offset_m", p.offset_m}});
    }
  }
  for (const Finding& f : map.findings()) {
    if (const auto at = pipe_point(map, f.pipe, f.offset_m)) {
      w.point(*at, {{"layer", "finding"},
                    {"code", f.code},
                    {"characterisation", f.characterisation},
                    {"pipe", map.pipe(f.pipe).name},
                    {"offset_m", f.offset_m},
                    {"quantity1", optional_number(f.quantity1)},
                    {"quantity2", optional_number(f.quantity2)}});
    }
  }
}

void mission_features(const SewerMap& map, const Mission& mission, Writer& w) {
  if (const auto at = place_point(map, mission.start)) {
    w.point(*at, {{"layer", "start"}, {"name", mission.name}});
  }
  for (const Task& t : mission.tasks) {
    if (t.kind == TaskKind::kInspectPipe) {
      const PipeId pipe = std::get<PipeSpot>(t.place).pipe;
      if (const auto line = pipe_line(map, pipe)) {
        w.line(*line, {{"layer", "task"},
                       {"name", t.name},
                       {"kind", std::string(to_string(t.kind))},
                       {"final", t.final}});
      }
      continue;
    }
    if (const auto at = place_point(map, t.place)) {
      w.point(*at, {{"layer", "task"},
                    {"name", t.name},
                    {"kind", std::string(to_string(t.kind))},
                    {"final", t.final}});
    }
  }
}

void discrepancy_feature(const SewerMap& map, const Discrepancy& d, Writer& w) {
  std::optional<MapXY> at;
  if (d.manhole) {
    at = place_point(map, *d.manhole);
  } else if (d.pipe) {
    const double offset = d.kind == Discrepancy::Kind::kUnmappedJunction
                              ? d.offset_m
                              : map.pipe(*d.pipe).length_m / 2;
    at = pipe_point(map, *d.pipe, offset);
  }
  if (!at) return;
  w.point(*at, {{"layer", "discrepancy"},
                {"kind", std::string(to_string(d.kind))},
                {"description", describe(d, map)},
                {"value", d.value},
                {"map_value", d.map_value},
                {"sigma", d.sigma},
                {"pipe", d.pipe ? Json(map.pipe(*d.pipe).name) : Json()},
                {"manhole", d.manhole ? Json(map.manhole(*d.manhole).name) : Json()},
                {"slot", d.slot ? Json(to_paper_number(*d.slot)) : Json()},
                {"or_slot", d.or_slot ? Json(to_paper_number(*d.or_slot)) : Json()}});
}

}  // namespace

Result<std::string> to_geojson(const GeoJsonInput& in, const Wgs84Projection& wgs84) {
  SEWER_CHECK(in.map != nullptr, "to_geojson needs a map");
  const SewerMap& map = *in.map;
  Writer w(wgs84);
  network(map, in.driveability, w);
  if (in.mission != nullptr) {
    mission_features(map, *in.mission, w);
    if (in.plan != nullptr) {
      w.line(route_points(map, *in.mission, in.plan->steps),
             {{"layer", "planned_route"}, {"steps", in.plan->steps.size()}});
    }
    if (in.driven != nullptr) {
      w.line(route_points(map, *in.mission, *in.driven),
             {{"layer", "driven_route"}, {"steps", in.driven->size()}});
    }
  }
  for (const Blockage& b : in.blocked) {
    if (const auto at = pipe_point(map, b.pipe, b.offset_m)) {
      w.point(*at,
              {{"layer", "blocked"}, {"pipe", map.pipe(b.pipe).name}, {"offset_m", b.offset_m}});
    }
  }
  for (const FoundDiscrepancy& f : in.discrepancies) discrepancy_feature(map, f.discrepancy, w);
  return w.finish(map.name(), wgs84.crs());
}

std::string to_nav2_route_graph(const SewerMap& map, MapXY origin, std::string_view frame) {
  Json features = Json::array();
  const auto xy = [&](MapXY p) { return Json::array({p.x - origin.x, p.y - origin.y}); };
  for (ManholeId id : map.manhole_ids()) {
    features.push_back(
        {{"type", "Feature"},
         {"properties",
          {{"id", id.value()}, {"frame", frame}, {"metadata", {{"name", map.manhole(id).name}}}}},
         {"geometry", {{"type", "Point"}, {"coordinates", xy(manhole_point(map, id))}}}});
  }
  // Edge IDs follow the node IDs, so that every ID in the file is unique.
  std::size_t next_id = map.manhole_count();
  for (PipeId id : map.pipe_ids()) {
    const Pipe& p = map.pipe(id);
    if (!p.ends[0].manhole || !p.ends[1].manhole) continue;  // a blind end leads nowhere
    const std::array<ManholeId, 2> ends{*p.ends[0].manhole, *p.ends[1].manhole};
    for (std::size_t e = 0; e < 2; ++e) {
      const ManholeId start = ends[e];
      const ManholeId end = ends[1 - e];
      features.push_back(
          {{"type", "Feature"},
           {"properties",
            {{"id", next_id++},
             {"startid", start.value()},
             {"endid", end.value()},
             {"cost", p.length_m},
             {"metadata", {{"pipe", p.name}, {"diameter_m", p.diameter_m}}}}},
           {"geometry",
            {{"type", "MultiLineString"},
             {"coordinates", Json::array({Json::array({xy(manhole_point(map, start)),
                                                       xy(manhole_point(map, end))})})}}}});
    }
  }
  Json doc = {
      {"type", "FeatureCollection"}, {"name", map.name()}, {"features", std::move(features)}};
  return doc.dump(1, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace sewerplan::gis
