// SPDX-License-Identifier: MIT
// The operator station's campaigns (docs/operator-station.md, "Campaigns"): started on the open map
// and mission, their progress streamed, cancelled, summarized by the campaign library's own
// summary.json, one at a time, and any run simulated again for the replay view; hostile requests
// get a 400 that names the field.
#include <atomic>
#include <chrono>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "sewerplan/campaign/campaign.h"
#include "sewerplan/campaign/summary.h"
#include "sewerplan/core/map_io.h"

#include "station_fixture.h"

namespace sewerplan::server {
namespace {

class CampaignApiTest : public StationFixture {
 protected:
  // A campaign request on the paper's mission.
  static std::string request(json fields) {
    fields["mission"] = json::parse(read(kAis / "missions/paper.json"));
    return fields.dump();
  }

  // The station's runs equal the library's records of them, but for what is measured (times).
  static void expect_same_runs(const json& runs, const std::vector<campaign::RunRecord>& records,
                               std::size_t count) {
    ASSERT_GE(records.size(), count);
    for (std::size_t i = 0; i < count; ++i) {
      json line = json::parse(campaign::run_json_line(records[i]));
      json got = runs[i];
      line.erase("measured");
      got.erase("measured");
      EXPECT_EQ(got, line) << "run " << i;
    }
  }

  // The server-sent events of a finished stream: (type, data).
  static std::vector<std::pair<std::string, json>> events(const std::string& stream) {
    std::vector<std::pair<std::string, json>> out;
    std::istringstream in(stream);
    std::string type;
    for (std::string line; std::getline(in, line);) {
      if (line.starts_with("event: ")) type = line.substr(7);
      if (line.starts_with("data: ")) out.emplace_back(type, json::parse(line.substr(6)));
    }
    return out;
  }

  // Posts a campaign and reads its stream as it comes; `on_event(type, data)` returns false to
  // close the connection (a closed tab).
  void stream(const std::string& body,
              const std::function<bool(const std::string&, const json&)>& on_event) {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(300, 0);
    httplib::Request req;
    req.method = "POST";
    req.path = "/api/maps/map/campaign";
    req.body = body;
    req.set_header("Content-Type", "application/json");
    std::string buffer;
    req.content_receiver = [&](const char* data, std::size_t n, std::uint64_t, std::uint64_t) {
      buffer.append(data, n);
      for (std::size_t end; (end = buffer.find("\n\n")) != std::string::npos;) {
        const auto block = events(buffer.substr(0, end + 1));
        buffer.erase(0, end + 2);
        for (const auto& [type, data_json] : block) {
          if (!on_event(type, data_json)) return false;
        }
      }
      return true;
    };
    c.send(req);
  }
};

TEST_F(CampaignApiTest, StreamsItsProgressThenTheSummaryTheCampaignLibraryWrites) {
  auto r = client_->Post("/api/maps/map/campaign",
                         request({{"runs", 12},
                                  {"seed", 3},
                                  {"jobs", 1},
                                  {"fault_rates", {{"obstacles", 40}, {"passages", 0.05}}}}),
                         "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type"), "text/event-stream");
  const auto stream = events(r->body);
  ASSERT_GE(stream.size(), 14u);
  EXPECT_EQ(stream.front().first, "start");
  EXPECT_EQ(stream.front().second["total"], 12);
  EXPECT_EQ(stream.front().second["fault_rates"],
            "obstacles=40,danger=5,passages=0.05,malfunctions=0.5,permanent=0.1,transient=0.5");
  for (std::size_t k = 1; k <= 12; ++k) {
    ASSERT_EQ(stream[k].first, "progress");
    EXPECT_EQ(stream[k].second["done"], k);
    EXPECT_EQ(stream[k].second["total"], 12);
  }
  const json& last = stream[12].second;
  std::size_t outcomes = 0;
  for (const auto& [name, n] : last["outcomes"].items()) outcomes += n.get<std::size_t>();
  EXPECT_EQ(outcomes + last["failed"].get<std::size_t>(), 12u);
  ASSERT_EQ(stream.back().first, "summary");
  const json& done = stream.back().second;
  EXPECT_EQ(done["state"], "done");
  ASSERT_EQ(done["runs"].size(), 12u);

  // The same campaign through the library: the same runs and the same summary.json (but what is
  // measured).
  Diagnostics diagnostics;
  const SewerMap map = *read_map(kAis / "map.json", diagnostics);
  const Mission mission = *read_mission(kAis / "missions/paper.json", map, diagnostics);
  campaign::CampaignSpec spec;
  spec.map_name = "map";
  spec.mission_name = mission.name;
  spec.seed = 3;
  spec.runs = 12;
  spec.rates.obstacles_per_km = 40;
  spec.rates.passage_share = 0.05;
  const auto records = campaign::run_campaign(map, mission, spec, {.jobs = 2});
  std::ostringstream text;
  campaign::write_summary_json(campaign::summarize(spec, records), text);
  json expected = json::parse(text.str());
  json summary = done["summary"];
  for (json* j : {&expected, &summary}) {
    j->erase("measured");
    for (const char* policy : {"ours", "baseline"}) {
      (*j)[policy].erase("planning_ms_p50");
      (*j)[policy].erase("planning_ms_p99");
    }
  }
  EXPECT_EQ(summary, expected);
  expect_same_runs(done["runs"], records, 12);
  // The last campaign stays, for the page.
  auto [status, state] = get("/api/campaign");
  EXPECT_EQ(status, 200);
  EXPECT_EQ(state["state"], "done");
  EXPECT_EQ(state["summary"]["runs"], 12);
}

// A run of the campaign simulated again from its seed: the events the page replays, ending as the
// campaign recorded the run (tasks done, replans, outcome), each plan followed by its route.
TEST_F(CampaignApiTest, ReplaysAnyRunOfTheLastCampaignAsItsRecordSays) {
  EXPECT_EQ(get("/api/campaign/runs/0").first, 404);  // no campaign yet
  auto r = client_->Post(
      "/api/maps/map/campaign",
      request({{"runs", 6}, {"seed", "4"}, {"jobs", 1}, {"fault_rates", "obstacles=60"}}),
      "application/json");
  ASSERT_TRUE(r);
  const json done = events(r->body).back().second;
  ASSERT_EQ(done["runs"].size(), 6u);
  std::size_t replanned = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    for (const char* policy : {"ours", "baseline"}) {
      auto [status, j] =
          get("/api/campaign/runs/" + std::to_string(i) + "?policy=" + std::string(policy));
      ASSERT_EQ(status, 200) << j.dump();
      EXPECT_TRUE(j["same_as_record"]) << i << " " << policy;
      const json& recorded = done["runs"][i][policy];
      const json& events = j["events"];
      ASSERT_FALSE(events.empty());
      const json& end = events.back();
      EXPECT_EQ(end["type"], "mission_end");
      EXPECT_EQ(end["tasks_done"].size(), recorded["tasks"]);
      EXPECT_EQ(end["replans"], recorded["replans"]);
      std::size_t plans = 0;
      std::size_t routes = 0;
      for (std::size_t k = 0; k < events.size(); ++k) {
        const std::string type = events[k]["type"];
        if (type == "plan" || type == "replan") {
          ++plans;
          ASSERT_LT(k + 1, events.size());
          EXPECT_EQ(events[k + 1]["type"], "route");
        }
        if (type == "route") ++routes;
      }
      EXPECT_EQ(plans, routes);
      EXPECT_EQ(plans, recorded["replans"].get<std::size_t>() + 1);
      if (recorded["replans"].get<std::size_t>() > 0) ++replanned;
    }
  }
  EXPECT_GT(replanned, 0u) << "no run replanned: the replay was not put to the test";
  EXPECT_EQ(get("/api/campaign/runs/6").first, 404);
  EXPECT_EQ(get("/api/campaign/runs/abc").first, 400);
  EXPECT_EQ(get("/api/campaign/runs/99999999999999999999999").first, 400);
  EXPECT_EQ(get("/api/campaign/runs/1?policy=oracle").first, 400);
  EXPECT_EQ(get("/api/campaign/runs/1?policy=risk_aware").first, 400);
}

TEST_F(CampaignApiTest, RefusesHostileRequestsWithA400NamingTheField) {
  const auto refused = [&](json fields, const std::string& named) {
    auto [status, j] = post("/api/maps/map/campaign", request(std::move(fields)));
    EXPECT_EQ(status, 400) << named;
    const std::string message = j["error"]["message"];
    EXPECT_NE(message.find(named), std::string::npos) << message;
  };
  refused({{"runs", 1000000000}}, "runs");
  refused({{"runs", 0}}, "runs");
  refused({{"runs", -5}}, "runs");
  refused({{"runs", 2.5}}, "runs");
  refused({{"runs", "many"}}, "runs");
  refused({{"seed", -3}}, "seed");
  refused({{"seed", "12x"}}, "seed");
  refused({{"jobs", 100000}}, "jobs");
  refused({{"jobs", 0}}, "jobs");
  refused({{"fault_rates", {{"obstacles", -1}}}}, "obstacles");
  refused({{"fault_rates", {{"obstacles", "lots"}}}}, "fault_rates.obstacles");
  refused({{"fault_rates", {{"meteors", 1}}}}, "fault_rates.meteors");
  refused({{"fault_rates", "permanent=2"}}, "permanent");
  refused({{"fault_rates", 7}}, "fault_rates");
  refused({{"allow_push", "yes"}}, "allow_push");
  refused({{"runs", 3}, {"evil", true}}, "evil");
  EXPECT_EQ(post("/api/maps/map/campaign", "[1]").first, 400);
  EXPECT_EQ(post("/api/maps/map/campaign", R"({"runs": 3})").first, 400);  // no mission
  EXPECT_EQ(post("/api/maps/map/campaign", R"({"mission": {"format": "x"}})").first, 422);
  EXPECT_EQ(post("/api/maps/nowhere/campaign", request({})).first, 404);
  EXPECT_EQ(post("/api/campaign/cancel", "").first, 409);  // none runs
  EXPECT_EQ(get("/api/campaign").second["state"], "none");
}

// Cancel while it runs: the stream ends with the summary of the runs that finished; meanwhile a
// second campaign is refused (one at a time) and, once it has ended, accepted.
TEST_F(CampaignApiTest, CancelsARunningCampaignAndRunsOneAtATime) {
  bool cancelled = false;
  json summary;
  stream(request({{"runs", 2000}, {"jobs", 1}}), [&](const std::string& type, const json& data) {
    if (type == "progress" && !cancelled) {
      httplib::Client other("127.0.0.1", port_);
      auto second =
          other.Post("/api/maps/map/campaign", request({{"runs", 2}}), "application/json");
      EXPECT_TRUE(second && second->status == 409);
      auto state = other.Get("/api/campaign");
      EXPECT_TRUE(state && json::parse(state->body)["state"] == "running");
      auto cancel = other.Post("/api/campaign/cancel", "", "application/json");
      EXPECT_TRUE(cancel && cancel->status == 200);
      cancelled = true;
    }
    if (type == "summary") summary = data;
    return true;
  });
  ASSERT_TRUE(cancelled);
  EXPECT_EQ(summary["state"], "cancelled");
  EXPECT_LT(summary["runs"].size(), 2000u);
  EXPECT_EQ(summary["summary"]["runs"], summary["runs"].size());
  EXPECT_EQ(post("/api/campaign/cancel", "").first, 409);
  auto r = client_->Post("/api/maps/map/campaign", request({{"runs", 2}}), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(events(r->body).back().second["state"], "done");
}

// A closed tab cancels its campaign: the next campaign is accepted once the stream has noticed.
TEST_F(CampaignApiTest, AClosedStreamCancelsItsCampaign) {
  stream(request({{"runs", 5000}, {"jobs", 1}}),
         [&](const std::string& type, const json&) { return type != "progress"; });
  // The server notices at its next write, after the run in progress: wait for it.
  // (Bounded: a server that never notices fails the test instead of spinning until ctest's
  // timeout.)
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (get("/api/campaign").second["state"] == "running" &&
         std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  auto [status, state] = get("/api/campaign");
  EXPECT_EQ(state["state"], "cancelled");
  EXPECT_LT(state["runs"].size(), 5000u);
}

// Stopping the server stops its campaign (else it would wait for 5,000 runs).
TEST_F(CampaignApiTest, StoppingTheServerStopsItsCampaign) {
  json summary;
  stream(request({{"runs", 5000}, {"jobs", 1}}), [&](const std::string& type, const json& data) {
    if (type == "progress" && data["done"] == 1) server_->stop();
    if (type == "summary") summary = data;
    return true;
  });
  TearDown();
  EXPECT_EQ(summary["state"], "cancelled");
  EXPECT_LT(summary["runs"].size(), 5000u);
}

// Unguarded (ServerOptions::campaign_guard, for the sanitizer build): the same runs, and a cancel
// between runs.
TEST_F(CampaignApiTest, ManualRunsUnguardedWithTheSameRunsAndStopsBetweenThem) {
  start({.campaign_guard = false});
  auto r = client_->Post("/api/maps/map/campaign", request({{"runs", 4}, {"seed", 3}}),
                         "application/json");
  ASSERT_TRUE(r);
  const json done = events(r->body).back().second;
  ASSERT_EQ(done["runs"].size(), 4u);
  Diagnostics diagnostics;
  const SewerMap map = *read_map(kAis / "map.json", diagnostics);
  const Mission mission = *read_mission(kAis / "missions/paper.json", map, diagnostics);
  campaign::CampaignSpec spec;
  spec.seed = 3;
  spec.runs = 4;
  const auto guarded = campaign::run_campaign(map, mission, spec, {});
  expect_same_runs(done["runs"], guarded, 4);
  json summary;
  stream(request({{"runs", 5000}}), [&](const std::string& type, const json& data) {
    if (type == "progress" && data["done"] == 1) {
      httplib::Client other("127.0.0.1", port_);
      EXPECT_TRUE(other.Post("/api/campaign/cancel", "", "application/json"));
    }
    if (type == "summary") summary = data;
    return true;
  });
  EXPECT_EQ(summary["state"], "cancelled");
  EXPECT_LT(summary["runs"].size(), 5000u);
}

}  // namespace
}  // namespace sewerplan::server
