// SPDX-License-Identifier: MIT
// The operator station's HTTP API (docs/operator-station.md), through httplib's client against a
// server on an ephemeral port: every endpoint answers what the CLI's --json answers, and every bad
// request gets a 4xx JSON error naming what is wrong.
#include "sewerplan/server/station_server.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "sewerplan/core/limits.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/passage_motion.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/text_file.h"

#include "station_fixture.h"
#include "support/paths.h"
#include <httplib.h>

namespace sewerplan::server {
namespace {

using ::testing::HasSubstr;

class StationServerTest : public StationFixture {};

TEST_F(StationServerTest, ListsItsMapsByIdAndTheBuiltInProfiles) {
  auto [status, j] = get("/api/maps");
  EXPECT_EQ(status, 200);
  ASSERT_EQ(j["maps"].size(), 1u);
  EXPECT_EQ(j["maps"][0]["id"], "map");
  EXPECT_EQ(j["maps"][0]["manholes"], 12);
  EXPECT_TRUE(j["maps"][0]["crs"].is_null());  // the AIS test environment: local coordinates
  EXPECT_NE(std::find(j["profiles"].begin(), j["profiles"].end(), "makro-plus"),
            j["profiles"].end());
}

TEST_F(StationServerTest, GivesAMapsGeometryAsColumnsOfNamesAndCoordinates) {
  auto [status, j] = get("/api/maps/map");
  EXPECT_EQ(status, 200);
  const json& m = j["manholes"];
  EXPECT_EQ(m["name"].size(), m["x"].size());
  EXPECT_EQ(m["name"].size(), 12u);
  EXPECT_EQ(j["pipes"]["name"].size(), 14u);
  EXPECT_NE(std::find(j["pipes"]["name"].begin(), j["pipes"]["name"].end(), "P6"),
            j["pipes"]["name"].end());
  EXPECT_EQ(j["bounds"].size(), 4u);
}

// The page's compact geometry (GET /api/maps/ID/geometry, map_geometry.h, format 2), read as the
// page reads it: little-endian sections after a 56-byte header.
struct BinaryGeometry {
  std::uint32_t version = 0, manholes = 0, pipes = 0;
  std::vector<double> bounds, positions, lengths, diameters;
  std::vector<long long> from, to;  // -1: an open end, as the JSON
  std::vector<int> slots, exits;
  std::vector<std::string> names;  // manholes', then pipes'
};
BinaryGeometry decode_geometry(const std::string& body) {
  BinaryGeometry g;
  std::size_t at = 0;
  const auto bytes = [&](std::size_t n) {
    if (at + n > body.size())
      throw std::runtime_error("geometry: truncated at " + std::to_string(at));
    std::uint64_t v = 0;
    for (std::size_t k = 0; k < n; ++k) {
      v |= static_cast<std::uint64_t>(static_cast<unsigned char>(body[at + k])) << (8 * k);
    }
    at += n;
    return v;
  };
  const auto u32 = [&] { return static_cast<std::uint32_t>(bytes(4)); };
  const auto f64 = [&] { return std::bit_cast<double>(bytes(8)); };
  if (body.substr(0, 4) != "SPGM") throw std::runtime_error("geometry: no magic");
  at = 4;
  g.version = u32();
  g.manholes = u32();
  g.pipes = u32();
  for (int k = 0; k < 4; ++k) g.bounds.push_back(f64());
  const std::uint32_t name_bytes = u32();
  u32();
  for (std::uint32_t i = 0; i < 2 * g.manholes; ++i) g.positions.push_back(f64());
  for (std::uint32_t i = 0; i < g.pipes; ++i) g.lengths.push_back(f64());
  for (std::uint32_t i = 0; i < g.pipes; ++i) g.diameters.push_back(f64());
  for (auto* ends : {&g.from, &g.to}) {
    for (std::uint32_t i = 0; i < g.pipes; ++i) {
      const std::uint32_t m = u32();
      ends->push_back(m == 0xffffffff ? -1 : static_cast<long long>(m));
    }
  }
  std::vector<std::uint32_t> offsets;
  for (std::uint32_t i = 0; i <= g.manholes + g.pipes; ++i) offsets.push_back(u32());
  for (std::uint32_t i = 0; i < g.manholes; ++i) g.slots.push_back(static_cast<int>(bytes(2)));
  for (std::uint32_t i = 0; i < g.manholes; ++i) g.exits.push_back(static_cast<int>(bytes(1)));
  const std::size_t names_at = at;
  if (names_at + name_bytes != body.size()) throw std::runtime_error("geometry: wrong size");
  for (std::size_t i = 0; i + 1 < offsets.size(); ++i) {
    g.names.push_back(body.substr(names_at + offsets[i], offsets[i + 1] - offsets[i]));
  }
  return g;
}

// The binary geometry holds the JSON's values bit for bit: on the AIS map and on a SWMM map
// uploaded.
TEST_F(StationServerTest, GivesThePageTheSameGeometryAsTypedArrays) {
  auto [up, uploaded] =
      post("/api/maps?name=epa-example1.inp", read(kSource / "datasets/swmm/epa-example1.inp"));
  ASSERT_EQ(up, 201);
  for (const std::string& id : {std::string("map"), uploaded["id"].get<std::string>()}) {
    SCOPED_TRACE(id);
    auto [status, j] = get("/api/maps/" + id);
    ASSERT_EQ(status, 200);
    auto r = client_->Get(("/api/maps/" + id + "/geometry").c_str());
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200);
    EXPECT_EQ(r->get_header_value("Content-Type"), "application/octet-stream");
    const BinaryGeometry g = decode_geometry(r->body);
    EXPECT_EQ(g.version, 2u);
    const json& m = j["manholes"];
    const json& p = j["pipes"];
    ASSERT_EQ(g.manholes, m["name"].size());
    ASSERT_EQ(g.pipes, p["name"].size());
    EXPECT_EQ(g.bounds, j["bounds"].get<std::vector<double>>());
    for (std::size_t i = 0; i < g.manholes; ++i) {
      EXPECT_EQ(g.names[i], m["name"][i]);
      EXPECT_EQ(g.positions[2 * i], m["x"][i].get<double>());
      EXPECT_EQ(g.positions[2 * i + 1], m["y"][i].get<double>());
      EXPECT_EQ(g.slots[i], m["slots"][i]);
      EXPECT_EQ(g.exits[i], m["exit"][i]);
    }
    for (std::size_t i = 0; i < g.pipes; ++i) {
      EXPECT_EQ(g.names[g.manholes + i], p["name"][i]);
      EXPECT_EQ(g.from[i], p["from"][i]);
      EXPECT_EQ(g.to[i], p["to"][i]);
      EXPECT_EQ(g.lengths[i], p["length_m"][i].get<double>());
      EXPECT_EQ(g.diameters[i], p["diameter_m"][i].get<double>());
    }
  }
  auto [status, j] = get("/api/maps/nowhere/geometry");
  EXPECT_EQ(status, 404);
  EXPECT_EQ(j["error"]["message"], "no map 'nowhere'");
}

// A map of what the compact geometry must carry whole (written here, uploaded as JSON): names of
// 2- and 4-byte UTF-8 characters, a pipe with an open end, one with no manhole at either end,
// a manhole of as many slots as a map may give one (kMaxSlotsPerManhole, 100: more than a byte's
// worth of passages), coordinates in national grid metres with
// all of a double's digits, a length that is no short decimal.
std::string awkward_map() {
  json hub_slots = json::array();
  json manholes = json::array();
  json pipes = json::array();
  constexpr int kHub = static_cast<int>(sewerplan::kMaxSlotsPerManhole);
  for (int k = 0; k < kHub; ++k) {
    const std::string pipe = "Zweig-" + std::to_string(k);
    const double azimuth = 360.0 * k / kHub;
    hub_slots.push_back({{"pipe", pipe}, {"azimuth_deg", azimuth}, {"invert_m", 0}});
    manholes.push_back({{"name", "Blatt-" + std::to_string(k)},
                        {"x_m", 3512300.0 + k},
                        {"y_m", 5612300.0},
                        {"z_m", 0},
                        {"diameter_m", 1.0},
                        {"slots",
                         {{{"pipe", pipe},
                           {"azimuth_deg", azimuth < 180 ? azimuth + 180 : azimuth - 180},
                           {"invert_m", 0}}}}});
    pipes.push_back({{"name", pipe},
                     {"from", "Zentrum-\xF0\x9D\x84\x9E"},  // U+1D11E, four bytes
                     {"to", "Blatt-" + std::to_string(k)},
                     {"length_m", 10.0 + k},
                     {"diameter_m", 0.3}});
  }
  manholes.push_back({{"name", "Zentrum-\xF0\x9D\x84\x9E"},
                      {"x_m", 3512345.678901234},
                      {"y_m", 5612345.123456789},
                      {"z_m", 0},
                      {"diameter_m", 3.0},
                      {"exit", true},
                      {"slots", hub_slots}});
  manholes.push_back(
      {{"name",
        "Sch\xC3\xA4"
        "cht-\xC3\x84"
        "1"},  // "Schächt-Ä1"
       {"x_m", 3512400.25},
       {"y_m", 5612400.5},
       {"z_m", 0},
       {"diameter_m", 1.0},
       {"slots", {{{"pipe", "Rohr-\xC3\xB6"}, {"azimuth_deg", 0}, {"invert_m", 0}}}}});
  pipes.push_back({{"name", "Rohr-\xC3\xB6"},  // "Rohr-ö": an open end downstream
                   {"from",
                    "Sch\xC3\xA4"
                    "cht-\xC3\x84"
                    "1"},
                   {"to", nullptr},
                   {"length_m", 0.1 + 0.2},
                   {"diameter_m", 0.25}});
  pipes.push_back({{"name", "Stumpf-\xF0\x9F\x98\x80"},  // U+1F600: no manhole at either end
                   {"from", nullptr},
                   {"to", nullptr},
                   {"length_m", 4.5},
                   {"diameter_m", 0.2}});
  return json{{"format", "sewerplan-map"},
              {"version", 1},
              {"name", "awkward"},
              {"manholes", manholes},
              {"pipes", pipes}}
      .dump();
}

// Value for value against the JSON endpoint, on a map of every case a narrower field or a wrong
// offset would lose: the hub's many slots, the open and the placeless pipes' ends, the wide names.
TEST_F(StationServerTest, GivesTheJsonsValuesWholeInTheBinaryForWideNamesOpenEndsAndManySlots) {
  auto [up, uploaded] = post("/api/maps?name=awkward.json", awkward_map());
  ASSERT_EQ(up, 201) << uploaded.dump();
  auto [status, j] = get("/api/maps/awkward");
  ASSERT_EQ(status, 200);
  auto r = client_->Get("/api/maps/awkward/geometry");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200);
  const BinaryGeometry g = decode_geometry(r->body);
  const json& m = j["manholes"];
  const json& p = j["pipes"];
  ASSERT_EQ(g.manholes, sewerplan::kMaxSlotsPerManhole + 2);
  ASSERT_EQ(g.pipes, sewerplan::kMaxSlotsPerManhole + 2);
  EXPECT_EQ(g.bounds, j["bounds"].get<std::vector<double>>());
  for (std::size_t i = 0; i < g.manholes; ++i) {
    EXPECT_EQ(g.names[i], m["name"][i].get<std::string>());
    EXPECT_EQ(g.positions[2 * i], m["x"][i].get<double>());
    EXPECT_EQ(g.positions[2 * i + 1], m["y"][i].get<double>());
    EXPECT_EQ(g.slots[i], m["slots"][i].get<int>());
    EXPECT_EQ(g.exits[i], m["exit"][i].get<int>());
  }
  for (std::size_t i = 0; i < g.pipes; ++i) {
    EXPECT_EQ(g.names[g.manholes + i], p["name"][i].get<std::string>());
    EXPECT_EQ(g.from[i], p["from"][i].get<long long>());
    EXPECT_EQ(g.to[i], p["to"][i].get<long long>());
    EXPECT_EQ(g.lengths[i], p["length_m"][i].get<double>());
    EXPECT_EQ(g.diameters[i], p["diameter_m"][i].get<double>());
  }
  // The cases themselves, so that the loops above compare what they should.
  const auto manhole = [&](const std::string& name) {
    return std::find(g.names.begin(), g.names.begin() + g.manholes, name) - g.names.begin();
  };
  const auto pipe = [&](const std::string& name) {
    return std::find(g.names.begin() + g.manholes, g.names.end(), name) - g.names.begin() -
           g.manholes;
  };
  const auto hub = static_cast<std::size_t>(manhole("Zentrum-\xF0\x9D\x84\x9E"));
  ASSERT_LT(hub, g.manholes);
  EXPECT_EQ(g.slots[hub], static_cast<int>(sewerplan::kMaxSlotsPerManhole));
  EXPECT_EQ(g.positions[2 * hub], 3512345.678901234);  // the double the map read, every digit
  EXPECT_EQ(g.positions[2 * hub + 1], 5612345.123456789);
  const auto open = static_cast<std::size_t>(pipe("Rohr-\xC3\xB6"));
  ASSERT_LT(open, g.pipes);
  EXPECT_EQ(g.from[open], manhole("Sch\xC3\xA4"
                                  "cht-\xC3\x84"
                                  "1"));
  EXPECT_EQ(g.to[open], -1);
  EXPECT_EQ(g.lengths[open], 0.1 + 0.2);
  const auto placeless = static_cast<std::size_t>(pipe("Stumpf-\xF0\x9F\x98\x80"));
  ASSERT_LT(placeless, g.pipes);
  EXPECT_EQ(g.from[placeless], -1);
  EXPECT_EQ(g.to[placeless], -1);
}

// An upload's geometry is built with the maps unlocked: held in the hook after its geometry is
// built and before it is listed, the upload waits for requests to another map, the list and
// another upload, and all are answered. Were the maps locked, they would wait for the upload that
// waits for them, until the client's timeout fails the test (no time is measured). The upload
// being held counts against the limit of maps; it is listed once it is let go.
TEST_F(StationServerTest, ManualAnswersOtherRequestsWhileAnUploadsGeometryIsBuilt) {
  std::vector<int> statuses;
  std::size_t listed_meanwhile = 0;
  std::string held;
  ServerOptions options{.max_maps = 2};
  options.on_geometry_built = [&](const std::string& id) {
    held = id;
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(30, 0);
    for (const char* path : {"/api/maps/map/geometry", "/api/maps/map", "/api/maps"}) {
      auto r = c.Get(path);
      statuses.push_back(r ? r->status : 0);
      if (r && r->status == 200 && std::string_view(path) == "/api/maps") {
        listed_meanwhile = json::parse(r->body)["maps"].size();
      }
    }
    auto r = c.Post("/api/maps?name=second.json", read(kAis / "map.json"), "application/json");
    statuses.push_back(r ? r->status : 0);
  };
  start(options);
  auto [status, uploaded] = post("/api/maps?name=first.json", read(kAis / "map.json"));
  ASSERT_EQ(status, 201) << uploaded.dump();
  EXPECT_EQ(held, "first");
  EXPECT_EQ(statuses, (std::vector<int>{200, 200, 200, 409}));
  EXPECT_EQ(listed_meanwhile, 1u);  // the upload is not listed before its geometry is whole
  const json maps = get("/api/maps").second["maps"];
  ASSERT_EQ(maps.size(), 2u);
  EXPECT_EQ(maps[1]["id"], "first");
  EXPECT_EQ(get("/api/maps/first").first, 200);
}

// A condition upload changes the findings, not the geometry: both forms are the same bytes after
// it, each answer whole (its Content-Length its body's).
TEST_F(StationServerTest, ManualKeepsAMapsGeometryWhenItsConditionIsUploaded) {
  const std::filesystem::path condition = kSource / "datasets/condition/swmm-state-plane";
  start({.maps = {kSource / "datasets/swmm/swmmio-state-plane.inp"}});
  const std::string map = "/api/maps/swmmio-state-plane";
  std::vector<std::string> before;
  for (const std::string& path : {map, map + "/geometry"}) {
    auto r = client_->Get(path.c_str());
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 200);
    EXPECT_EQ(r->get_header_value("Content-Length"), std::to_string(r->body.size()));
    before.push_back(r->body);
  }
  for (int upload = 0; upload < 2; ++upload) {
    auto [status, joined] =
        post(map + "/condition?name=zustand.xml", read(condition / "zustand.xml"));
    ASSERT_EQ(status, 200) << joined.dump();
    EXPECT_GT(joined["findings"].get<int>(), 0);
    EXPECT_EQ(get(map + "/geometry").first, 200);
    EXPECT_EQ(client_->Get(map.c_str())->body, before[0]);
    EXPECT_EQ(client_->Get((map + "/geometry").c_str())->body, before[1]);
  }
}

// Issue 32: the reader's warnings of a map given at the start, of an uploaded one and of a map's
// condition data are listed with the map, for the page to show (they were printed nowhere).
TEST_F(StationServerTest, ManualListsTheReadersWarningsOfEachMapAndOfItsConditionData) {
  const std::filesystem::path isybau = kSource / "datasets/isybau";
  start({.maps = {isybau / "street-2013.xml"}});
  const auto listed = [&](const std::string& id) {
    const json maps = get("/api/maps").second["maps"];
    for (const auto& m : maps) {
      if (m["id"] == id) return m;
    }
    ADD_FAILURE() << "map " << id << " not listed";
    return json();
  };
  const auto messages = [](const json& warnings) {
    std::string all;
    for (const auto& w : warnings)
      all += w["where"].get<std::string>() + ": " + w["message"].get<std::string>() + "\n";
    return all;
  };
  json given = listed("street-2013");
  EXPECT_THAT(messages(given["warnings"]),
              ::testing::HasSubstr("street-2013.xml: 4 manholes have no shaft size"));
  EXPECT_EQ(given["condition_warnings"], json::array());
  auto [status, joined] = post("/api/maps/street-2013/condition?name=street-zustand.xml",
                               read(isybau / "street-zustand.xml"));
  ASSERT_EQ(status, 200) << joined.dump();
  EXPECT_THAT(messages(joined["warnings"]),
              ::testing::HasSubstr("findings name no pipe of the map"));
  given = listed("street-2013");
  EXPECT_EQ(given["condition_warnings"], joined["warnings"]);
  EXPECT_THAT(messages(given["warnings"]), ::testing::HasSubstr("4 manholes have no shaft size"));
  auto r = client_->Post("/api/maps?name=polyline.xml", read(isybau / "street-polyline.xml"),
                         "application/octet-stream");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  const json uploaded = json::parse(r->body);
  EXPECT_THAT(messages(uploaded["warnings"]),
              ::testing::HasSubstr("pipe ends begin inside their manhole"));
  EXPECT_EQ(listed("polyline")["warnings"], uploaded["warnings"]);
}

TEST_F(StationServerTest, WithATokenRefusesTheBinaryGeometryWithoutIt) {
  TearDown();
  start({.token = "s3cret"});
  EXPECT_EQ(get("/api/maps/map/geometry").first, 401);
  client_->set_bearer_token_auth("s3cret");
  auto r = client_->Get("/api/maps/map/geometry");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(decode_geometry(r->body).manholes, 12u);
}

TEST_F(StationServerTest, PlansThePapersMissionIn14StepsWithItsFusedActions) {
  auto [status, j] = post("/api/maps/map/plan?time_limit=20", read(kAis / "missions/paper.json"));
  ASSERT_EQ(status, 200) << j.dump();
  EXPECT_TRUE(j["valid"]);
  EXPECT_EQ(j["steps"].size(), 14u);
  EXPECT_EQ(j["decision"], "follow-plan");
  EXPECT_EQ(j["fused"].size(), 14u);
  EXPECT_EQ(j["dropped"].size(), 0u);
  EXPECT_NEAR(j["cost_s"].get<double>(), 585.4, 0.1);
}

// As the CLI's plan: the planned manhole passages beside the map are used, unless ?motion=0.
TEST_F(StationServerTest, ManualPlansWithTheMotionTableBesideTheMapAndSaysSo) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "station-motion-table";
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(kAis / "map.json", dir / "ais.json",
                             std::filesystem::copy_options::overwrite_existing);
  Diagnostics diagnostics;
  const Result<SewerMap> map = read_map(dir / "ais.json", diagnostics);
  ASSERT_TRUE(map.has_value());
  // One passage the paper's plan takes, M3 from P1 (slot 3) to P5 (slot 1), found impossible.
  const PassageMotion passage{.manhole = *map->find_manhole("M3"),
                              .from = SlotIndex{2},
                              .to = SlotIndex{0},
                              .feasible = false,
                              .reason = "the body hits the wall"};
  const PassageMotionTable table(map_geometry_fingerprint(*map),
                                 profile_geometry_fingerprint(*builtin_profile("makro-1.1")),
                                 {passage});
  {
    std::ofstream out(default_motion_path(dir / "ais.json"));
    write_passage_motion_json(table, *map, out);
  }
  start({.maps = {dir / "ais.json"}});
  const std::string mission = read(kAis / "missions/paper.json");
  auto [status, with] = post("/api/maps/ais/plan", mission);
  ASSERT_EQ(status, 200) << with.dump();
  EXPECT_TRUE(with["motion_table"]);
  EXPECT_EQ(with["text"].get<std::string>().find("FROM_3_TO_1 M3"), std::string::npos)
      << with["text"];
  auto [status_rules, rules] = post("/api/maps/ais/plan?motion=0", mission);
  ASSERT_EQ(status_rules, 200);
  EXPECT_FALSE(rules["motion_table"]);
  EXPECT_NEAR(rules["cost_s"].get<double>(), 585.4, 0.1);
  EXPECT_GT(with["cost_s"].get<double>(), rules["cost_s"].get<double>());
  std::filesystem::remove_all(dir);
}

// The page's GeoJSON export: the mission, the plan's text and a run's log, written as
// `export-geojson --mission --plan --log` writes them; a map without a CRS, or a plan that does not
// read, answered with why.
TEST_F(StationServerTest, ExportsAPlanAndARunAsGeoJsonOnAMapWithACrs) {
  const std::string mission = read(kAis / "missions/paper.json");
  auto [status, plan] = post("/api/maps/map/plan", mission);
  ASSERT_EQ(status, 200) << plan.dump();
  const std::string log = read(kSource / "tests/data/events/demo.jsonl");
  const json request = {{"mission", json::parse(mission)}, {"plan", plan["text"]}, {"log", log}};
  auto [local, why] = post("/api/maps/map/geojson", request.dump());
  EXPECT_EQ(local, 422);
  EXPECT_NE(why["error"]["message"].get<std::string>().find("names no coordinate reference system"),
            std::string::npos)
      << why.dump();
  std::string georeferenced = read(kAis / "map.json");
  georeferenced.insert(georeferenced.find('{') + 1, R"("crs": "EPSG:25832",)");
  auto r = client_->Post("/api/maps?name=utm.json", georeferenced, "application/json");
  ASSERT_EQ(r->status, 201) << r->body;
  r = client_->Post("/api/maps/utm/geojson", request.dump(), "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type"), "application/geo+json");
  std::map<std::string, int> layers;
  const json exported = json::parse(r->body);
  for (const json& f : exported["features"]) ++layers[f["properties"]["layer"].get<std::string>()];
  EXPECT_EQ(layers["planned_route"], 1);
  EXPECT_EQ(layers["driven_route"], 1);
  EXPECT_EQ(layers["task"], 3);
  EXPECT_EQ(layers["manhole"], 12);
  // The mission alone: the network and its marks, no route.
  auto [bare, doc] = post("/api/maps/utm/geojson", json{{"mission", json::parse(mission)}}.dump());
  ASSERT_EQ(bare, 200);
  for (const json& f : doc["features"]) {
    EXPECT_NE(f["properties"]["layer"], "planned_route");
    EXPECT_NE(f["properties"]["layer"], "driven_route");
  }
  // A plan that does not read, a plan that is not text: the reader's message, a 400.
  auto [bad, bad_why] = post("/api/maps/utm/geojson",
                             json{{"mission", json::parse(mission)}, {"plan", "FLY P1"}}.dump());
  EXPECT_EQ(bad, 422);
  EXPECT_NE(bad_why["error"]["message"].get<std::string>().find("plan"), std::string::npos);
  EXPECT_EQ(
      post("/api/maps/utm/geojson", json{{"mission", json::parse(mission)}, {"plan", 5}}.dump())
          .first,
      400);
  EXPECT_EQ(post("/api/maps/utm/geojson", R"({"plan": ""})").first, 400);
}

TEST_F(StationServerTest, TakesAnUploadedMapInAnyFormatUnderANewId) {
  auto r =
      client_->Post("/api/maps?name=epa-example1.inp",
                    read(kSource / "datasets/swmm/epa-example1.inp"), "application/octet-stream");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  EXPECT_EQ(json::parse(r->body)["id"], "epa-example1");
  EXPECT_GT(json::parse(r->body)["manholes"].get<int>(), 0);
  // A map that names its coordinate reference system: the list says which (the page shows the
  // cursor's position in it).
  std::string georeferenced = read(kAis / "map.json");
  georeferenced.insert(georeferenced.find('{') + 1, R"("crs": "EPSG:25832",)");
  r = client_->Post("/api/maps?name=utm.json", georeferenced, "application/json");
  ASSERT_EQ(r->status, 201) << r->body;
  const json maps = get("/api/maps").second["maps"];
  const auto utm =
      std::find_if(maps.begin(), maps.end(), [](const json& m) { return m["id"] == "utm"; });
  ASSERT_NE(utm, maps.end());
  EXPECT_EQ((*utm)["crs"], "EPSG:25832");
  r = client_->Post("/api/maps?name=ais.json", read(kAis / "map.json"), "application/json");
  ASSERT_EQ(r->status, 201) << r->body;
  EXPECT_EQ(json::parse(r->body)["id"], "ais");
  EXPECT_EQ(get("/api/maps").second["maps"].size(), 4u);
  auto [status, plan] = post("/api/maps/ais/plan", read(kAis / "missions/paper.json"));
  EXPECT_EQ(status, 200) << plan.dump();
  EXPECT_EQ(plan["steps"].size(), 14u);
  // The same name again: a new ID. The format named by ?format=.
  r = client_->Post("/api/maps?name=ais.json", read(kAis / "map.json"), "application/json");
  EXPECT_EQ(json::parse(r->body)["id"], "ais-2");
  r = client_->Post("/api/maps?name=x&format=json", read(kAis / "map.json"), "application/json");
  EXPECT_EQ(r->status, 201);
}

TEST_F(StationServerTest, RefusesHostileUploadsWithA4xxAndWritesNothing) {
  const std::string map = read(kAis / "map.json");
  // A name that climbs: only its stem, cleaned, becomes the ID; nothing is written anywhere.
  auto r =
      client_->Post("/api/maps?name=../../../tmp/evil%20%3Bname.json", map, "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  EXPECT_EQ(json::parse(r->body)["id"], "evilname");
  EXPECT_FALSE(std::filesystem::exists("/tmp/evil ;name.json"));
  EXPECT_EQ(post("/api/maps?name=a.json", "{not json").first, 422);
  EXPECT_EQ(post("/api/maps?name=a.json", R"({"format": "sewerplan-map"})").first, 422);
  EXPECT_EQ(post("/api/maps?name=a.bin", std::string(100, '\0')).first, 422);
  EXPECT_EQ(post("/api/maps?name=a&format=pdf", map).first, 400);
  const auto [status, error] = post("/api/maps?name=a.json", "{not json");
  EXPECT_TRUE(error["error"].contains("message")) << error.dump();
}

TEST_F(StationServerTest, ManualRefusesMapsBeyondItsLimit) {
  start({.max_maps = 2});
  const std::string map = read(kAis / "map.json");
  EXPECT_EQ(post("/api/maps?name=a.json", map).first, 201);
  EXPECT_EQ(post("/api/maps?name=b.json", map).first, 409);
}

// Uploads while other requests plan and list: every answer whole, no map lost.
TEST_F(StationServerTest, AnswersConcurrentPlansAndUploads) {
  const std::string map = read(kAis / "map.json");
  const std::string mission = read(kAis / "missions/paper.json");
  const int port = port_;
  std::vector<std::thread> threads;
  std::atomic<int> planned{0};
  std::atomic<int> uploaded{0};
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      httplib::Client c("127.0.0.1", port);
      c.set_read_timeout(120, 0);
      for (int i = 0; i < 3; ++i) {
        if (t % 2 == 0) {
          auto r = c.Post("/api/maps/map/plan", mission, "application/json");
          if (r && r->status == 200 && json::parse(r->body)["steps"].size() == 14) ++planned;
        } else {
          auto r = c.Post("/api/maps?name=m.json", map, "application/json");
          if (r && r->status == 201) ++uploaded;
        }
      }
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(planned, 6);
  EXPECT_EQ(uploaded, 6);
  EXPECT_EQ(get("/api/maps").second["maps"].size(), 7u);
}

TEST_F(StationServerTest, ValidatesAMissionWithTheClisMessages) {
  std::string mission = read(kAis / "missions/paper.json");
  mission.replace(mission.find("\"P4\""), 4, "\"P99\"");
  auto [status, j] = post("/api/maps/map/validate", mission);
  EXPECT_EQ(status, 200);
  EXPECT_FALSE(j["valid"]);
  ASSERT_FALSE(j["errors"].empty());
  EXPECT_NE(j["errors"][0]["message"].get<std::string>().find("P99"), std::string::npos);
  // Planning it is a 422 with the same messages.
  auto [plan_status, plan] = post("/api/maps/map/plan", mission);
  EXPECT_EQ(plan_status, 422);
  EXPECT_EQ(plan["error"]["code"], "invalid-mission");
}

TEST_F(StationServerTest, AnswersBadRequestsWithA4xxJsonError) {
  EXPECT_EQ(post("/api/maps/map/plan", "{not json").first, 422);
  EXPECT_EQ(post("/api/maps/map/plan", "{not json").second["error"]["code"], "parse");
  EXPECT_EQ(get("/api/maps/nowhere").first, 404);
  EXPECT_EQ(get("/api/maps/nowhere").second["error"]["message"], "no map 'nowhere'");
  EXPECT_EQ(get("/api/no-such-endpoint").first, 404);
  EXPECT_EQ(post("/api/maps/map/plan?time_limit=abc", "{}").first, 400);
  EXPECT_EQ(post("/api/maps/map/plan?time_limit=-1", "{}").first, 400);
  EXPECT_EQ(get("/api/maps/map/driveability?profile=/etc/passwd").first, 400);
  EXPECT_EQ(post("/api/maps/map/simulate", "[1]").first, 400);
  EXPECT_EQ(post("/api/maps/map/simulate", R"({"mission": 3})").first, 400);
  EXPECT_EQ(post("/api/maps/map/replay", "not a log\n").first, 422);
}

// nlohmann keeps the last of two equal keys; the station's file readers refuse them (JsonFields),
// and so do /simulate and /campaign, whose mission comes inside a larger object: before, the second
// "start" (or "runs") silently won.
TEST_F(StationServerTest, RefusesAKeyGivenTwiceInASimulateOrCampaignBody) {
  const std::string mission = read(kAis / "missions/paper.json");
  const std::size_t brace = mission.find('{');
  ASSERT_NE(brace, std::string::npos);
  // The mission with its first key repeated at its start: {"id": ..., <the mission's members>}.
  const json parsed = json::parse(mission);
  const std::string first_key = parsed.begin().key();
  const std::string twice =
      "{\"" + first_key + "\": " + parsed.begin().value().dump() + ", " + mission.substr(brace + 1);
  auto [status, j] = post("/api/maps/map/simulate", "{\"mission\": " + twice + "}");
  EXPECT_EQ(status, 400);
  EXPECT_EQ(j["error"]["message"], "body:$.mission." + first_key + ": error: field '" + first_key +
                                       "' given twice in one object: which value is meant is "
                                       "unclear");
  auto [campaign_status, c] =
      post("/api/maps/map/campaign", R"({"mission": )" + mission + R"(, "runs": 2, "runs": 3})");
  EXPECT_EQ(campaign_status, 400);
  EXPECT_EQ(c["error"]["message"],
            "body:$.runs: error: field 'runs' given twice in one object: which value is meant is "
            "unclear");
  // Within an array, by index; every repeat, one a line.
  auto [array_status, a] =
      post("/api/maps/map/simulate", R"({"faults": [{"at": 1}, {"at": 2, "at": 3}], "mission": )" +
                                         mission + R"(, "faults": []})");
  EXPECT_EQ(array_status, 400);
  EXPECT_EQ(a["error"]["message"],
            "body:$.faults[1].at: error: field 'at' given twice in one object: which value is "
            "meant is unclear\nbody:$.faults: error: field 'faults' given twice in one object: "
            "which value is meant is unclear");
  auto [syntax_status, syntax] = post("/api/maps/map/simulate", "{\"mission\": ");
  EXPECT_EQ(syntax_status, 400);
  EXPECT_EQ(syntax["error"]["message"].get<std::string>().rfind(
                "body:1:13: error: JSON syntax error: syntax error while parsing value", 0),
            0u)
      << syntax;
}

// A hostile body: thousands of repeats are answered with the first 20 and a count, not with many
// times the body's size; nesting beyond 256 levels is refused before it is read.
TEST_F(StationServerTest, BoundsWhatItSaysOfAHostileBody) {
  std::string repeats = "{";
  for (int i = 0; i < 5000; ++i) repeats += "\"a\": 0, ";
  repeats += "\"a\": 0}";
  auto [status, j] = post("/api/maps/map/campaign", repeats);
  EXPECT_EQ(status, 400);
  const std::string message = j["error"]["message"];
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 20);
  EXPECT_NE(message.find("(4980 more fields given twice)"), std::string::npos) << message;
  EXPECT_LT(message.size(), 2000u);
  auto [deep_status, deep] = post("/api/maps/map/simulate", std::string(100000, '['));
  EXPECT_EQ(deep_status, 400);
  EXPECT_EQ(deep["error"]["message"],
            "body:1:257: error: the JSON nests arrays and objects more than 256 levels deep");
}

// Issue 33: the station reads its bodies with the file readers' parser and JsonFields (no parse,
// dump and parse again of its own): what the old body reader refused is refused alike, named at
// its place in the body, and what the mission's and faults' readers say is said at the body's path.
TEST_F(StationServerTest, ReadsBodiesWithTheFileReadersNamingTheBodysPath) {
  const std::string mission = read(kAis / "missions/paper.json");
  const auto message = [&](const std::string& path, const std::string& body) {
    auto [status, j] = post(path, body);
    return std::to_string(status) + " " + j["error"]["message"].get<std::string>();
  };
  // Nested deeper than 256 levels inside a well-formed body, in a part no reader looks at: where.
  const std::string deep = std::string(300, '[') + std::string(300, ']');
  EXPECT_EQ(message("/api/maps/map/simulate", "{\"mission\": " + mission + ", \"x\": " + deep + "}")
                .rfind("400 body:", 0),
            0u);
  EXPECT_THAT(
      message("/api/maps/map/simulate", "{\"x\": " + deep + "}"),
      HasSubstr(":1:262: error: the JSON nests arrays and objects more than 256 levels deep"));
  // A key given twice in an object no reader reads (an unknown field's value) is still refused.
  EXPECT_EQ(message("/api/maps/map/campaign",
                    "{\"mission\": " + mission + ", \"extra\": [{\"a\": 1, \"a\": 2}]}"),
            "400 body:$.extra[0].a: error: field 'a' given twice in one object: which value is "
            "meant is unclear");
  // Text that is not UTF-8, a number beyond a double: at their line and column.
  EXPECT_THAT(message("/api/maps/map/simulate", "{\"mission\": \"\xff\xfe\"}"),
              HasSubstr("400 body:1:"));
  EXPECT_THAT(message("/api/maps/map/simulate", "{\"mission\": " + mission + ",\n \"x\": 1e999}"),
              HasSubstr("error: number 1e999 is out of range"));
  EXPECT_THAT(message("/api/maps/map/simulate", "{\"mission\": " + mission + ",\n \"x\": 1e999}"),
              HasSubstr("400 body:"));
  // A wrong type in the mission: the mission file's reader's message, at the body's path (422).
  json typed = json::parse(mission);
  typed["tasks"][1]["type"] = 3;
  EXPECT_THAT(message("/api/maps/map/simulate", json{{"mission", typed}}.dump()),
              HasSubstr("422 body:$.mission.tasks[1].type: error: expected a string, got 3"));
  // And in the faults: the fault file's reader's message, at the body's path.
  EXPECT_THAT(
      message("/api/maps/map/simulate", json{{"mission", json::parse(mission)},
                                             {"faults",
                                              {{"format", "sewerplan-faults"},
                                               {"version", 1},
                                               {"obstacles", {{{"pipe", 7}, {"offset_m", 1}}}}}}}
                                            .dump()),
      HasSubstr("body:$.faults.obstacles[0].pipe: error: expected a string, got 7"));
  EXPECT_THAT(message("/api/maps/map/simulate",
                      json{{"mission", json::parse(mission)}, {"random_faults", 7}}.dump()),
              HasSubstr("400 body:$.random_faults: error: expected \"SEED[,RATE]\", got 7"));
  EXPECT_THAT(
      message("/api/maps/map/geojson", json{{"mission", json::parse(mission)}, {"plan", 7}}.dump()),
      HasSubstr("400 body:$.plan: error: expected a string, got 7"));
  // Every wrong field of a campaign in one answer, each at its path.
  const std::string both = message(
      "/api/maps/map/campaign",
      json{{"mission", json::parse(mission)}, {"runs", "many"}, {"allow_push", "yes"}}.dump());
  EXPECT_THAT(both, HasSubstr("400 body:$.runs: error: expected a whole number from 1 to"));
  EXPECT_THAT(both, HasSubstr("\nbody:$.allow_push: error: expected true or false, got \"yes\""));
}

// Issue 33: every JSON body refuses an unknown field with a 400 naming its path and the fields
// known, every wrong field in one answer. Before, /simulate and /geojson ignored one without a word
// (a "seeed" ran with the default seed), and a mission's misspelt field was a warning /plan never
// showed.
TEST_F(StationServerTest, Issue33RefusesUnknownFieldsInEveryJsonBody) {
  const json mission = json::parse(read(kAis / "missions/paper.json"));
  const auto message = [&](const std::string& path, const json& body) {
    auto [status, j] = post(path, body.dump());
    return std::to_string(status) + " " + j["error"]["message"].get<std::string>();
  };
  EXPECT_EQ(message("/api/maps/map/simulate", {{"mission", mission}, {"seeed", 4}}),
            "400 body:$.seeed: error: unknown field 'seeed' (expected mission, faults, "
            "random_faults)");
  // Every wrong field at once, a wrong type beside the unknown ones.
  EXPECT_EQ(message("/api/maps/map/simulate",
                    {{"mission", mission}, {"a", 1}, {"random_faults", 7}, {"b", 2}}),
            "400 body:$.a: error: unknown field 'a' (expected mission, faults, random_faults)\n"
            "body:$.b: error: unknown field 'b' (expected mission, faults, random_faults)\n"
            "body:$.random_faults: error: expected \"SEED[,RATE]\", got 7");
  // Both ways of giving faults: which one runs is not guessed.
  EXPECT_EQ(message("/api/maps/map/simulate",
                    {{"mission", mission}, {"faults", json::object()}, {"random_faults", "4"}}),
            "400 body:$.random_faults: error: give faults or random_faults, not both");
  EXPECT_EQ(message("/api/maps/map/geojson", {{"mission", mission}, {"plann", "x"}}),
            "400 body:$.plann: error: unknown field 'plann' (expected mission, plan, log)");
  EXPECT_EQ(message("/api/maps/map/campaign", {{"mission", mission}, {"rnus", 3}}),
            "400 body:$.rnus: error: unknown field 'rnus' (expected mission, runs, seed, "
            "fault_rates, jobs, allow_push, planner_time_limit_s, risk, faults_from_condition, "
            "timeout_s)");
  // Not an object: the fields it should have, from the same list.
  EXPECT_EQ(message("/api/maps/map/geojson", json::array({1})),
            "400 body:$: expected a JSON object {\"mission\", \"plan\", \"log\"}, got an array");
  // The mission's own fields, by the mission file's reader: in a body at the body's path, in
  // /plan's and /validate's mission file at the file's.
  json misspelt = mission;
  misspelt["batery_reserve"] = 0.5;
  misspelt["tasks"][0]["finall"] = true;
  const std::string top =
      "$.batery_reserve: error: unknown field 'batery_reserve' (expected format, version, name, "
      "profile, start, tasks, exits, battery_reserve, closed)";
  const std::string task =
      "$.tasks[0].finall: error: unknown field 'finall' (expected name, "
      "type, at, pipe, pipes, final)";
  for (const char* path :
       {"/api/maps/map/simulate", "/api/maps/map/geojson", "/api/maps/map/campaign"}) {
    const std::string m = message(path, {{"mission", misspelt}});
    EXPECT_THAT(m, HasSubstr("422 body:$.mission" + top.substr(1))) << path;
    EXPECT_THAT(m, HasSubstr("body:$.mission" + task.substr(1))) << path;
  }
  const std::string planned = message("/api/maps/map/plan", misspelt);
  EXPECT_THAT(planned, HasSubstr("422 mission.json:" + top));
  EXPECT_THAT(planned, HasSubstr("mission.json:" + task));
  auto [status, validated] = post("/api/maps/map/validate", misspelt.dump());
  EXPECT_EQ(status, 200);
  EXPECT_FALSE(validated["valid"]);
  ASSERT_EQ(validated["errors"].size(), 2u) << validated;
  EXPECT_EQ(validated["errors"][0]["where"], "mission.json:$.batery_reserve");
  EXPECT_EQ(validated["errors"][1]["where"], "mission.json:$.tasks[0].finall");
}

TEST_F(StationServerTest, RefusesABodyOverTheSizeLimit) {
  TearDown();
  start({.max_body_bytes = 1000});
  auto [status, j] = post("/api/maps/map/validate", std::string(5000, ' '));
  EXPECT_EQ(status, 413);
  EXPECT_EQ(j["error"]["code"], "http-413");
  EXPECT_EQ(j["error"]["message"], "the request body is over the size limit of 1000 bytes");
}

TEST_F(StationServerTest, WithATokenRefusesApiRequestsWithoutIt) {
  TearDown();
  start({.token = "s3cret"});
  EXPECT_EQ(get("/api/maps").first, 401);
  client_->set_bearer_token_auth("wrong");
  EXPECT_EQ(get("/api/maps").first, 401);
  client_->set_bearer_token_auth("s3cret");
  EXPECT_EQ(get("/api/maps").first, 200);
  // A stream too: the page reads it with fetch() and the header.
  auto r = client_->Post("/api/maps/map/simulate",
                         json{{"mission", json::parse(read(kAis / "missions/paper.json"))}}.dump(),
                         "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_NE(r->body.find("event: report"), std::string::npos);
}

// A token in the URL ends up in logs and the history: refused with a 401 that says where it goes,
// with or without the header, right or wrong.
TEST_F(StationServerTest, WithATokenRefusesOneInTheUrl) {
  TearDown();
  start({.token = "s3cret"});
  auto [status, j] = get("/api/maps?token=s3cret");
  EXPECT_EQ(status, 401);
  EXPECT_EQ(j["error"]["code"], "unauthorised");
  EXPECT_NE(j["error"]["message"].get<std::string>().find("Authorization: Bearer"),
            std::string::npos);
  EXPECT_NE(j["error"]["message"].get<std::string>().find("?token="), std::string::npos);
  client_->set_bearer_token_auth("s3cret");
  EXPECT_EQ(get("/api/maps?token=s3cret").first, 401);
  EXPECT_EQ(get("/api/campaign?token=wrong").first, 401);
  EXPECT_EQ(post("/api/maps/map/simulate?token=s3cret", "{}").first, 401);
  EXPECT_EQ(get("/api/maps").first, 200);
}

TEST_F(StationServerTest, ServesThePageButNoFileOutsideIt) {
  const std::filesystem::path root = std::filesystem::temp_directory_path() / "sewerplan-web-test";
  std::filesystem::create_directories(root / "assets");
  std::ofstream(root / "index.html") << "<html>station</html>";
  TearDown();
  start({.web_root = root});
  auto page = client_->Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_EQ(page->body, "<html>station</html>");
  for (const char* path : {"/../station_server_test.cc", "/assets/../../etc/passwd",
                           "/%2e%2e/%2e%2e/etc/passwd", "/..%2f..%2fetc%2fpasswd"}) {
    auto r = client_->Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_GE(r->status, 400) << path;
    EXPECT_EQ(r->body.find("root:"), std::string::npos) << path;
  }
  std::filesystem::remove_all(root);
}

// httplib would compress with brotli at its slowest quality for a browser ("br"): the page's
// bundle took 14 s to arrive on a loaded machine. The page and the maps go uncompressed.
TEST_F(StationServerTest, SendsThePageAndTheMapsUncompressedToABrowser) {
  const std::filesystem::path root = std::filesystem::temp_directory_path() / "sewerplan-web-br";
  std::filesystem::create_directories(root);
  std::ofstream(root / "index.html") << "<html>station</html>";
  std::ofstream(root / "bundle.js") << std::string(100000, ' ') << "export const x = 1;\n";
  TearDown();
  start({.web_root = root});
  const httplib::Headers browser = {{"Accept-Encoding", "gzip, deflate, br"}};
  for (const char* path : {"/bundle.js", "/api/maps/map", "/api/maps"}) {
    auto r = client_->Get(path, browser);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 200) << path;
    EXPECT_EQ(r->get_header_value("Content-Encoding"), "") << path;
  }
  EXPECT_EQ(client_->Get("/bundle.js", browser)->get_header_value("Content-Type"),
            "application/javascript; charset=utf-8");
  std::filesystem::remove_all(root);
}

// One server-sent event of the simulation's stream.
struct Sse {
  std::string type;
  std::string data;
  long long wall_ms = -1;
};

std::vector<Sse> parse_stream(const std::string& body) {
  std::vector<Sse> events;
  std::size_t at = 0;
  for (std::size_t end; (end = body.find("\n\n", at)) != std::string::npos; at = end + 2) {
    Sse e;
    std::istringstream block(body.substr(at, end - at));
    for (std::string line; std::getline(block, line);) {
      if (line.starts_with("event: ")) e.type = line.substr(7);
      if (line.starts_with("data: ")) e.data = line.substr(6);
      if (line.starts_with("wall_ms: ")) e.wall_ms = std::stoll(line.substr(9));
    }
    events.push_back(std::move(e));
  }
  return events;
}

// A map with inspection findings is planned and simulated as the CLI's plan and simulate do it
// (--risk, default impassable): what the findings close is closed, unless ?risk=ignore.
TEST_F(StationServerTest, ManualPlansAndSimulatesWithWhatTheMapsFindingsClose) {
  const std::filesystem::path condition = kSource / "datasets/condition/swmm-state-plane";
  start({.maps = {kSource / "datasets/swmm/swmmio-state-plane.inp"}});
  const std::string mission = read(condition / "mission.json");
  const std::string map = "/api/maps/swmmio-state-plane";
  // Before the findings: every task is reachable.
  auto [before, planned] = post(map + "/plan", mission);
  ASSERT_EQ(before, 200) << planned.dump();
  EXPECT_EQ(planned["risk"]["closed_by_findings"], 0);
  ASSERT_EQ(post(map + "/condition?name=zustand.xml", read(condition / "zustand.xml")).first, 200);
  // With them (as `plan --condition`), a sample lies behind a pipe no robot passes.
  auto [closed, why] = post(map + "/plan", mission);
  EXPECT_EQ(closed, 422);
  EXPECT_NE(why.dump().find("sample-J2-023.1"), std::string::npos) << why.dump();
  auto [selected, dropped] = post(map + "/plan?select_goals=1", mission);
  ASSERT_EQ(selected, 200) << dropped.dump();
  EXPECT_EQ(dropped["risk"]["mode"], "impassable");
  EXPECT_EQ(dropped["risk"]["closed_by_findings"], 19);
  EXPECT_NE(dropped["dropped"].dump().find("sample-J2-023.1"), std::string::npos)
      << dropped["dropped"].dump();
  auto [expected, weighed] = post(map + "/plan?select_goals=1&risk=expected", mission);
  ASSERT_EQ(expected, 200) << weighed.dump();
  EXPECT_GT(weighed["risk"]["possible_blockages"].get<int>(), 0);
  auto [ignored, blind] = post(map + "/plan?risk=ignore", mission);
  ASSERT_EQ(ignored, 200) << blind.dump();
  EXPECT_EQ(blind["cost_s"], planned["cost_s"]);
  auto [bad, named] = post(map + "/plan?risk=maybe", mission);
  EXPECT_EQ(bad, 400);
  EXPECT_NE(named["error"]["message"].get<std::string>().find("risk"), std::string::npos);
  // The simulation leaves the closed sample out, as the plan did; blind to the findings, it takes
  // it (the hidden world has no faults).
  const std::string body = R"({"mission": )" + mission + "}";
  const auto sample_taken = [&](const std::string& query) {
    auto r = client_->Post(map + "/simulate" + query, body, "application/json");
    EXPECT_TRUE(r && r->status == 200) << (r ? r->body : "no answer");
    if (!r) return false;
    return std::ranges::any_of(parse_stream(r->body), [](const Sse& e) {
      return e.type == "task_done" && e.data.find("sample-J2-023.1") != std::string::npos;
    });
  };
  EXPECT_FALSE(sample_taken(""));
  EXPECT_TRUE(sample_taken("?risk=ignore"));
  EXPECT_EQ(client_->Post(map + "/simulate?risk=maybe", body, "application/json")->status, 400);
}

TEST_F(StationServerTest, StreamsASimulationsEventsAndItsReportThatReplayReadsBack) {
  const std::string body = R"({"mission": )" + read(kAis / "missions/paper.json") +
                           R"(, "faults": )" + read(kAis / "faults/blocked-p5.json") + "}";
  auto r = client_->Post("/api/maps/map/simulate", body, "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type"), "text/event-stream");
  const std::vector<Sse> stream = parse_stream(r->body);
  ASSERT_FALSE(stream.empty());
  ASSERT_EQ(stream.back().type, "report");
  const json report = json::parse(stream.back().data);
  EXPECT_EQ(report["outcome"], "ended");
  EXPECT_GE(report["replans"].get<int>(), 1);
  // The event log's JSON lines (replay reads them back, one event each), each plan followed by
  // its route, every event stamped with the server's wall clock.
  std::string log;
  std::size_t events = 0;
  std::vector<json> routes;
  std::vector<std::string> plans;
  for (std::size_t i = 0; i + 1 < stream.size(); ++i) {
    const Sse& e = stream[i];
    EXPECT_GT(e.wall_ms, 0) << e.type;
    if (e.type == "route") {
      ASSERT_GT(i, 0u);
      EXPECT_TRUE(stream[i - 1].type == "plan" || stream[i - 1].type == "replan");
      routes.push_back(json::parse(e.data));
      continue;
    }
    if (e.type == "learnt") continue;  // after the run: not an event of the log
    if (e.type == "plan" || e.type == "replan") plans.push_back(e.type);
    log += e.data + "\n";
    ++events;
  }
  ASSERT_EQ(plans, (std::vector<std::string>{"plan", "replan"}));  // P5 is blocked
  ASSERT_EQ(routes.size(), 2u);
  // The paper's route, through P5 to the end in P9; the replan's backs out of P5 and avoids it.
  EXPECT_EQ(routes[0]["steps"].size(), 14u);
  EXPECT_EQ(routes[0]["steps"][0], "DRIVE_PIPE_TO_MANHOLE P12 M2");
  EXPECT_EQ(routes[0]["pipes"], json::parse(R"(["P12", "P1", "P5", "P6", "P4", "P8", "P9"])"));
  ASSERT_FALSE(routes[1]["pipes"].empty());
  EXPECT_EQ(routes[1]["pipes"][0], "P5");
  EXPECT_EQ(std::ranges::count(routes[1]["pipes"], json("P5")), 1);
  auto [status, replayed] = post("/api/maps/map/replay", log);
  EXPECT_EQ(status, 200);
  EXPECT_EQ(replayed["events"].size(), events);
}

// Each finding of the map for the page to draw: where it is, its code and the code's name, its
// class for the robot, and what the risk mode makes of it, as close_findings does: the places the
// plan says it closed are those the findings document calls closed.
TEST_F(StationServerTest, ManualSaysWhatEachRiskModeMakesOfEachFinding) {
  const std::filesystem::path isybau = kSource / "datasets/isybau";
  start({.maps = {isybau / "street-2017.xml"}});
  const std::string map = "/api/maps/street-2017";
  const auto findings = [&](const std::string& query) {
    auto r = client_->Get(map + "/findings" + query);
    EXPECT_TRUE(r);
    return r ? std::pair{r->status, json::parse(r->body)} : std::pair{0, json()};
  };
  auto [none, empty] = findings("?profile=makro-plus");
  ASSERT_EQ(none, 200) << empty.dump();
  EXPECT_TRUE(empty["findings"].empty());
  ASSERT_EQ(
      post(map + "/condition?name=street-zustand.xml", read(isybau / "street-zustand.xml")).first,
      200);
  const auto of = [](const json& doc, std::string_view pipe, std::string_view code) {
    for (const json& f : doc["findings"]) {
      if (f["pipe"] == pipe && f["code"] == code) return f;
    }
    return json();
  };
  const auto count = [](const json& doc, std::string_view use) {
    return std::ranges::count_if(doc["findings"],
                                 [&](const json& f) { return f["planner"] == use; });
  };
  auto [status, expected] = findings("?profile=makro-plus&risk=expected");
  ASSERT_EQ(status, 200) << expected.dump();
  EXPECT_EQ(expected["risk"], "expected");
  EXPECT_EQ(expected["profile"], "makro-plus");
  const json roots = of(expected, "S1", "BBA");
  EXPECT_EQ(roots["name"], "roots");
  EXPECT_EQ(roots["offset_m"], 7.5);
  EXPECT_EQ(roots["characterisation"], "B");
  EXPECT_EQ(roots["quantity1"], 10);
  EXPECT_EQ(roots["class"], "blockage");
  EXPECT_NEAR(roots["probability"].get<double>(), 0.3, 1e-12);
  EXPECT_EQ(roots["reason"], "BBA roots");
  EXPECT_EQ(roots["planner"], "weighed");
  const json collapse = of(expected, "S2", "BAC");
  EXPECT_EQ(collapse["class"], "impassable");
  EXPECT_EQ(collapse["planner"], "closed");
  EXPECT_EQ(of(expected, "S1", "BAJ")["class"], "danger");
  EXPECT_EQ(of(expected, "S1", "BAJ")["planner"], "ignored");
  EXPECT_EQ(of(expected, "S1", "BCD")["name"], "start node");
  EXPECT_EQ(of(expected, "S1", "BCD")["class"], "none");
  EXPECT_EQ(expected["counts"]["weighed"], count(expected, "weighed"));
  EXPECT_EQ(expected["counts"]["closed"], count(expected, "closed"));
  // The default mode closes only what no robot of the profile passes; avoid closes the danger too.
  auto [s1, impassable] = findings("?profile=makro-plus");
  EXPECT_EQ(impassable["risk"], "impassable");
  EXPECT_EQ(of(impassable, "S1", "BBA")["planner"], "ignored");
  EXPECT_EQ(count(impassable, "weighed"), 0);
  auto [s2, avoid] = findings("?profile=makro-plus&risk=avoid");
  EXPECT_EQ(of(avoid, "S1", "BAJ")["planner"], "closed");
  auto [s3, ignore] = findings("?profile=makro-plus&risk=ignore");
  EXPECT_EQ(count(ignore, "ignored"), std::ssize(ignore["findings"]));
  // The plan closes what the document calls closed.
  const std::string mission = R"({"format": "sewerplan-mission", "version": 1, "name": "m",
    "profile": "makro-plus", "start": {"manhole": "S2"},
    "tasks": [{"name": "end", "type": "go_to", "at": {"pipe": "S3", "offset_m": 40}, "final": true}]})";
  for (const std::string mode : {"impassable", "avoid", "expected", "ignore"}) {
    auto [plan_status, plan] = post(map + "/plan?select_goals=1&risk=" + mode, mission);
    auto [doc_status, doc] = findings("?profile=makro-plus&risk=" + mode);
    ASSERT_EQ(doc_status, 200);
    EXPECT_EQ(plan_status, 200) << mode << ": " << plan.dump();
    EXPECT_EQ(plan["risk"]["closed_by_findings"], count(doc, "closed")) << mode;
    EXPECT_EQ(plan["risk"]["possible_blockages"], count(doc, "weighed")) << mode;
  }
  EXPECT_EQ(findings("?profile=nobody").first, 400);
  EXPECT_EQ(findings("?profile=makro-plus&risk=maybe").first, 400);
  EXPECT_EQ(client_->Get("/api/maps/nowhere/findings?profile=makro-plus")->status, 404);
}

// A plan that weighs possible blockages says its risk beside it: the chance that none on its
// route stops the robot, the expected cost of stops it was chosen with, and the blockages passed;
// the mode's own figures are added, not put in their place.
TEST_F(StationServerTest, ManualSaysThePlansRiskWhenItWeighsPossibleBlockages) {
  const std::filesystem::path condition = kSource / "datasets/condition/swmm-state-plane";
  start({.maps = {kSource / "datasets/swmm/swmmio-state-plane.inp"}});
  const std::string map = "/api/maps/swmmio-state-plane";
  ASSERT_EQ(post(map + "/condition?name=zustand.xml", read(condition / "zustand.xml")).first, 200);
  auto [status, plan] =
      post(map + "/plan?select_goals=1&risk=expected", read(condition / "mission.json"));
  ASSERT_EQ(status, 200) << plan.dump();
  const json& risk = plan["risk"];
  EXPECT_EQ(risk["mode"], "expected");
  ASSERT_TRUE(risk.contains("unobstructed_probability")) << risk.dump();
  ASSERT_TRUE(risk.contains("expected_cost_s")) << risk.dump();
  ASSERT_FALSE(risk["hazards"].empty()) << risk.dump();
  double unobstructed = 1;
  for (const json& h : risk["hazards"]) unobstructed *= 1 - h["probability"].get<double>();
  EXPECT_NEAR(risk["unobstructed_probability"].get<double>(), unobstructed, 1e-9);
  EXPECT_LT(risk["unobstructed_probability"].get<double>(), 1.0);
  EXPECT_GT(risk["expected_cost_s"].get<double>(), 0.0);
  // Without weighing, no figures the planner did not compute.
  auto [s, blind] = post(map + "/plan?select_goals=1", read(condition / "mission.json"));
  ASSERT_EQ(s, 200);
  EXPECT_FALSE(blind["risk"].contains("unobstructed_probability"));
  EXPECT_FALSE(blind["risk"].contains("expected_cost_s"));
}

// After a run, what the robot learnt: the blockage in P5 its recovery could not clear (as
// `simulate --learnt` writes it, which reads it back), and what it measured of the map: in the
// simulated world, which is the map, no corrections.
TEST_F(StationServerTest, SendsWhatTheRobotLearntAfterTheRun) {
  const std::string body = R"({"mission": )" + read(kAis / "missions/paper.json") +
                           R"(, "faults": )" + read(kAis / "faults/blocked-p5.json") + "}";
  auto r = client_->Post("/api/maps/map/simulate", body, "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const std::vector<Sse> stream = parse_stream(r->body);
  ASSERT_GE(stream.size(), 2u);
  ASSERT_EQ(stream[stream.size() - 2].type, "learnt");
  const json doc = json::parse(stream[stream.size() - 2].data);
  const json& learnt = doc["learnt"];
  EXPECT_EQ(learnt["format"], "sewerplan-learnt");
  ASSERT_EQ(learnt["blockages"].size(), 1u) << doc.dump();
  EXPECT_EQ(learnt["blockages"][0]["pipe"], "P5");
  const json& measured = doc["measurements"];
  EXPECT_GT(measured["pipes_measured"].get<int>(), 0) << doc.dump();
  EXPECT_TRUE(measured["discrepancies"].empty()) << doc.dump();
}

TEST_F(StationServerTest, NamesTheMapThatCannotBeRead) {
  Result<std::unique_ptr<StationServer>> created =
      StationServer::create({.maps = {kAis / "no-such-map.json"}});
  ASSERT_FALSE(created.has_value());
  EXPECT_NE(created.error().message.find("no-such-map.json"), std::string::npos);
}

}  // namespace
}  // namespace sewerplan::server
