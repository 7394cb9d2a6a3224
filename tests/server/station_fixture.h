// SPDX-License-Identifier: MIT
// A station server on an ephemeral port with the AIS map, and httplib's client to it, for the API
// tests. A test whose name starts with "Manual" starts its own server (start(options)).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "sewerplan/core/text_file.h"
#include "sewerplan/server/station_server.h"
#if SEWERPLAN_TEST_WITH_GIS
#include "sewerplan/modules/gis.h"
#endif

#include "support/paths.h"
#include <httplib.h>

namespace sewerplan::server {

using nlohmann::json;

inline const std::filesystem::path kSource = sewerplan::testing::source_dir();
inline const std::filesystem::path kAis = kSource / "datasets/ais-testbed";

inline std::string read(const std::filesystem::path& path) { return *read_text_file(path); }

class StationFixture : public ::testing::Test {
 protected:
  void start(ServerOptions options) {
    if (options.maps.empty()) options.maps = {kAis / "map.json"};
#if SEWERPLAN_TEST_WITH_GIS
    // GDAL and PROJ as `sewerplan serve` gives them: through the GIS module.
    if (!options.gis.reproject && !options.gis.to_geojson) options.gis = modules::station_gis();
#endif
#ifdef SEWERPLAN_TEST_FORK_UNSAFE_ALLOCATOR
    // The test's own client threads allocate while a campaign forks its guarded children.
    options.campaign_guard = false;
#endif
    options.port = 0;
    Result<std::unique_ptr<StationServer>> created = StationServer::create(options);
    ASSERT_TRUE(created.has_value()) << created.error();
    server_ = std::move(*created);
    Result<int> port = server_->bind();
    ASSERT_TRUE(port.has_value()) << port.error();
    thread_ = std::thread([this] { server_->run(); });
    port_ = *port;
    client_ = std::make_unique<httplib::Client>("127.0.0.1", *port);
    client_->set_read_timeout(120, 0);
  }
  void SetUp() override {
    if (!std::string(::testing::UnitTest::GetInstance()->current_test_info()->name())
             .starts_with("Manual")) {
      start({});
    }
  }
  void TearDown() override {
    if (server_) server_->stop();
    if (thread_.joinable()) thread_.join();
  }

  // The status and the body as JSON (a 4xx body must be JSON too).
  std::pair<int, json> get(const std::string& path) {
    auto r = client_->Get(path.c_str());
    EXPECT_TRUE(r) << path;  // no answer: the test fails, the binary goes on
    if (!r) return {0, json()};
    return {r->status, json::parse(r->body, nullptr, false)};
  }
  std::pair<int, json> post(const std::string& path, const std::string& body) {
    auto r = client_->Post(path.c_str(), body, "application/json");
    EXPECT_TRUE(r) << path;  // no answer: the test fails, the binary goes on
    if (!r) return {0, json()};
    return {r->status, json::parse(r->body, nullptr, false)};
  }

  std::unique_ptr<StationServer> server_;
  std::thread thread_;
  std::unique_ptr<httplib::Client> client_;
  int port_ = 0;
};

}  // namespace sewerplan::server
