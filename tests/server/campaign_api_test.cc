// SPDX-License-Identifier: MIT
// The operator station's campaigns (docs/operator-station.md, "Campaigns"): started on the open map
// and mission, their progress streamed, cancelled, summarized by the campaign library's own
// summary.json, one at a time, and any run simulated again for the replay view; hostile requests
// get a 400 that names the field.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "sewerplan/campaign/campaign.h"
#include "sewerplan/campaign/summary.h"
#include "sewerplan/core/condition.h"
#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/map_io.h"

#include "campaign_service.h"
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
  refused({{"planner_time_limit_s", -1}}, "planner_time_limit_s");
  refused({{"planner_time_limit_s", 1e9}}, "planner_time_limit_s");
  refused({{"planner_time_limit_s", "soon"}}, "planner_time_limit_s");
  refused({{"timeout_s", 0}}, "timeout_s");
  refused({{"timeout_s", 1e9}}, "timeout_s");
  refused({{"timeout_s", "later"}}, "timeout_s");
  refused({{"risk", "reckless"}}, "risk");
  refused({{"risk", 1}}, "risk");
  refused({{"faults_from_condition", 1}}, "faults_from_condition");
  // The AIS map has no condition data: nothing to draw faults from.
  refused({{"faults_from_condition", true}}, "faults_from_condition");
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

// Condition data for a map, uploaded as the page does beside the map: the risk-aware execution and
// obstacles drawn from the findings, with a planner time limit, run as the campaign library runs
// them on the map joined with the same findings (`sewerplan campaign --condition --risk expected
// --faults-from-condition --planner-time-limit`).
TEST_F(CampaignApiTest, ManualRunsWithConditionDataRiskAndAPlannerTimeLimit) {
  const std::filesystem::path swmm = kSource / "datasets/swmm/swmmio-state-plane.inp";
  const std::filesystem::path condition = kSource / "datasets/condition/swmm-state-plane";
  // The library's map with the same findings.
  Diagnostics diagnostics;
  Result<SewerMap> map = read_map(swmm, diagnostics);
  ASSERT_TRUE(map.has_value());
  map = read_condition(std::move(*map), condition / "zustand.xml", diagnostics);
  ASSERT_TRUE(map.has_value());
  ASSERT_GT(map->finding_count(), 0u);
  start({.maps = {swmm}});
  const std::string mission_text = read(condition / "mission.json");
  json body = {{"mission", json::parse(mission_text)},
               {"runs", 2},
               {"seed", 5},
               {"risk", "expected"},
               {"faults_from_condition", true},
               {"planner_time_limit_s", 20},
               {"timeout_s", 300}};
  // Before the findings: nothing to draw faults from.
  auto [refused, why] = post("/api/maps/swmmio-state-plane/campaign", body.dump());
  EXPECT_EQ(refused, 400);
  EXPECT_NE(why["error"]["message"].get<std::string>().find("faults_from_condition"),
            std::string::npos);
  EXPECT_EQ(post("/api/maps/swmmio-state-plane/condition?name=z.xml", "<not isybau/>").first, 422);
  auto [uploaded, joined] = post("/api/maps/swmmio-state-plane/condition?name=zustand.xml",
                                 read(condition / "zustand.xml"));
  ASSERT_EQ(uploaded, 200) << joined.dump();
  EXPECT_EQ(joined["findings"], map->finding_count());
  // Again: it replaces the findings, not adds to them.
  EXPECT_EQ(post("/api/maps/swmmio-state-plane/condition?name=zustand.xml",
                 read(condition / "zustand.xml"))
                .second["findings"],
            map->finding_count());
  EXPECT_EQ(get("/api/maps").second["maps"][0]["findings"], map->finding_count());
  auto r = client_->Post("/api/maps/swmmio-state-plane/campaign", body.dump(), "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const auto stream = events(r->body);
  ASSERT_FALSE(stream.empty());
  EXPECT_EQ(stream.front().second["risk"], "expected");
  EXPECT_EQ(stream.front().second["faults_from_condition"], true);
  EXPECT_EQ(stream.front().second["planner_time_limit_s"], 20);
  EXPECT_EQ(stream.front().second["timeout_s"], 300);
  const json done = stream.back().second;
  ASSERT_EQ(done["runs"].size(), 2u);
  for (const json& run : done["runs"]) EXPECT_TRUE(run.contains("risk_aware")) << run.dump();

  Result<Mission> mission = read_mission(condition / "mission.json", *map, diagnostics);
  ASSERT_TRUE(mission.has_value()) << mission.error();
  close_findings(*map, *mission, RiskMode::kExpected, default_risk_table());
  campaign::CampaignSpec spec;
  spec.seed = 5;
  spec.runs = 2;
  spec.risk = "expected";
  spec.faults_from_condition = true;
  spec.planner_time_limit_s = 20;
  const auto records = campaign::run_campaign(*map, *mission, spec, {.guard = false});
  expect_same_runs(done["runs"], records, 2);
}

// The start event says what runs: unguarded, one job whatever was asked; guarded, at most one a
// run.
TEST_F(CampaignApiTest, ManualTheStartEventReportsTheJobsThatRun) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "needs 2 cores to ask for 2 jobs";
  start({.campaign_guard = false});
  auto r = client_->Post("/api/maps/map/campaign", request({{"runs", 3}, {"jobs", 2}}),
                         "application/json");
  ASSERT_TRUE(r);
  const auto unguarded = events(r->body);
  ASSERT_FALSE(unguarded.empty());
  EXPECT_EQ(unguarded.front().second["jobs"], 1);
  EXPECT_EQ(unguarded.front().second["jobs_requested"], 2);
#ifndef SEWERPLAN_TEST_FORK_UNSAFE_ALLOCATOR
  TearDown();
  start({});
  r = client_->Post("/api/maps/map/campaign", request({{"runs", 1}, {"jobs", 2}}),
                    "application/json");
  ASSERT_TRUE(r);
  const auto one_run = events(r->body);
  ASSERT_FALSE(one_run.empty());
  EXPECT_EQ(one_run.front().second["jobs"], 1);
  r = client_->Post("/api/maps/map/campaign", request({{"runs", 3}, {"jobs", 2}}),
                    "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(events(r->body).front().second["jobs"], 2);
#endif
}

// A reader that does not read: the stream's writes block until the test lets them go, as a
// stalled browser's socket does (for httplib's 5 s write timeout). The campaign goes on without it.
class CampaignStreamTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Diagnostics diagnostics;
    map_ = std::make_shared<const SewerMap>(*read_map(kAis / "map.json", diagnostics));
    mission_ = *read_mission(kAis / "missions/paper.json", *map_, diagnostics);
  }

  // Begins a campaign and streams it on a thread of its own into a reader that stalls.
  void begin(json fields) {
    fields["mission"] = json::parse(read(kAis / "missions/paper.json"));
    httplib::Response res;
    Diagnostics diagnostics;
    const std::optional<JsonDocument> body =
        JsonDocument::parse(fields.dump(), "body", diagnostics);
    ASSERT_TRUE(body) << diagnostics.error_summary();
    running_ = service_.begin(body->root(), map_, "map", mission_, res);
    ASSERT_TRUE(running_) << res.body;
    reader_ = std::thread([this] {
      service_.stream(running_, [this](std::string_view text) {
        std::unique_lock lock(mutex_);
        released_.wait(lock, [this] { return reading_; });
        written_ += text;
        return true;
      });
      service_.release(running_);
    });
  }
  // The reader reads again; its stream ends.
  void let_go() {
    {
      const std::lock_guard lock(mutex_);
      reading_ = true;
    }
    released_.notify_all();
    reader_.join();
  }
  json status() {
    httplib::Response res;
    service_.status(res);
    return json::parse(res.body);
  }
  // Polls status() until `done` says so: a generous bound that only a stuck campaign reaches.
  json wait_for(const std::function<bool(const json&)>& done) {
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    json s = status();
    while (!done(s) && std::chrono::steady_clock::now() < give_up) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      s = status();
    }
    return s;
  }
  void TearDown() override {
    if (reader_.joinable()) let_go();
  }

#ifdef SEWERPLAN_TEST_FORK_UNSAFE_ALLOCATOR
  static constexpr bool kGuard = false;
#else
  static constexpr bool kGuard = true;
#endif
  CampaignService service_{{.max_runs = 10000, .max_jobs = 2, .guard = kGuard}};
  std::shared_ptr<const SewerMap> map_;
  Mission mission_;
  std::shared_ptr<CampaignService::Running> running_;
  std::thread reader_;
  std::mutex mutex_;
  std::condition_variable released_;
  bool reading_ = false;
  std::string written_;
};

// Every run ends while the reader has not read the first event; then the stream has them all.
TEST_F(CampaignStreamTest, AReaderThatStallsHoldsUpNoRun) {
  begin({{"runs", 12u}, {"jobs", 2u}});
  const json s = wait_for([](const json& j) { return j["state"] != "running"; });
  EXPECT_EQ(s["state"], "done");
  EXPECT_EQ(s["runs"].size(), 12u);
  let_go();
  std::size_t progress = 0;
  std::vector<std::string> types;
  for (std::size_t at = 0; (at = written_.find("event: ", at)) != std::string::npos; ++at) {
    types.push_back(written_.substr(at + 7, written_.find('\n', at) - at - 7));
    progress += types.back() == "progress" ? 1U : 0U;
  }
  ASSERT_GE(types.size(), 2u);
  EXPECT_EQ(types.front(), "start");
  EXPECT_EQ(progress, 12u);
  EXPECT_EQ(types.back(), "summary");
}

// A cancel while the reader stalls stops the campaign: its summary is there before the reader
// reads again.
TEST_F(CampaignStreamTest, ACancelWhileTheReaderStallsStopsTheCampaign) {
  begin({{"runs", 5000u}, {"jobs", 2u}});
  wait_for([](const json& j) {
    return j["state"] != "running" || j.value("progress", json::object()).value("done", 0) >= 2;
  });
  httplib::Response res;
  service_.cancel(res);
  EXPECT_EQ(res.status, 200) << res.body;
  const json s = wait_for([](const json& j) { return j["state"] != "running"; });
  EXPECT_EQ(s["state"], "cancelled");
  EXPECT_GE(s["runs"].size(), 2u);
  EXPECT_LT(s["runs"].size(), 5000u);
  let_go();
  EXPECT_NE(written_.rfind("event: summary"), std::string::npos);
}

}  // namespace
}  // namespace sewerplan::server
