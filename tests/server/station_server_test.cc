// SPDX-License-Identifier: MIT
// The operator station's HTTP API (docs/server.md), through httplib's client against a server on
// an ephemeral port: every endpoint answers what the CLI's --json answers, and every bad request
// gets a 4xx JSON error naming what is wrong.
#include "sewerplan/server/station_server.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "sewerplan/core/text_file.h"

#include <httplib.h>

namespace sewerplan::server {
namespace {

using nlohmann::json;

const std::filesystem::path kSource = SEWERPLAN_SOURCE_DIR;
const std::filesystem::path kAis = kSource / "datasets/ais-testbed";

std::string read(const std::filesystem::path& path) { return *read_text_file(path); }

class StationServerTest : public ::testing::Test {
 protected:
  void start(ServerOptions options) {
    options.maps = {kAis / "map.json"};
    options.port = 0;
    Result<std::unique_ptr<StationServer>> created = StationServer::create(options);
    ASSERT_TRUE(created.has_value()) << created.error();
    server_ = std::move(*created);
    Result<int> port = server_->bind();
    ASSERT_TRUE(port.has_value()) << port.error();
    thread_ = std::thread([this] { server_->run(); });
    client_ = std::make_unique<httplib::Client>("127.0.0.1", *port);
    client_->set_read_timeout(120, 0);
  }
  void SetUp() override { start({}); }
  void TearDown() override {
    if (server_) server_->stop();
    if (thread_.joinable()) thread_.join();
  }

  // The status and the body as JSON (a 4xx body must be JSON too).
  std::pair<int, json> get(const std::string& path) {
    auto r = client_->Get(path.c_str());
    EXPECT_TRUE(r) << path;
    return {r->status, json::parse(r->body)};
  }
  std::pair<int, json> post(const std::string& path, const std::string& body) {
    auto r = client_->Post(path.c_str(), body, "application/json");
    EXPECT_TRUE(r) << path;
    return {r->status, json::parse(r->body)};
  }

  std::unique_ptr<StationServer> server_;
  std::thread thread_;
  std::unique_ptr<httplib::Client> client_;
};

TEST_F(StationServerTest, ListsItsMapsByIdAndTheBuiltInProfiles) {
  auto [status, j] = get("/api/maps");
  EXPECT_EQ(status, 200);
  ASSERT_EQ(j["maps"].size(), 1u);
  EXPECT_EQ(j["maps"][0]["id"], "map");
  EXPECT_EQ(j["maps"][0]["manholes"], 12);
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

TEST_F(StationServerTest, RefusesABodyOverTheSizeLimit) {
  TearDown();
  start({.max_body_bytes = 1000});
  auto [status, j] = post("/api/maps/map/validate", std::string(5000, ' '));
  EXPECT_EQ(status, 413);
  EXPECT_EQ(j["error"]["code"], "http-413");
}

TEST_F(StationServerTest, WithATokenRefusesApiRequestsWithoutIt) {
  TearDown();
  start({.token = "s3cret"});
  EXPECT_EQ(get("/api/maps").first, 401);
  client_->set_bearer_token_auth("wrong");
  EXPECT_EQ(get("/api/maps").first, 401);
  client_->set_bearer_token_auth("s3cret");
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

TEST_F(StationServerTest, StreamsASimulationsEventsAndItsReportThatReplayReadsBack) {
  const std::string body = R"({"mission": )" + read(kAis / "missions/paper.json") +
                           R"(, "faults": )" + read(kAis / "faults/blocked-p5.json") + "}";
  auto r = client_->Post("/api/maps/map/simulate", body, "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type"), "text/event-stream");
  EXPECT_NE(r->body.find("event: plan\n"), std::string::npos);
  EXPECT_NE(r->body.find("event: replan"), std::string::npos);  // P5 is blocked
  const auto report_at = r->body.find("event: report\ndata: ");
  ASSERT_NE(report_at, std::string::npos);
  const json report = json::parse(r->body.substr(report_at + 20));
  EXPECT_EQ(report["outcome"], "ended");
  EXPECT_GE(report["replans"].get<int>(), 1);
  // The data lines are the event log's JSON lines: replay reads them back, one event each.
  std::string log;
  std::size_t events = 0;
  for (std::size_t at = 0; (at = r->body.find("data: ", at)) < report_at; ++events) {
    const auto end = r->body.find('\n', at);
    log += r->body.substr(at + 6, end - at - 6) + "\n";
    at = end;
  }
  auto [status, replayed] = post("/api/maps/map/replay", log);
  EXPECT_EQ(status, 200);
  EXPECT_EQ(replayed["events"].size(), events);
}

TEST_F(StationServerTest, NamesTheMapThatCannotBeRead) {
  Result<std::unique_ptr<StationServer>> created =
      StationServer::create({.maps = {kAis / "no-such-map.json"}});
  ASSERT_FALSE(created.has_value());
  EXPECT_NE(created.error().message.find("no-such-map.json"), std::string::npos);
}

}  // namespace
}  // namespace sewerplan::server
