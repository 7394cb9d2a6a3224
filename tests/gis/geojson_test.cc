// SPDX-License-Identifier: MIT
#include "sewerplan/gis/geojson.h"

#include <cmath>
#include <set>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "sewerplan/core/map_builder.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/map_isybau.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/domain/plan_text.h"

#include "support/isybau_georeferenced.h"
#include "support/paths.h"
#include "tm_reference.h"

namespace sewerplan::gis {
namespace {

using Json = nlohmann::json;

// The rules of RFC 7946 a reader relies on: a FeatureCollection of Features, each with a
// "geometry" (a Point, LineString or MultiLineString, or null) and a "properties" object; positions
// [longitude, latitude] within their ranges; at least two positions in a line; no "crs" member
// (section 4: WGS84 only). Returns what is wrong, or empty.
std::string rfc7946_problem(const Json& doc) {
  if (doc.value("type", "") != "FeatureCollection") return "not a FeatureCollection";
  if (doc.contains("crs")) return "a crs member";
  if (!doc.contains("features") || !doc["features"].is_array()) return "no features array";
  const auto position_problem = [](const Json& p) -> std::string {
    if (!p.is_array() || p.size() < 2 || !p[0].is_number() || !p[1].is_number()) {
      return "a position that is not [lon, lat]";
    }
    const double lon = p[0];
    const double lat = p[1];
    if (!(lon >= -180 && lon <= 180 && lat >= -90 && lat <= 90)) return "a position out of range";
    return "";
  };
  for (const Json& f : doc["features"]) {
    if (f.value("type", "") != "Feature") return "a member that is not a Feature";
    if (f.contains("crs")) return "a crs member in a feature";
    if (!f.contains("properties") || !(f["properties"].is_object())) return "no properties";
    if (!f.contains("geometry")) return "no geometry member";
    const Json& g = f["geometry"];
    if (g.is_null()) continue;
    const std::string type = g.value("type", "");
    const Json& c = g["coordinates"];
    if (type == "Point") {
      if (std::string p = position_problem(c); !p.empty()) return p;
    } else if (type == "LineString") {
      if (!c.is_array() || c.size() < 2) return "a LineString of fewer than two positions";
      for (const Json& p : c) {
        if (std::string problem = position_problem(p); !problem.empty()) return problem;
      }
    } else {
      return "an unexpected geometry " + type;
    }
  }
  return "";
}

std::vector<Json> layer(const Json& doc, const std::string& name) {
  std::vector<Json> found;
  for (const Json& f : doc["features"]) {
    if (f["properties"]["layer"] == name) found.push_back(f);
  }
  return found;
}

SewerMap georeferenced_street() {
  Diagnostics d;
  Result<SewerMap> map =
      read_map_isybau(sewerplan::testing::georeferenced_street("ETRS89_UTM32"), "street.xml", d);
  SEWER_CHECK(map.has_value(), "the georeferenced street reads");
  return std::move(*map);
}

TEST(GeoJson, TheNetworkIsValidRfc7946WithItsAttributes) {
  const SewerMap map = georeferenced_street();
  Result<Wgs84Projection> wgs84 = Wgs84Projection::create(*map.crs());
  ASSERT_TRUE(wgs84.has_value()) << wgs84.error();
  Result<std::string> text = to_geojson({.map = &map}, *wgs84);
  ASSERT_TRUE(text.has_value()) << text.error();
  const Json doc = Json::parse(*text);
  EXPECT_EQ(rfc7946_problem(doc), "");
  EXPECT_EQ(layer(doc, "manhole").size(), map.manhole_count());
  EXPECT_EQ(layer(doc, "pipe").size(), map.pipe_count());
  const Json pipe = layer(doc, "pipe").front();
  EXPECT_EQ(pipe["properties"]["name"], map.pipe(PipeId{0}).name);
  EXPECT_DOUBLE_EQ(pipe["properties"]["diameter_m"].get<double>(), map.pipe(PipeId{0}).diameter_m);
  EXPECT_EQ(pipe["geometry"]["type"], "LineString");
}

TEST(GeoJson, AKnownIsybauManholeLiesWhereAnIndependentProjectionPutsIt) {
  const SewerMap map = georeferenced_street();
  Result<Wgs84Projection> wgs84 = Wgs84Projection::create(*map.crs());
  ASSERT_TRUE(wgs84.has_value()) << wgs84.error();
  const Json doc = Json::parse(to_geojson({.map = &map}, *wgs84).value());
  for (const Json& m : layer(doc, "manhole")) {
    if (m["properties"]["name"] != "S1") continue;
    const double lon = m["geometry"]["coordinates"][0];
    const double lat = m["geometry"]["coordinates"][1];
    // Longitude first: Bielefeld is near 8.7 E, 52.0 N.
    EXPECT_NEAR(lon, 8.66, 0.05);
    EXPECT_NEAR(lat, 51.98, 0.05);
    const auto en = sewerplan::testing::transverse_mercator(sewerplan::testing::kUtm32, lon, lat);
    EXPECT_NEAR(en.east, sewerplan::testing::kStreetEasting, 0.01);
    EXPECT_NEAR(en.north, sewerplan::testing::kStreetNorthing, 0.01);
    return;
  }
  FAIL() << "no manhole S1";
}

struct Ais {
  SewerMap map;
  Mission mission;
  domain::Plan plan;
};

Ais ais_in_utm() {
  Diagnostics d;
  Result<SewerMap> map = read_map(sewerplan::testing::dataset_path("ais-testbed/map.json"), d);
  SEWER_CHECK(map.has_value(), "the AIS map reads");
  SewerMap utm = MapBuilder::with_crs(std::move(*map), Crs{.authority = "EPSG", .code = 25832});
  Result<Mission> mission =
      read_mission(sewerplan::testing::dataset_path("ais-testbed/missions/paper.json"), utm, d);
  SEWER_CHECK(mission.has_value(), "the paper's mission reads");
  const auto plan_path = sewerplan::testing::dataset_path("ais-testbed/plans/paper-corrected.plan");
  Result<domain::Plan> plan =
      domain::parse_plan(read_text_file(plan_path).value(), "paper.plan", utm, *mission, d);
  SEWER_CHECK(plan.has_value(), "the paper's plan reads");
  return {std::move(utm), std::move(*mission), std::move(*plan)};
}

TEST(GeoJson, APlansRouteStartsAtTheMissionsStartAndVisitsItsManholes) {
  const Ais ais = ais_in_utm();
  Result<Wgs84Projection> wgs84 = Wgs84Projection::create(*ais.map.crs());
  ASSERT_TRUE(wgs84.has_value());
  const Json doc = Json::parse(
      to_geojson({.map = &ais.map, .mission = &ais.mission, .plan = &ais.plan}, *wgs84).value());
  EXPECT_EQ(rfc7946_problem(doc), "");
  const std::vector<Json> routes = layer(doc, "planned_route");
  ASSERT_EQ(routes.size(), 1U);
  EXPECT_EQ(routes[0]["properties"]["steps"], ais.plan.steps.size());
  const Json start = layer(doc, "start").at(0)["geometry"]["coordinates"];
  EXPECT_EQ(routes[0]["geometry"]["coordinates"][0], start);
  const std::vector<MapXY> points = domain::route_points(ais.map, ais.mission, ais.plan.steps);
  EXPECT_EQ(routes[0]["geometry"]["coordinates"].size(), points.size());
  EXPECT_EQ(layer(doc, "task").size(), ais.mission.tasks.size());
}

TEST(GeoJson, DriveabilityMarksEveryPipe) {
  const Ais ais = ais_in_utm();
  Result<Wgs84Projection> wgs84 = Wgs84Projection::create(*ais.map.crs());
  ASSERT_TRUE(wgs84.has_value());
  domain::DriveabilityReport report;
  report.too_narrow = {PipeId{0}};
  for (PipeId p : ais.map.pipe_ids()) {
    if (p != PipeId{0}) report.reachable_pipes.push_back(p);
  }
  const Json doc =
      Json::parse(to_geojson({.map = &ais.map, .driveability = &report}, *wgs84).value());
  for (const Json& pipe : layer(doc, "pipe")) {
    const bool first = pipe["properties"]["name"] == ais.map.pipe(PipeId{0}).name;
    EXPECT_EQ(pipe["properties"]["driveable"], !first);
    EXPECT_EQ(pipe["properties"]["why_not"], first ? Json("too narrow") : Json());
  }
}

TEST(GeoJson, DiscrepanciesAreALayerWhereTheyAre) {
  const Ais ais = ais_in_utm();
  Result<Wgs84Projection> wgs84 = Wgs84Projection::create(*ais.map.crs());
  ASSERT_TRUE(wgs84.has_value());
  const PipeId p{0};
  const ManholeId m = *ais.map.pipe(p).ends[1].manhole;
  const std::vector<FoundDiscrepancy> found = {
      {{.kind = Discrepancy::Kind::kLengthOff, .pipe = p, .map_value = 5, .value = 6, .sigma = 0.2},
       {0}},
      {{.kind = Discrepancy::Kind::kUnmappedLateral, .manhole = m, .value = 45, .sigma = 5}, {0}},
      {{.kind = Discrepancy::Kind::kUnmappedJunction, .pipe = p, .offset_m = 0, .value = 3}, {0}}};
  const Json doc =
      Json::parse(to_geojson({.map = &ais.map, .discrepancies = found}, *wgs84).value());
  EXPECT_EQ(rfc7946_problem(doc), "");
  const std::vector<Json> shown = layer(doc, "discrepancy");
  ASSERT_EQ(shown.size(), 3U);
  EXPECT_EQ(shown[0]["properties"]["kind"], "length-off");
  EXPECT_EQ(shown[0]["properties"]["pipe"], ais.map.pipe(p).name);
  EXPECT_EQ(shown[0]["properties"]["description"], describe(found[0].discrepancy, ais.map));
  EXPECT_DOUBLE_EQ(shown[0]["properties"]["sigma"].get<double>(), 0.2);
  // The lateral at its manhole, the junction at its offset (0: the pipe's first manhole).
  const auto manhole_at = [&](ManholeId id) {
    for (const Json& f : layer(doc, "manhole")) {
      if (f["properties"]["name"] == ais.map.manhole(id).name) return f["geometry"]["coordinates"];
    }
    return Json();
  };
  EXPECT_EQ(shown[1]["geometry"]["coordinates"], manhole_at(m));
  EXPECT_EQ(shown[2]["geometry"]["coordinates"], manhole_at(*ais.map.pipe(p).ends[0].manhole));
}

TEST(Nav2RouteGraph, NodesAndTwoDirectedEdgesPerPipeWithUniqueIds) {
  const Ais ais = ais_in_utm();
  const Json doc = Json::parse(to_nav2_route_graph(ais.map, {.x = 1, .y = 2}));
  std::set<unsigned> ids;
  std::set<unsigned> nodes;
  std::size_t edges = 0;
  for (const Json& f : doc["features"]) {
    const unsigned id = f["properties"]["id"];
    EXPECT_TRUE(ids.insert(id).second) << "id " << id << " twice";
    if (f["geometry"]["type"] == "Point") {
      nodes.insert(id);
      EXPECT_EQ(f["properties"]["frame"], "map");
      const Position& p = ais.map.manhole(ManholeId{id}).position;
      EXPECT_DOUBLE_EQ(f["geometry"]["coordinates"][0].get<double>(), p.x_m - 1);
      EXPECT_DOUBLE_EQ(f["geometry"]["coordinates"][1].get<double>(), p.y_m - 2);
    }
  }
  for (const Json& f : doc["features"]) {
    if (f["geometry"]["type"] != "MultiLineString") continue;
    ++edges;
    EXPECT_TRUE(nodes.contains(f["properties"]["startid"].get<unsigned>()));
    EXPECT_TRUE(nodes.contains(f["properties"]["endid"].get<unsigned>()));
    EXPECT_GT(f["properties"]["cost"].get<double>(), 0);
  }
  std::size_t between_manholes = 0;
  for (const Pipe& p : ais.map.pipes()) {
    if (p.ends[0].manhole && p.ends[1].manhole) ++between_manholes;
  }
  EXPECT_EQ(nodes.size(), ais.map.manhole_count());
  EXPECT_EQ(edges, 2 * between_manholes);
}

}  // namespace
}  // namespace sewerplan::gis
