// SPDX-License-Identifier: MIT
#include "sewerplan/campaign/campaign.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "sewerplan/campaign/merge.h"
#include "sewerplan/campaign/summary.h"
#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_json.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/domain/mission_generator.h"
#include "sewerplan/executor/events.h"

#include "support/ais_testbed.h"
#include "support/enum_round_trip.h"

namespace sewerplan::campaign {
namespace {

namespace fs = std::filesystem;

CampaignSpec ais_spec(std::size_t runs, std::uint64_t seed = 1) {
  CampaignSpec spec;
  spec.map_name = "datasets/ais-testbed/map.json";
  spec.mission_name = "datasets/ais-testbed/missions/paper.json";
  spec.map_fingerprint = "0000000000000001";
  spec.mission_fingerprint = "0000000000000002";
  spec.seed = seed;
  spec.runs = runs;
  return spec;
}

// Run `run` of a campaign of `runs` runs in the realistic world (issue 29), seed `seed`: what a
// scan found a run to do, replayed.
Result<RunResult> realistic_run(const SewerMap& map, const Mission& mission, std::size_t runs,
                                std::uint64_t seed, std::size_t run) {
  CampaignSpec spec = ais_spec(runs, seed);
  spec.world_errors = "realistic";
  return run_one(map, mission, run_settings(spec), run);
}

// The deterministic part of a record's line: all but the trailing "measured" object.
std::string fixed_part(const RunRecord& r) {
  const std::string line = run_json_line(r);
  return line.substr(0, line.find(",\"measured\":"));
}

std::vector<std::string> fixed_parts(const std::vector<RunRecord>& records) {
  std::vector<std::string> out;
  for (const RunRecord& r : records) out.push_back(fixed_part(r));
  return out;
}

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("sewerplan-campaign-test-" + name);
  fs::remove_all(dir);
  return dir;
}

TEST(CampaignNames, EveryValueRoundTripsThroughItsNameAndBack) {
  testing::expect_round_trip(
      {Outcome::kExit, Outcome::kEndPoint, Outcome::kBeacon, Outcome::kStranded},
      outcome_from_string);
  testing::expect_round_trip({Policy::kOurs, Policy::kBaseline, Policy::kRiskAware},
                             policy_from_string);
}

TEST(Campaign, TheSameSeedGivesTheSameRunsWithAnyNumberOfJobs) {
  const auto ais = testing::load_ais_testbed();
  const CampaignSpec spec = ais_spec(12);
  const auto one = run_campaign(ais.map, ais.mission, spec, {.jobs = 1});
  const auto two = run_campaign(ais.map, ais.mission, spec, {.jobs = 2});
  ASSERT_EQ(one.size(), 12U);
  EXPECT_EQ(fixed_parts(one), fixed_parts(two));
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].index, i);
    EXPECT_EQ(one[i].status, RunRecord::Status::kOk) << one[i].detail;
  }
  // Another seed, other faults.
  const auto other = run_campaign(ais.map, ais.mission, ais_spec(12, 2), {.jobs = 1});
  EXPECT_NE(fixed_parts(one), fixed_parts(other));
}

TEST(Campaign, OneRunAloneEqualsItsLineInTheCampaign) {
  const auto ais = testing::load_ais_testbed();
  const CampaignSpec spec = ais_spec(8);
  const auto all = run_campaign(ais.map, ais.mission, spec, {});
  for (std::size_t k : {0U, 5U, 7U}) {
    const auto alone = run_campaign(ais.map, ais.mission, spec, {.only = k});
    ASSERT_EQ(alone.size(), 1U);
    EXPECT_EQ(fixed_part(alone.front()), fixed_part(all[k]));
    // Unguarded, in this process: the same.
    const auto in_process = run_campaign(ais.map, ais.mission, spec, {.guard = false, .only = k});
    EXPECT_EQ(fixed_part(in_process.front()), fixed_part(all[k]));
  }
}

// A robot that ends in an exit the mission names is out, whether or not the map marks that manhole
// an exit: the campaign read the map's flag, so on the official ISYBAU sample, with a mission whose
// exits are a pump station and dead ends the map does not mark, 35 of 40 runs that ended in such an
// exit were counted "stranded" and the campaign was not clean.
TEST(Campaign, ARunEndingInAnExitOfTheMissionEndsAtAnExitWhateverTheMapMarks) {
  const auto ais = testing::load_ais_testbed();
  Mission mission = ais.mission;
  mission.tasks.clear();
  const ManholeId m2 = *ais.map.find_manhole("M2");
  ASSERT_FALSE(ais.map.manhole(m2).exit);
  mission.exits = {m2};
  RunSettings settings;
  settings.rates = *parse_fault_rates("obstacles=0,danger=0,passages=0,malfunctions=0");
  const Result<RunResult> run = run_one(ais.map, mission, settings, 0);
  ASSERT_TRUE(run.has_value()) << run.error();
  EXPECT_EQ(run->ours.end, "exit M2");
  EXPECT_EQ(run->ours.outcome, Outcome::kExit);
  EXPECT_EQ(run->baseline.outcome, Outcome::kExit);
}

// The oracle knows every fault that stays in advance and plans optimally on the AIS mission (A*),
// so no policy does more tasks; and wherever it can end the mission, our robot ends it too.
TEST(Campaign, TheOracleBoundsOursAndEveryRunThatCanEndEnds) {
  const auto ais = testing::load_ais_testbed();
  CampaignSpec spec = ais_spec(60, 3);
  spec.rates.obstacles_per_km = 40;
  spec.rates.passage_share = 0.05;
  const auto records = run_campaign(ais.map, ais.mission, spec, {.jobs = 2});
  std::size_t could = 0;
  for (const RunRecord& r : records) {
    ASSERT_TRUE(r.result) << r.index << ": " << r.detail;
    const RunResult& x = *r.result;
    if (x.oracle_can_end) {
      EXPECT_LE(x.ours.tasks, x.oracle_tasks) << run_json_line(r);
      EXPECT_LE(x.baseline.tasks, x.oracle_tasks) << run_json_line(r);
    }
    EXPECT_TRUE(x.ours.reserve_kept) << run_json_line(r);
    EXPECT_NE(x.ours.outcome, Outcome::kStranded) << run_json_line(r);
    if (x.could_reach_exit) {
      ++could;
      EXPECT_TRUE(x.ours.outcome == Outcome::kExit || x.ours.outcome == Outcome::kEndPoint)
          << run_json_line(r);
    }
  }
  EXPECT_GT(could, 30U);
  const Summary s = summarize(spec, records);
  EXPECT_EQ(s.oracle_below_ours, 0U);
  EXPECT_GE(s.ours.vs_oracle_mean, s.baseline.vs_oracle_mean);
  EXPECT_TRUE(s.clean());
}

// Issue 14: beacons by cause sum to "ended: beacon". A robot that breaks down at an exit manhole
// calls for recovery, yet ends `exit` (it is where it can be recovered): it is counted apart, and
// a limit there still makes the campaign unclean.
TEST(Campaign, BeaconsByCauseSumToTheBeaconOutcome) {
  using Cause = executor::MissionReport::BeaconCause;
  auto record = [](std::size_t index, Outcome outcome, Cause cause) {
    RunResult x;
    x.index = index;
    x.ours.outcome = outcome;
    x.ours.beacon_cause = cause;
    return RunRecord{.index = index, .result = x};
  };
  std::vector<RunRecord> records{record(0, Outcome::kBeacon, Cause::kMalfunction),
                                 record(1, Outcome::kExit, Cause::kMalfunction),
                                 record(2, Outcome::kExit, Cause::kNone)};
  const Summary s = summarize(ais_spec(3), records);
  const auto n = [](const auto& counts, auto i) { return counts[static_cast<std::size_t>(i)]; };
  std::size_t by_cause = 0;
  for (std::size_t c = 1; c < s.ours.beacon_causes.size(); ++c) by_cause += s.ours.beacon_causes[c];
  EXPECT_EQ(by_cause, n(s.ours.outcomes, Outcome::kBeacon));
  EXPECT_EQ(n(s.ours.beacon_causes, Cause::kMalfunction), 1U);
  EXPECT_EQ(n(s.ours.ended_otherwise_beacon_causes, Cause::kMalfunction), 1U);
  EXPECT_EQ(n(s.ours.outcomes, Outcome::kExit), 2U);
  std::ostringstream md;
  write_summary_markdown(s, md);
  EXPECT_THAT(md.str(), ::testing::HasSubstr("| beacon called, run ended otherwise | 1 |"));
  EXPECT_TRUE(s.clean());
  records.push_back(record(3, Outcome::kExit, Cause::kLimit));
  EXPECT_FALSE(summarize(ais_spec(4), records).clean());
}

TEST(Campaign, ShardsMergeIntoTheWholeCampaign) {
  const auto ais = testing::load_ais_testbed();
  const CampaignSpec whole = ais_spec(10);
  const auto all = run_campaign(ais.map, ais.mission, whole, {});
  std::vector<fs::path> dirs;
  for (std::size_t i = 0; i < 3; ++i) {
    CampaignSpec shard = whole;
    shard.shard_index = i;
    shard.shard_count = 3;
    const auto part = run_campaign(ais.map, ais.mission, shard, {});
    for (const RunRecord& r : part) EXPECT_EQ(r.index % 3, i);
    dirs.push_back(temp_dir("shard-" + std::to_string(i)));
    ASSERT_TRUE(write_campaign_dir(dirs.back(), shard, part).has_value());
  }
  // In any order.
  Result<MergedCampaign> merged = merge_shards({dirs[2], dirs[0], dirs[1]});
  ASSERT_TRUE(merged.has_value()) << merged.error().message;
  EXPECT_EQ(fixed_parts(merged->records), fixed_parts(all));
  EXPECT_EQ(merged->spec.shard_count, 1U);
  // Its summary equals the unsharded one in everything not measured.
  std::ostringstream a;
  std::ostringstream b;
  write_summary_markdown(summarize(whole, all), a);
  write_summary_markdown(summarize(merged->spec, merged->records), b);
  auto cut = [](const std::string& s) {
    std::string out;
    std::istringstream in(s);
    for (std::string line; std::getline(in, line);) {
      if (line.find("measured") == std::string::npos) out += line + "\n";
    }
    return out;
  };
  EXPECT_EQ(cut(a.str()), cut(b.str()));

  // Rejected: a shard twice, a shard missing, another campaign, a lost line.
  Result<MergedCampaign> twice = merge_shards({dirs[0], dirs[1], dirs[1], dirs[2]});
  ASSERT_FALSE(twice.has_value());
  EXPECT_NE(twice.error().message.find("shard 1/3 given twice"), std::string::npos)
      << twice.error().message;
  Result<MergedCampaign> missing = merge_shards({dirs[0], dirs[2]});
  ASSERT_FALSE(missing.has_value());
  EXPECT_NE(missing.error().message.find("shard(s) 1 of 3 missing"), std::string::npos)
      << missing.error().message;

  CampaignSpec other = whole;
  other.seed = 99;
  other.shard_count = 3;
  other.shard_index = 1;
  const fs::path foreign = temp_dir("foreign");
  ASSERT_TRUE(write_campaign_dir(foreign, other, run_campaign(ais.map, ais.mission, other, {}))
                  .has_value());
  Result<MergedCampaign> mixed = merge_shards({dirs[0], foreign, dirs[2]});
  ASSERT_FALSE(mixed.has_value());
  EXPECT_NE(mixed.error().message.find("the seed differs"), std::string::npos)
      << mixed.error().message;

  {
    // Drop the last line of shard 2.
    std::ifstream in(dirs[2] / "runs.jsonl");
    std::string first;
    std::getline(in, first);
    in.close();
    std::ofstream(dirs[2] / "runs.jsonl") << first << '\n';
  }
  Result<MergedCampaign> lost = merge_shards({dirs[0], dirs[1], dirs[2]});
  ASSERT_FALSE(lost.has_value());
  EXPECT_NE(lost.error().message.find("2 run(s) missing: 5, 8"), std::string::npos)
      << lost.error().message;
  {
    // A line of another shard.
    std::ofstream(dirs[2] / "runs.jsonl") << run_json_line(all[1]) << '\n';
  }
  Result<MergedCampaign> stray = merge_shards({dirs[0], dirs[1], dirs[2]});
  ASSERT_FALSE(stray.has_value());
  EXPECT_NE(stray.error().message.find("runs.jsonl:1: run 1 does not belong to shard 2/3"),
            std::string::npos)
      << stray.error().message;
}

TEST(Campaign, ACrashOrAHangIsCaughtCountedAndReproducible) {
  const auto ais = testing::load_ais_testbed();
  const CampaignSpec spec = ais_spec(6);
  // A limit well above a run's time even in a loaded sanitizer build, so only the hang hits it: the
  // slowest other run there is the crash, whose sanitizer report takes up to 1 s. The hang waits
  // it out, so the test takes this long.
  CampaignOptions options{.jobs = 2, .timeout_s = 5};
  options.inject = {{2, InjectedFault::kCrash}, {4, InjectedFault::kHang}};
  const auto records = run_campaign(ais.map, ais.mission, spec, options);
  ASSERT_EQ(records.size(), 6U);
  EXPECT_EQ(records[2].status, RunRecord::Status::kCrash);
  EXPECT_EQ(records[4].status, RunRecord::Status::kHang);
  EXPECT_FALSE(records[2].result);
  EXPECT_EQ(records[2].seed, run_seed(1, 2));
  for (std::size_t i : {0U, 1U, 3U, 5U}) EXPECT_EQ(records[i].status, RunRecord::Status::kOk);
  const Summary s = summarize(spec, records);
  EXPECT_FALSE(s.clean());
  ASSERT_EQ(s.failed.size(), 2U);
  EXPECT_EQ(s.failed[0].run, 2U);
  EXPECT_EQ(s.failed[0].status, RunRecord::Status::kCrash);
  EXPECT_NE(s.failed[0].command.find("--seed 1 "), std::string::npos);
  EXPECT_NE(s.failed[0].command.find("--only 2"), std::string::npos);
  EXPECT_EQ(s.failed[1].status, RunRecord::Status::kHang);
  EXPECT_EQ(s.completed, 4U);
  // A failed run's line reads back.
  Result<RunRecord> back = parse_run_line(run_json_line(records[4]), "runs.jsonl", 5);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->status, RunRecord::Status::kHang);
  EXPECT_EQ(back->seed, records[4].seed);
}

// A cancel from the progress callback (as the station's cancel button, from another thread): no run
// starts after it, and a child still running is killed at once. Run 0 hangs for ever (far beyond
// any test's time limit): without the stop, the campaign would wait for its hour-long timeout.
TEST(Campaign, ACancelStopsTheCampaignAndKillsTheRunInProgress) {
  const auto ais = testing::load_ais_testbed();
  const CampaignSpec spec = ais_spec(40);
  std::atomic<bool> cancel{false};
  CampaignOptions options{.jobs = 2, .timeout_s = 3600};
  options.inject = {{0, InjectedFault::kHang}};
  options.stop = StopCondition().with_cancel(cancel);
  std::size_t seen = 0;
  options.progress = [&](const Progress& p) {
    ASSERT_NE(p.last, nullptr);
    EXPECT_EQ(p.last->status, RunRecord::Status::kOk);
    ++seen;
    if (p.done == 3) cancel = true;
  };
  const auto records = run_campaign(ais.map, ais.mission, spec, options);
  // The runs that finished, in index order, each as the campaign without a cancel has it; not the
  // hung run 0.
  ASSERT_EQ(records.size(), seen);
  EXPECT_GE(records.size(), 3U);
  EXPECT_LT(records.size(), 40U);
  const auto whole = run_campaign(ais.map, ais.mission, ais_spec(6), {.jobs = 2});
  for (std::size_t k = 0; k < records.size(); ++k) {
    EXPECT_NE(records[k].index, 0U);
    if (k > 0) {
      EXPECT_LT(records[k - 1].index, records[k].index);
    }
    if (records[k].index < whole.size()) {
      EXPECT_EQ(fixed_part(records[k]), fixed_part(whole[records[k].index]));
    }
  }
}

// A clock for a stop condition's deadline that reads 0 until fired, then far beyond it, and counts
// how often it was read since: each read is a worker checking whether to stop.
class FiringClock final : public Clock {
 public:
  double now_s() const override {
    if (!fired) return 0;
    ++reads_since;
    return 1e9;
  }
  std::atomic<bool> fired{false};
  mutable std::atomic<std::size_t> reads_since{0};
};

// The progress callback runs on the caller's thread under no lock of the campaign's: while it is
// held up, the workers still check the stop condition, and the one waiting on a hung child kills
// it (run 1 would otherwise wait out its hour-long timeout). Before, the callback ran with the
// workers' lock held, and no worker checked anything until it returned (the station's campaign
// stalled behind a browser that did not read its stream).
TEST(Campaign, AStopIsHonouredWhileTheProgressCallbackIsHeldUp) {
  const auto ais = testing::load_ais_testbed();
  FiringClock clock;
  CampaignOptions options{.jobs = 2, .timeout_s = 3600};
  options.inject = {{1, InjectedFault::kHang}};
  options.stop = StopCondition::at_deadline(clock, 1.0);
  const auto caller = std::this_thread::get_id();
  std::size_t calls = 0;
  bool checked = false;
  options.progress = [&](const Progress& p) {
    EXPECT_EQ(std::this_thread::get_id(), caller);
    ASSERT_NE(p.last, nullptr);
    EXPECT_NE(p.last->index, 1U);
    if (calls++ > 0) return;
    clock.fired = true;
    // Both workers check the stop while this call is held up; a generous bound, not a timing.
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (clock.reads_since < 2 && std::chrono::steady_clock::now() < give_up) {
      std::this_thread::yield();
    }
    checked = clock.reads_since >= 2;
  };
  const auto records = run_campaign(ais.map, ais.mission, ais_spec(40), options);
  EXPECT_TRUE(checked) << "no worker checked the stop while the callback ran";
  ASSERT_EQ(records.size(), calls);  // every finished run reported, the hung one not finished
  EXPECT_GE(records.size(), 1U);
  EXPECT_LT(records.size(), 40U);
  for (const RunRecord& r : records) EXPECT_NE(r.index, 1U);
}

// What runs: the jobs asked for, at most one per run of the shard, and one unguarded.
TEST(Campaign, CampaignJobsAreWhatRuns) {
  CampaignSpec spec = ais_spec(5);
  EXPECT_EQ(campaign_jobs(spec, {.jobs = 4}), 4U);
  EXPECT_EQ(campaign_jobs(spec, {.jobs = 8}), 5U);
  EXPECT_EQ(campaign_jobs(spec, {.jobs = 4, .guard = false}), 1U);
  EXPECT_EQ(campaign_jobs(spec, {.jobs = 4, .only = 3}), 1U);
  spec.shard_index = 1;
  spec.shard_count = 3;  // runs 1 and 4
  EXPECT_EQ(campaign_jobs(spec, {.jobs = 4}), 2U);
  spec.runs = 0;
  EXPECT_EQ(campaign_jobs(spec, {.jobs = 4}), 1U);
}

TEST(Campaign, AStopUnguardedEndsBetweenRuns) {
  const auto ais = testing::load_ais_testbed();
  std::atomic<bool> cancel{false};
  CampaignOptions options{.guard = false};
  options.stop = StopCondition().with_cancel(cancel);
  options.progress = [&](const Progress& p) { cancel = p.done == 2; };
  const auto records = run_campaign(ais.map, ais.mission, ais_spec(10), options);
  ASSERT_EQ(records.size(), 2U);
  EXPECT_EQ(records[1].index, 1U);
}

// A run's execution simulated again from its seed (the station's replay of a campaign run) is the
// one the campaign recorded, event by event to its end, for ours and the baseline.
TEST(Campaign, AnExecutionReplayedFromItsSeedEqualsTheRunsRecord) {
  const auto ais = testing::load_ais_testbed();
  CampaignSpec spec = ais_spec(10, 4);
  spec.rates.obstacles_per_km = 60;
  const auto records = run_campaign(ais.map, ais.mission, spec, {.jobs = 2});
  const RunSettings settings = run_settings(spec);
  std::size_t replanned = 0;
  for (const RunRecord& r : records) {
    ASSERT_TRUE(r.result) << r.detail;
    for (Policy policy : {Policy::kOurs, Policy::kBaseline}) {
      std::vector<executor::Event> events;
      std::size_t plans = 0;
      ExecutionObservers observers{
          .on_event = [&](const executor::Event& e) { events.push_back(e); },
          .on_plan = [&](const executor::PlanResponse&) { ++plans; }};
      Result<Execution> again =
          replay_execution(ais.map, ais.mission, settings, r.index, policy, observers);
      ASSERT_TRUE(again.has_value()) << again.error();
      Execution recorded = policy == Policy::kOurs ? r.result->ours : r.result->baseline;
      recorded.planning_times_s.clear();
      EXPECT_EQ(again->planning_times_s.size(), plans);
      again->planning_times_s.clear();
      EXPECT_EQ(*again, recorded) << to_string(policy) << " of " << run_json_line(r);
      ASSERT_FALSE(events.empty());
      const auto* end = std::get_if<executor::MissionEndEvent>(&events.back().what);
      ASSERT_NE(end, nullptr) << "the last event is not the mission's end";
      EXPECT_EQ(end->tasks_done.size(), recorded.tasks);
      EXPECT_EQ(end->replans, recorded.replans);
      if (policy == Policy::kOurs && recorded.replans > 0) ++replanned;
    }
  }
  EXPECT_GT(replanned, 0U) << "no run replanned: the replay was not put to the test";
  EXPECT_FALSE(
      replay_execution(ais.map, ais.mission, settings, 0, Policy::kRiskAware, {}).has_value());
  EXPECT_EQ(policy_from_string("baseline"), Policy::kBaseline);
  EXPECT_FALSE(policy_from_string("oracle"));
}

TEST(Campaign, RecordsReadBackAndBadLinesNameFileLineAndField) {
  const auto ais = testing::load_ais_testbed();
  const auto records = run_campaign(ais.map, ais.mission, ais_spec(3), {});
  for (const RunRecord& r : records) {
    Result<RunRecord> back = parse_run_line(run_json_line(r), "runs.jsonl", r.index + 1);
    ASSERT_TRUE(back.has_value()) << back.error().message;
    EXPECT_EQ(run_json_line(*back), run_json_line(r));
  }
  // Every status reads back as itself (an ok run's above); a status not ours is an error.
  for (RunRecord::Status status : {RunRecord::Status::kCrash, RunRecord::Status::kHang}) {
    const RunRecord failed{.index = 1, .seed = 7, .status = status, .detail = "x", .wall_s = 1};
    Result<RunRecord> back = parse_run_line(run_json_line(failed), "runs.jsonl", 2);
    ASSERT_TRUE(back.has_value()) << back.error().message;
    EXPECT_EQ(*back, failed) << run_json_line(failed);
  }
  Result<RunRecord> bad = parse_run_line(
      R"({"run": 1, "seed": "1", "status": "lost", "measured": {"wall_s": 1}})", "runs.jsonl", 6);
  ASSERT_FALSE(bad.has_value());
  EXPECT_THAT(bad.error().message,
              ::testing::HasSubstr("runs.jsonl:6:$.status: error: unknown status 'lost'"));
  bad = parse_run_line("{\"run\": 1}", "runs.jsonl", 7);
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().message,
            "runs.jsonl:7:$: error: missing required field 'seed'\n"
            "runs.jsonl:7:$: error: missing required field 'status'\n"
            "runs.jsonl:7:$: error: missing required field 'measured'");
  bad = parse_run_line("[1", "runs.jsonl", 2);
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().message, "runs.jsonl:2: not a JSON object");
  bad = parse_run_line(R"({"run": -1, "seed": "1"})", "r", 1);
  ASSERT_FALSE(bad.has_value());
  EXPECT_THAT(bad.error().message,
              ::testing::StartsWith(
                  "r:1:$.run: error: expected a whole number from 0 to 9007199254740992, got -1"));
  // A record's field given twice is refused, not read as one of the two.
  std::string twice = run_json_line(records[0]);
  twice.insert(twice.find("\"status\""), "\"status\":\"crash\",");
  bad = parse_run_line(twice, "runs.jsonl", 3);
  ASSERT_FALSE(bad.has_value());
  EXPECT_THAT(bad.error().message,
              ::testing::HasSubstr("runs.jsonl:3:$.status: error: field 'status' given twice"));
  std::string nested = run_json_line(records[0]);
  nested.replace(nested.find("\"outcome\":\""), 11, "\"outcome\":\"x");
  bad = parse_run_line(nested, "runs.jsonl", 4);
  ASSERT_FALSE(bad.has_value());
  EXPECT_THAT(bad.error().message, ::testing::HasSubstr("runs.jsonl:4:$.ours.outcome: error: "
                                                        "unknown outcome 'x"));
  // A duration the writer's rounding would turn into infinity (written as null) is refused, so a
  // record that reads also reads back as written.
  bad = parse_run_line(R"({"run":0,"seed":"0","status":"crash","measured":{"wall_s":1e305}})",
                       "runs.jsonl", 5);
  ASSERT_FALSE(bad.has_value());
  EXPECT_THAT(bad.error().message,
              ::testing::HasSubstr("runs.jsonl:5:$.measured.wall_s: error: out of range"));
}

TEST(Campaign, ABadCampaignFileNamesEveryBadFieldByJsonPath) {
  CampaignSpec spec = ais_spec(4);
  spec.shard_index = 1;
  spec.shard_count = 2;
  const std::string good = campaign_json(spec);
  Result<CampaignSpec> back = parse_campaign_json(good, "campaign.json");
  ASSERT_TRUE(back.has_value()) << back.error().message;
  EXPECT_TRUE(back->same_campaign(spec));
  EXPECT_EQ(back->shard_index, 1U);

  auto edited = [](std::string text, const std::string& from, const std::string& to) {
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  std::string bad = edited(good, "\"runs\": 4", "\"runs\": 4.5");
  bad = edited(bad, "\"index\": 1", "\"index\": 2");
  bad = edited(bad, "\"seed\": \"", "\"seed\": \"-");
  Result<CampaignSpec> refused = parse_campaign_json(bad, "campaign.json");
  ASSERT_FALSE(refused.has_value());
  const std::string& e = refused.error().message;
  EXPECT_THAT(e, ::testing::HasSubstr("campaign.json:$.runs: error: expected a whole number"));
  EXPECT_THAT(e, ::testing::HasSubstr("campaign.json:$.shard: error: index must be below count"));
  EXPECT_THAT(e, ::testing::HasSubstr("campaign.json:$.seed: error: expected an unsigned integer"));

  refused = parse_campaign_json(edited(good, "\"version\": 1", "\"version\": 9"), "campaign.json");
  ASSERT_FALSE(refused.has_value());
  EXPECT_THAT(refused.error().message,
              ::testing::HasSubstr("campaign.json:$.version: error: unsupported version 9"));
  refused = parse_campaign_json("{\"format\": ", "campaign.json");
  ASSERT_FALSE(refused.has_value());
  EXPECT_THAT(refused.error().message, ::testing::HasSubstr("campaign.json:1:"));
}

TEST(Campaign, APlannerTimeLimitIsPartOfTheCampaignAndNoRunCallsTheBeaconForIt) {
  const auto ais = testing::load_ais_testbed();
  CampaignSpec spec = ais_spec(8);
  spec.planner_time_limit_s = 1e-6;
  Result<CampaignSpec> back = parse_campaign_json(campaign_json(spec), "campaign.json");
  ASSERT_TRUE(back.has_value()) << back.error().message;
  EXPECT_EQ(back->planner_time_limit_s, 1e-6);
  EXPECT_FALSE(spec.same_campaign(ais_spec(8)));
  EXPECT_NE(reproduce_command(spec, 3).find("--planner-time-limit 1e-06 --only 3"),
            std::string::npos);
  // Every plan reaches the limit: no beacon is the limit's, and (issue 34) the anytime ladder
  // still does tasks instead of heading for the nearest exit at once.
  std::size_t tasks = 0;
  for (const RunRecord& r : run_campaign(ais.map, ais.mission, spec, {})) {
    ASSERT_TRUE(r.result.has_value());
    EXPECT_NE(r.result->ours.beacon_cause, executor::MissionReport::BeaconCause::kLimit);
    EXPECT_NE(r.result->ours.outcome, Outcome::kStranded);
    tasks += r.result->ours.tasks;
  }
  EXPECT_GT(tasks, 0U);
}

// Which rung of the anytime ladder answered each plan (issue 34) is counted per side, read back
// from the record and summed in the summary.
TEST(Campaign, TheRungsThatAnsweredAreCountedPerSideAndSummed) {
  using Rung = executor::PlanResponse::Rung;
  const auto ais = testing::load_ais_testbed();
  const auto total = [](const Execution& e) {
    std::size_t n = 0;
    for (std::size_t c : e.rungs) n += c;
    return n;
  };
  // Without a limit, every plan is the search's: one per plan, the first and each replan.
  const auto unlimited = run_campaign(ais.map, ais.mission, ais_spec(3), {});
  for (const RunRecord& r : unlimited) {
    ASSERT_TRUE(r.result.has_value());
    for (const Execution* e : {&r.result->ours, &r.result->baseline}) {
      EXPECT_EQ(e->rungs[static_cast<std::size_t>(Rung::kSearch)], e->replans + 1);
      EXPECT_EQ(total(*e), e->replans + 1);
    }
  }
  // With a limit every search reaches, the rungs below answer; each record reads back its counts.
  CampaignSpec spec = ais_spec(4);
  spec.planner_time_limit_s = 1e-6;
  const auto limited = run_campaign(ais.map, ais.mission, spec, {});
  std::array<std::size_t, executor::PlanResponse::kRungCount> ours{};
  for (const RunRecord& r : limited) {
    ASSERT_TRUE(r.result.has_value());
    EXPECT_EQ(total(r.result->ours), r.result->ours.replans + 1);
    for (std::size_t k = 0; k < ours.size(); ++k) ours[k] += r.result->ours.rungs[k];
    Result<RunRecord> back = parse_run_line(run_json_line(r), "runs.jsonl", r.index + 1);
    ASSERT_TRUE(back.has_value()) << back.error().message;
    EXPECT_EQ(back->result->ours.rungs, r.result->ours.rungs);
    EXPECT_EQ(back->result->baseline.rungs, r.result->baseline.rungs);
  }
  EXPECT_LT(ours[static_cast<std::size_t>(Rung::kSearch)],
            ours[0] + ours[1] + ours[2] + ours[3] + ours[4] + ours[5]);
  const Summary summary = summarize(spec, limited);
  EXPECT_EQ(summary.ours.rungs, ours);
  std::ostringstream json;
  write_summary_json(summary, json);
  const nlohmann::json j = nlohmann::json::parse(json.str());
  for (std::size_t k = 0; k < ours.size(); ++k) {
    const std::string name(executor::to_string(static_cast<Rung>(k)));
    EXPECT_EQ(j["ours"]["rungs"][name], ours[k]) << name;
  }
  // A record with a rung of another name is an error naming it.
  std::string line = run_json_line(limited[0]);
  const std::size_t at = line.find("\"rungs\":{");
  ASSERT_NE(at, std::string::npos);
  line.insert(at + 9, "\"guess\":1,");
  Result<RunRecord> bad = parse_run_line(line, "runs.jsonl", 1);
  ASSERT_FALSE(bad.has_value());
  EXPECT_NE(bad.error().message.find("rungs.guess"), std::string::npos) << bad.error().message;
}

TEST(Campaign, FaultRatesAndShardsParseOrSayWhatIsWrong) {
  Result<FaultRates> r = parse_fault_rates("obstacles=40.123456789012,permanent=0.5");
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->obstacles_per_km, 40.123456789012);
  EXPECT_EQ(r->permanent_share, 0.5);
  EXPECT_EQ(r->danger_per_km, FaultRates{}.danger_per_km);
  Result<FaultRates> back = parse_fault_rates(format_fault_rates(*r));
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(*back, *r);
  for (const char* bad : {"obstacles", "obstacles=x", "permanent=2", "rain=1", "danger=-1"}) {
    Result<FaultRates> e = parse_fault_rates(bad);
    ASSERT_FALSE(e.has_value()) << bad;
    EXPECT_NE(e.error().message.find(std::string("'") + bad + "'"), std::string::npos)
        << e.error().message;
  }
  Result<std::pair<std::size_t, std::size_t>> shard = parse_shard("2/5");
  ASSERT_TRUE(shard.has_value());
  EXPECT_EQ(shard->first, 2U);
  EXPECT_EQ(shard->second, 5U);
  for (const char* bad : {"5/5", "1", "a/2", "1/0", "-1/2"})
    EXPECT_FALSE(parse_shard(bad).has_value()) << bad;
  Result<std::map<std::size_t, InjectedFault>> inject = parse_injections("crash:3,hang:5");
  ASSERT_TRUE(inject.has_value());
  EXPECT_EQ(inject->at(3), InjectedFault::kCrash);
  EXPECT_FALSE(parse_injections("boom:1").has_value());
}

TEST(Campaign, TheSummaryIsWrittenAsJsonMarkdownAndSvg) {
  const auto ais = testing::load_ais_testbed();
  const CampaignSpec spec = ais_spec(5);
  const fs::path dir = temp_dir("summary");
  ASSERT_TRUE(
      write_campaign_dir(dir, spec, run_campaign(ais.map, ais.mission, spec, {})).has_value());
  for (const char* f :
       {"campaign.json", "runs.jsonl", "summary.json", "summary.md", "summary.svg"}) {
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  }
  std::ifstream in(dir / "summary.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("runs"), 5);
  EXPECT_EQ(j.at("crashes"), 0);
  EXPECT_TRUE(j.at("ours").contains("tasks_vs_oracle_mean"));
  EXPECT_TRUE(j.at("ours").at("outcomes").contains("stranded"));
  std::ifstream svg(dir / "summary.svg");
  const std::string text((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("<g id=\"histogram\">"), std::string::npos);
  EXPECT_NE(text.find("<g id=\"outcomes\">"), std::string::npos);
  Result<MergedCampaign> read = read_campaign_dir(dir);
  ASSERT_TRUE(read.has_value()) << read.error().message;
  EXPECT_EQ(read->spec, spec);
  EXPECT_EQ(read->records.size(), 5U);
}

}  // namespace
}  // namespace sewerplan::campaign

namespace sewerplan::campaign {
namespace {

// The AIS mission with a possible blockage (p = 0.4) in the middle of every pipe, as condition
// data would give.
Mission with_hazards(const SewerMap& map, Mission mission) {
  for (PipeId p : map.pipe_ids()) {
    mission.hazards.push_back({.pipe = p,
                               .offset_m = map.pipe(p).length_m / 2,
                               .probability = 0.4,
                               .reason = "BBA roots"});
  }
  return mission;
}

TEST(Campaign, FaultsFromConditionAreSeededAndTheRiskAwareRunIsRecordedAndSummarized) {
  const auto ais = testing::load_ais_testbed();
  const Mission mission = with_hazards(ais.map, ais.mission);
  CampaignSpec spec = ais_spec(6);
  spec.rates = {.obstacles_per_km = 0, .danger_per_km = 0, .malfunctions_per_hour = 0};
  spec.risk = "expected";
  spec.faults_from_condition = true;
  const RunSettings settings = run_settings(spec);
  EXPECT_TRUE(settings.risk.active());
  std::size_t obstacles = 0;
  for (std::size_t k = 0; k < spec.runs; ++k) {
    Result<hal::FaultScenario> a = run_faults(ais.map, mission, settings, k);
    Result<hal::FaultScenario> b = run_faults(ais.map, mission, settings, k);
    ASSERT_TRUE(a.has_value() && b.has_value());
    EXPECT_EQ(*a, *b);
    for (const hal::Obstacle& o : a->obstacles) {
      EXPECT_EQ(o.kind, hal::ObstacleKind::kPermanent);
      EXPECT_EQ(o.offset_m, ais.map.pipe(o.pipe).length_m / 2);
    }
    obstacles += a->obstacles.size();
  }
  // 0.4 of every pipe, in each of six runs: some, not all.
  EXPECT_GT(obstacles, 0U);
  EXPECT_LT(obstacles, 6 * ais.map.pipe_count());
  // Without condition faults and with no random ones, nothing is hidden.
  CampaignSpec plain = spec;
  plain.faults_from_condition = false;
  EXPECT_TRUE(run_faults(ais.map, mission, run_settings(plain), 0)->obstacles.empty());

  const auto records = run_campaign(ais.map, mission, spec, {.guard = false});
  std::size_t observed = 0;
  for (const RunRecord& r : records) {
    ASSERT_TRUE(r.result.has_value());
    ASSERT_TRUE(r.result->risk_aware.has_value());
    Result<RunRecord> back = parse_run_line(run_json_line(r), "runs.jsonl", r.index + 1);
    ASSERT_TRUE(back.has_value()) << back.error().message;
    EXPECT_EQ(run_json_line(*back), run_json_line(r));
    // What each robot observed of the hazards is recorded (issue 34, the observations fit-risk
    // fits from), reads back, and agrees with the faults drawn: a hazard met as a blockage is
    // one drawn, one passed is not.
    const Result<hal::FaultScenario> drawn = run_faults(ais.map, mission, settings, r.index);
    ASSERT_TRUE(drawn.has_value());
    const auto is_drawn = [&](const executor::HazardBelief& h) {
      return std::any_of(
          drawn->obstacles.begin(), drawn->obstacles.end(),
          [&](const hal::Obstacle& o) { return o.pipe == h.pipe && o.offset_m == h.offset_m; });
    };
    for (const Execution* e : {&r.result->ours, &r.result->baseline, &*r.result->risk_aware}) {
      for (const executor::HazardBelief& h : e->hazards) {
        EXPECT_EQ(h.blocked, is_drawn(h)) << "run " << r.index << " pipe " << h.pipe.value();
        EXPECT_EQ(h.blocked, h.passes == 0);
        observed += 1;
      }
    }
    EXPECT_EQ(back->result->ours.hazards, r.result->ours.hazards);
  }
  EXPECT_GT(observed, 0U);
  const Summary s = summarize(spec, records);
  ASSERT_TRUE(s.risk_aware.has_value());
  EXPECT_EQ(s.risk_aware_better + s.risk_aware_equal + s.risk_aware_worse, spec.runs);
  std::ostringstream md;
  write_summary_markdown(s, md);
  EXPECT_NE(md.str().find("Risk-aware planning (--risk expected) against ours"), std::string::npos);
  // The risk settings are part of the campaign's identity.
  Result<CampaignSpec> spec_back = parse_campaign_json(campaign_json(spec), "campaign.json");
  ASSERT_TRUE(spec_back.has_value()) << spec_back.error().message;
  EXPECT_EQ(*spec_back, spec);
  EXPECT_FALSE(spec.same_campaign(plain));
}

}  // namespace
}  // namespace sewerplan::campaign

namespace sewerplan::campaign {
namespace {

// Five runs of the paper's mission in the realistic world that ended with the beacon on, the
// robot taken to be at a manhole it was not at, and each now ends outside with every arrival at
// its true manhole but the false detection of run 46 (an arrival is scored when it is made):
// - seed 2, run 69: a junction the map lacks taken for a false detection; the robot drove on,
//   0 m, to the manhole beyond, and the filter, refusing a drive on into a manhole, was restarted
//   there; the robot refused the turn (now the filter holds the robot at the junction);
// - seed 2, run 196: a mapped manhole 0.2 m ahead whose lateral the map has wrong read as no
//   manhole at all, and the robot drove on 0 m and arrived there 22 times (now a mouth the map has
//   wrong scores as a mouth of unknown size and direction, not as a stranger);
// - seed 3, run 46: a false detection 0.6 m short of M2 taken for M2; the robot refused the turn
//   there, was rebooted three times and called stuck (now a refused turn puts it in the pipe);
// - seed 2, run 45: backing out of P1, a false detection taken for a junction the map lacks; the
//   robot refused to pass it, the pipe was closed there and the beacon called "no exit" (now the
//   refused pass makes the junction a false detection, and the robot backs on to M2 and out);
// - seed 3, run 16: a robot that missed M2 met an obstacle 0.6 m into P1, held as likely at P12's
//   far end; P12 was closed at M2, its way back to M1 (now, stopped at the tracked pipe's end, the
//   blockage goes beyond when the filter holds that at 0.25 or more).
TEST(CampaignWorld, NoRobotIsLeftStuckAtAManholeItIsNotAt) {
  const auto ais = testing::load_ais_testbed();
  struct Case {
    std::uint64_t seed;
    std::size_t run;
    std::size_t wrong_arrivals;
  };
  for (const Case c :
       {Case{2, 69, 0}, Case{2, 196, 0}, Case{3, 46, 1}, Case{2, 45, 0}, Case{3, 16, 0}}) {
    SCOPED_TRACE("seed " + std::to_string(c.seed) + " run " + std::to_string(c.run));
    const Result<RunResult> r = realistic_run(ais.map, ais.mission, 200, c.seed, c.run);
    ASSERT_TRUE(r.has_value()) << r.error().message;
    const Execution& ours = r->ours;
    EXPECT_EQ(ours.beacon_cause, executor::MissionReport::BeaconCause::kNone) << ours.end;
    EXPECT_TRUE(r->could_reach_exit);
    EXPECT_TRUE(ours.outcome == Outcome::kExit || ours.outcome == Outcome::kEndPoint) << ours.end;
    ASSERT_TRUE(ours.world.has_value());
    EXPECT_GE(ours.world->arrivals, 2U);
    EXPECT_EQ(ours.world->correct_arrivals + c.wrong_arrivals, ours.world->arrivals);
  }
}

// Runs of the paper's mission in the realistic world that ended with the beacon "no exit" while
// the oracle reached one, found by scanning campaign seeds beyond those looked at before
// (docs/campaign.md, "Seeds never looked at"); each now ends outside:
// - backing out of P6 (or P4) through the junction the map lacks that the robot had passed on the
//   way in, the way on was refused (seen narrower than the map's pipe, which it was: the world's
//   pipe is narrower; or seen 32-35 degrees off straight, one sighting's noise beyond 30) and the
//   junction closed behind the robot: seed 33 run 182, seed 36 run 168, seed 38 run 29, seed 58
//   run 137 (Localising's straight_through);
// - seed 42, run 118: the same pass failed by a transient malfunction, and the junction was closed
//   for it (now the pass is rebooted through as any job);
// - seed 109, run 91, and seed 153, run 134: an obstacle closed under the tracked belief, then met
//   again by a robot the filter placed in that pipe beyond the first closure; it was shut in
//   between the two (now the blockages learnt on the way in are dropped: drove_through).
TEST(CampaignWorld, NoRobotIsShutInByItsOwnClosures) {
  const auto ais = testing::load_ais_testbed();
  struct Case {
    std::uint64_t seed;
    std::size_t run;
  };
  for (const Case c : {Case{33, 182}, Case{36, 168}, Case{38, 29}, Case{58, 137}, Case{42, 118},
                       Case{109, 91}, Case{153, 134}}) {
    SCOPED_TRACE("seed " + std::to_string(c.seed) + " run " + std::to_string(c.run));
    const Result<RunResult> r = realistic_run(ais.map, ais.mission, 200, c.seed, c.run);
    ASSERT_TRUE(r.has_value()) << r.error().message;
    EXPECT_TRUE(r->could_reach_exit);
    EXPECT_EQ(r->ours.beacon_cause, executor::MissionReport::BeaconCause::kNone) << r->ours.end;
    EXPECT_TRUE(r->ours.outcome == Outcome::kExit || r->ours.outcome == Outcome::kEndPoint)
        << r->ours.end;
  }
}

// AIS, realistic world: a robot backing out of P4 drove through M6 unseen, on through a junction
// the map lacks in P6, and arrived at M7, whose only way on from P6 (into P7) turns 127 degrees,
// beyond makro-1.1's 90. The planner knows no way back from a mouth into its own pipe, and the
// beacon came on with exits in reach (seeds 24, 26, 38, 44, 61 and 71). Now the robot, at the end
// of the pipe it came out of, backs into it, and leaves by an exit with every arrival right.
TEST(CampaignWorld, ARobotAtAMouthWithNoWayOnBacksIntoItsPipe) {
  const auto ais = testing::load_ais_testbed();
  struct Case {
    std::uint64_t seed;
    std::size_t run;
  };
  for (const Case c : {Case{24, 158}, Case{38, 6}, Case{71, 34}}) {
    SCOPED_TRACE("seed " + std::to_string(c.seed) + " run " + std::to_string(c.run));
    const Result<RunResult> r = realistic_run(ais.map, ais.mission, 200, c.seed, c.run);
    ASSERT_TRUE(r.has_value()) << r.error().message;
    EXPECT_EQ(r->ours.outcome, Outcome::kExit) << r->ours.end;
    ASSERT_TRUE(r->ours.world.has_value());
    EXPECT_EQ(r->ours.world->correct_arrivals, r->ours.world->arrivals);
  }
}

// AIS, realistic world, seed 50, run 167: the robot drove through M6 unseen, 9.68 m into P5
// (10 m mapped, shorter in the sewer), and met an obstacle just inside P10 beyond. The filter did
// not follow the place past M6, the odometry being short of its mapped mouth: backing out, the
// arrival at M6 was taken for a false detection, the next for M3, and the robot ended the mission
// "at M4", where it was not (stranded). Now the place past a manhole missed short of its mapped
// place is followed, weighed by the chance the mouth was passed: every arrival is right, and the
// robot ends at M4.
TEST(CampaignWorld, AManholeMissedShortOfItsMappedPlaceIsFollowed) {
  const auto ais = testing::load_ais_testbed();
  const Result<RunResult> r = realistic_run(ais.map, ais.mission, 200, 50, 167);
  ASSERT_TRUE(r.has_value()) << r.error().message;
  EXPECT_EQ(r->ours.outcome, Outcome::kExit) << r->ours.end;
  ASSERT_TRUE(r->ours.world.has_value());
  EXPECT_EQ(r->ours.world->correct_arrivals, r->ours.world->arrivals);
}

// The meshed network of docs/campaign.md (`generate --manholes 1000 --seed 1 --topology meshed
// --mission-tasks 10 --mission-spread near-exit`), its map and mission through their JSON files as
// the command reads them. In the realistic world, seed 2, run 20: a robot that missed M635 met an
// obstacle in P514 beyond; the filter held it about as likely 4 m past P515's mapped end, P515 was
// closed there, and the beacon came on with M635, an exit, 4 m behind it. Now, with no exit from
// the tracked place but another in the belief, the robot backs up to the manhole behind, is found
// at M635, and leaves there. Run 30: a robot that missed M635 backing out of P514 was found in P515
// beyond the place where it had reported a transient obstacle earlier; that blockage, driven
// through since, shut it in (now it is dropped: Replanner::drove_through). Run 5: a danger met past
// M635, missed, was placed at P515's end once the robot had backed off from it (now the place it
// stopped decides: at the tracked pipe's end, beyond).
struct MeshedNetwork {
  SewerMap map;
  Mission mission;
};
// The network and mission of the campaigns, read back from their JSON as the command reads
// them; empty (with the test failed) when any step fails.
std::optional<MeshedNetwork> meshed_1000() {
  const Result<SewerMap> generated =
      generate_network({.manholes = 1000, .seed = 1, .topology = Topology::kMeshed});
  if (!generated.has_value()) {
    ADD_FAILURE() << generated.error().message;
    return std::nullopt;
  }
  const Result<Mission> planned =
      domain::generate_mission(*generated, {.tasks = 10,
                                            .seed = 1,
                                            .profile = "makro-plus",
                                            .spread = domain::MissionSpread::kNearExit});
  if (!planned.has_value()) {
    ADD_FAILURE() << planned.error().message;
    return std::nullopt;
  }
  std::ostringstream map_text, mission_text;
  write_map_json(*generated, map_text);
  write_mission_json(*planned, *generated, mission_text);
  Diagnostics diagnostics;
  Result<SewerMap> map = read_map_json(map_text.str(), "m1k.json", diagnostics);
  if (!map.has_value()) {
    ADD_FAILURE() << map.error().message;
    return std::nullopt;
  }
  Result<Mission> mission =
      read_mission_json(mission_text.str(), "m1k-mission.json", *map, diagnostics);
  if (!mission.has_value()) {
    ADD_FAILURE() << mission.error().message;
    return std::nullopt;
  }
  return MeshedNetwork{std::move(*map), std::move(*mission)};
}

TEST(CampaignWorld, NoBeaconWhileTheBeliefHoldsAPlaceWithAnExit) {
  const std::optional<MeshedNetwork> net = meshed_1000();
  ASSERT_TRUE(net.has_value());
  CampaignSpec spec = ais_spec(40, 2);
  spec.world_errors = "realistic";
  for (const std::size_t run : {20U, 30U, 5U}) {
    SCOPED_TRACE("run " + std::to_string(run));
    const Result<RunResult> r = run_one(net->map, net->mission, run_settings(spec), run);
    ASSERT_TRUE(r.has_value()) << r.error().message;
    EXPECT_TRUE(r->could_reach_exit);
    EXPECT_EQ(r->ours.beacon_cause, executor::MissionReport::BeaconCause::kNone) << r->ours.end;
    EXPECT_EQ(r->ours.outcome, Outcome::kExit) << r->ours.end;
  }
}

// The meshed network, realistic world: a robot that drove through a manhole unseen met an
// obstacle or a danger in the pipe beyond; it was closed in the pipe before, at that manhole
// (the tracking's place). Backing out, the robot arrived at the manhole out of the pipe it was
// really in, and the closure shut its way on: the beacon, with an exit in reach (seed 26 run 5,
// seed 8 run 26, seed 10 run 38, seed 27 run 13). Now the arrival moves the closure into the
// pipe the robot came out of, as far from the mouth as it drove (Replanner::move_learnt).
TEST(CampaignWorld, AClosurePlacedUnderARefutedBeliefMoves) {
  const std::optional<MeshedNetwork> net = meshed_1000();
  ASSERT_TRUE(net.has_value());
  struct Case {
    std::uint64_t seed;
    std::size_t run;
  };
  for (const Case c : {Case{26, 5}, Case{8, 26}, Case{10, 38}, Case{27, 13}}) {
    SCOPED_TRACE("seed " + std::to_string(c.seed) + " run " + std::to_string(c.run));
    const Result<RunResult> r = realistic_run(net->map, net->mission, 40, c.seed, c.run);
    ASSERT_TRUE(r.has_value()) << r.error().message;
    EXPECT_TRUE(r->could_reach_exit);
    EXPECT_EQ(r->ours.beacon_cause, executor::MissionReport::BeaconCause::kNone) << r->ours.end;
    EXPECT_EQ(r->ours.outcome, Outcome::kExit) << r->ours.end;
  }
}

// The meshed network, realistic world: a robot that drove through a manhole unseen met a danger
// in the pipe beyond, short of where it had met the same danger from the other end before. Seed
// 4, run 19: the filter placed it past the danger learnt there (the odometry 1.3 m short), shut
// in between the two; now the danger learnt stops it where it was learnt. Seed 6, run 16: the
// tracking kept it short of the manhole, a blockage behind; the filter held the pipe beyond at
// p=0.011, under the ambiguity the robot went back to look at, and the drive back went the way
// of the step back off the danger, into the danger again. Both beacons came on with an exit a
// few manholes away; both robots now end there.
TEST(CampaignWorld, ADangerMetAgainPastAMissedManholeDoesNotShutTheRobotIn) {
  const std::optional<MeshedNetwork> net = meshed_1000();
  ASSERT_TRUE(net.has_value());
  struct Case {
    std::uint64_t seed;
    std::size_t run;
  };
  for (const Case c : {Case{4, 19}, Case{6, 16}}) {
    SCOPED_TRACE("seed " + std::to_string(c.seed) + " run " + std::to_string(c.run));
    const Result<RunResult> r = realistic_run(net->map, net->mission, 40, c.seed, c.run);
    ASSERT_TRUE(r.has_value()) << r.error().message;
    EXPECT_TRUE(r->could_reach_exit);
    EXPECT_EQ(r->ours.outcome, Outcome::kExit) << r->ours.end;
  }
  // Seed 4, run 19: the danger met again is placed where it was learnt, not 1.3 m beyond.
  CampaignSpec spec = ais_spec(40, 4);
  spec.world_errors = "realistic";
  std::vector<double> dangers;
  ExecutionObservers observers{.on_event = [&](const executor::Event& e) {
    const auto* failure = std::get_if<executor::FailureEvent>(&e.what);
    if (failure == nullptr || failure->kind != executor::Failure::Kind::kDangerInPipe) return;
    const auto* in = std::get_if<executor::FailureEvent::InPipe>(&failure->where);
    if (in != nullptr && in->pipe == "P1073") dangers.push_back(in->offset_m);
  }};
  ASSERT_TRUE(
      replay_execution(net->map, net->mission, run_settings(spec), 19, Policy::kOurs, observers)
          .has_value());
  ASSERT_EQ(dangers.size(), 2U);
  EXPECT_NEAR(dangers[1], dangers[0], 1e-9);
}

// A robot that drives through a manhole unseen goes on into the pipe straight on only where its
// body fits that pipe: the simulated robot drove on into pipes narrower than its profile (a
// 0.25 m pipe for makro-plus's 0.30 m on the meshed network, seed 28, run 16), where the filter
// then rightly placed it and no plan could start (the beacon). AIS seed 49, run 113, ended
// `stuck` the same way. Both now end outside.
TEST(CampaignWorld, TheSimulatedRobotDrivesOnlyIntoPipesItFits) {
  const auto ais = testing::load_ais_testbed();
  const Result<RunResult> a = realistic_run(ais.map, ais.mission, 200, 49, 113);
  ASSERT_TRUE(a.has_value()) << a.error().message;
  EXPECT_TRUE(a->ours.outcome == Outcome::kExit || a->ours.outcome == Outcome::kEndPoint)
      << a->ours.end;
  const std::optional<MeshedNetwork> net = meshed_1000();
  ASSERT_TRUE(net.has_value());
  const Result<RunResult> m = realistic_run(net->map, net->mission, 40, 28, 16);
  ASSERT_TRUE(m.has_value()) << m.error().message;
  EXPECT_EQ(m->ours.outcome, Outcome::kExit) << m->ours.end;
}

// --world-errors (issue 29): each run's robot drives a true world drawn from the run's seed, the
// oracle plans on it, and the line carries the seeded discrepancies, which read back.
TEST(CampaignWorld, RunsInATrueWorldRecordAndReadBackItsDiscrepancies) {
  const auto ais = testing::load_ais_testbed();
  CampaignSpec spec = ais_spec(4, 3);
  spec.world_errors = "realistic,lengths=1";
  const RunSettings settings = run_settings(spec);
  EXPECT_DOUBLE_EQ(settings.world_errors.length_share, 1);
  const Result<RunResult> r = run_one(ais.map, ais.mission, settings, 2);
  ASSERT_TRUE(r.has_value()) << r.error().message;
  std::size_t lengths = 0;
  for (const Discrepancy& d : r->seeded) {
    lengths += d.kind == Discrepancy::Kind::kLengthOff ? 1U : 0U;
  }
  EXPECT_EQ(lengths, ais.map.pipe_count());
  // The same run again: the same world.
  EXPECT_EQ(run_one(ais.map, ais.mission, settings, 2)->seeded, r->seeded);
  const RunRecord record{.index = 2, .seed = r->seed, .result = *r, .wall_s = r->wall_s};
  const std::string line = run_json_line(record);
  EXPECT_THAT(line, ::testing::HasSubstr("\"world\":{\"seeded\":[{\"kind\":\"length-off\""));
  const Result<RunRecord> back = parse_run_line(line, "runs.jsonl", 1);
  ASSERT_TRUE(back.has_value()) << back.error().message;
  ASSERT_TRUE(back->result.has_value());
  ASSERT_EQ(back->result->seeded.size(), r->seeded.size());
  for (std::size_t i = 0; i < r->seeded.size(); ++i) {
    EXPECT_TRUE(same_difference(back->result->seeded[i], r->seeded[i]));
    EXPECT_DOUBLE_EQ(back->result->seeded[i].value, r->seeded[i].value);
  }
  // Without world errors a line has no "world" and the campaign spec none either.
  const RunSettings plain = run_settings(ais_spec(4, 3));
  const Result<RunResult> exact = run_one(ais.map, ais.mission, plain, 2);
  EXPECT_TRUE(exact->seeded.empty());
  EXPECT_THAT(run_json_line({.index = 2, .seed = exact->seed, .result = *exact}),
              ::testing::Not(::testing::HasSubstr("\"world\"")));
  EXPECT_THAT(campaign_json(ais_spec(4, 3)), ::testing::Not(::testing::HasSubstr("world_errors")));
  EXPECT_THAT(campaign_json(spec),
              ::testing::HasSubstr("\"world_errors\": \"realistic,lengths=1\""));
  spec.world_errors = "realism";
  EXPECT_FALSE(parse_campaign_json(campaign_json(spec), "campaign.json").has_value());
}

}  // namespace
}  // namespace sewerplan::campaign
