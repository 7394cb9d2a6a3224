// SPDX-License-Identifier: MIT
// The campaign's summary tells the truth (issue 30): a campaign whose oracle can end no run says
// so, runs above the oracle are counted, each policy's missed exits count only the runs where its
// own robot could move, and the chart shows the verdict, the rates and limits and what it leaves
// out. Built from hand-made records, so each figure is known.
#include "sewerplan/campaign/summary.h"

#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace sewerplan::campaign {
namespace {

RunRecord record(std::size_t index, std::size_t oracle_tasks, bool oracle_can_end, Execution ours,
                 Execution baseline) {
  RunResult r;
  r.index = index;
  r.tasks = 4;
  r.oracle_tasks = oracle_tasks;
  r.oracle_can_end = oracle_can_end;
  r.could_reach_exit = oracle_can_end && !ours.disabled;
  r.ours = std::move(ours);
  r.baseline = std::move(baseline);
  return RunRecord{.index = index, .result = r};
}

Execution ended_with(std::size_t tasks, Outcome outcome = Outcome::kExit, bool disabled = false) {
  Execution e;
  e.tasks = tasks;
  e.outcome = outcome;
  e.disabled = disabled;
  return e;
}

CampaignSpec spec() {
  CampaignSpec s;
  s.map_name = "map.json";
  s.mission_name = "mission.json";
  s.runs = 3;
  s.rates = *fault_rate_profile("harsh");
  s.push_allowed = true;
  s.planner_time_limit_s = 0.5;
  return s;
}

std::string markdown(const Summary& s) {
  std::ostringstream out;
  write_summary_markdown(s, out);
  return out.str();
}

std::string svg(const Summary& s) {
  std::ostringstream out;
  write_summary_svg(s, out);
  return out.str();
}

nlohmann::json json(const Summary& s) {
  std::ostringstream out;
  write_summary_json(s, out);
  return nlohmann::json::parse(out.str());
}

// Before: "mean 0.0 %, worst 100.0 %" for a campaign with nothing to compare.
TEST(CampaignSummary, WhenTheOracleCanEndNoRunItSaysSo) {
  const Summary s = summarize(
      spec(),
      {record(0, 0, false, ended_with(0, Outcome::kBeacon), ended_with(0, Outcome::kBeacon)),
       record(1, 0, false, ended_with(0, Outcome::kBeacon), ended_with(0, Outcome::kBeacon))});
  EXPECT_EQ(s.ours.compared, 0U);
  EXPECT_EQ(s.oracle_can_end, 0U);
  const std::string md = markdown(s);
  EXPECT_EQ(md.find("0.0 %"), std::string::npos) << md;
  EXPECT_EQ(md.find("100.0 %"), std::string::npos) << md;
  EXPECT_NE(md.find("| tasks vs oracle, mean | none: the oracle could end no run |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("the oracle could end no run: no policy could reach an exit"),
            std::string::npos)
      << md;
  const nlohmann::json j = json(s);
  EXPECT_TRUE(j.at("ours").at("tasks_vs_oracle_mean").is_null());
  EXPECT_TRUE(j.at("ours").at("tasks_vs_oracle_worst").is_null());
  const std::string chart = svg(s);
  EXPECT_NE(chart.find("The oracle could end no run: nothing to compare"), std::string::npos);
  EXPECT_EQ(chart.find("100.0 %"), std::string::npos) << chart;
  EXPECT_NE(chart.find("runs the oracle could not end (not drawn): 2"), std::string::npos);
}

TEST(CampaignSummary, RunsWhereOursDidMoreThanTheOracleAreCounted) {
  const Summary s = summarize(
      spec(),
      {// More tasks than the oracle's plan.
       record(0, 1, true, ended_with(2), ended_with(1)),
       // Ended a mission the oracle could not end.
       record(1, 0, false, ended_with(1), ended_with(0, Outcome::kBeacon)),
       // A run the oracle cannot end, where ours did a task and was cut off: no bound
       // broken (the oracle counts tasks of missions that end).
       record(2, 0, false, ended_with(1, Outcome::kBeacon), ended_with(0, Outcome::kBeacon)),
       record(3, 2, true, ended_with(2), ended_with(2))});
  EXPECT_EQ(s.oracle_below_ours, 2U);
  EXPECT_EQ(s.ours.above_oracle, 1U);
  EXPECT_EQ(s.ours.vs_oracle_histogram[11], 1U);  // in a bin of its own, not at 100 %
  EXPECT_EQ(s.ours.vs_oracle_histogram[10], 1U);
  EXPECT_EQ(s.baseline.above_oracle, 0U);
  EXPECT_NE(markdown(s).find("| runs with more tasks than the oracle | 1 | 0 |"),
            std::string::npos);
  EXPECT_EQ(json(s).at("ours").at("runs_above_oracle"), 1);
  EXPECT_NE(svg(s).find(">more</text>"), std::string::npos);
}

TEST(CampaignSummary, TheBaselinesMissedExitsCountOnlyRunsWhereItsRobotCouldMove) {
  // Run 0: a permanent malfunction stopped the baseline's robot (not ours): no missed exit of the
  // baseline's. Run 1: it could move and did not get out: a missed exit.
  const Summary s = summarize(
      spec(),
      {record(0, 2, true, ended_with(2), ended_with(1, Outcome::kBeacon, /*disabled=*/true)),
       record(1, 2, true, ended_with(2), ended_with(1, Outcome::kBeacon))});
  EXPECT_EQ(s.baseline.could_reach_exit, 1U);
  EXPECT_EQ(s.baseline.missed_exits, 1U);
  EXPECT_EQ(s.ours.could_reach_exit, 2U);
  EXPECT_EQ(s.ours.missed_exits, 0U);
  EXPECT_TRUE(s.clean());
}

// A run the oracle cannot end (with the whole battery, knowing every fault, on the reserve as the
// last way out) is no missed exit of any policy, whatever its robot did; one it can end is, for a
// robot that could move.
TEST(CampaignSummary, ARunTheOracleCannotEndIsNoMissedExit) {
  const Summary s = summarize(
      spec(),
      {record(0, 0, false, ended_with(1, Outcome::kBeacon), ended_with(0, Outcome::kBeacon)),
       record(1, 1, true, ended_with(1, Outcome::kBeacon), ended_with(1))});
  EXPECT_EQ(s.ours.could_reach_exit, 1U);
  EXPECT_EQ(s.ours.missed_exits, 1U);
  EXPECT_EQ(s.baseline.could_reach_exit, 1U);
  EXPECT_EQ(s.baseline.missed_exits, 0U);
  EXPECT_FALSE(s.clean());
}

// Issue 34: the stranding risk the first plans computed, beside the missed exits observed with
// their 95 % Wilson interval (1 of 4: 0.25, [0.0456, 0.6994]).
TEST(CampaignSummary, TheComputedStrandingRiskStandsBesideTheMissedExitsObserved) {
  std::vector<RunRecord> runs;
  for (std::size_t i = 0; i < 4; ++i) {
    Execution ours = ended_with(2, i == 0 ? Outcome::kBeacon : Outcome::kExit);
    ours.strand_risk = 0.1 * static_cast<double>(i);
    runs.push_back(record(i, 2, true, ours, ended_with(2)));
  }
  const nlohmann::json j = json(summarize(spec(), runs));
  EXPECT_NEAR(j["ours"]["strand_risk_mean"].get<double>(), 0.15, 1e-12);
  EXPECT_NEAR(j["ours"]["missed_exit_share"].get<double>(), 0.25, 1e-12);
  EXPECT_NEAR(j["ours"]["missed_exit_share_95"][0].get<double>(), 0.0456, 1e-4);
  EXPECT_NEAR(j["ours"]["missed_exit_share_95"][1].get<double>(), 0.6994, 1e-4);
  EXPECT_EQ(j["baseline"]["strand_risk_mean"].get<double>(), 0.0);
  EXPECT_EQ(j["baseline"]["missed_exit_share_95"][0].get<double>(), 0.0);
}

TEST(CampaignSummary, TheChartShowsTheVerdictMissedExitsRatesAndLimits) {
  const Summary clean = summarize(spec(), {record(0, 2, true, ended_with(2), ended_with(2))});
  const std::string ok = svg(clean);
  EXPECT_NE(ok.find("Verdict: clean"), std::string::npos);
  EXPECT_NE(ok.find(format_fault_rates(*fault_rate_profile("harsh"))), std::string::npos);
  EXPECT_NE(ok.find("push allowed"), std::string::npos);
  EXPECT_NE(ok.find("planner time limit 0.5 s"), std::string::npos);
  const Summary missed =
      summarize(spec(), {record(0, 2, true, ended_with(1, Outcome::kBeacon), ended_with(2)),
                         record(1, 2, true, ended_with(1, Outcome::kStranded), ended_with(2))});
  const std::string bad = svg(missed);
  EXPECT_NE(bad.find("Verdict: NOT clean: 2 missed exits, 1 stranded robot"), std::string::npos)
      << bad;
  EXPECT_NE(bad.find("missed exits 2 of 2"), std::string::npos) << bad;
  EXPECT_NE(markdown(missed).find("Verdict: NOT clean: 2 missed exits, 1 stranded robot."),
            std::string::npos);
}

TEST(FaultRateProfiles, AProfileIsReadByNameAndItsRatesCanBeChanged) {
  Result<FaultRates> harsh = parse_fault_rates("harsh");
  ASSERT_TRUE(harsh.has_value()) << harsh.error().message;
  EXPECT_EQ(*harsh, *fault_rate_profile("harsh"));
  EXPECT_EQ(harsh->obstacles_per_km, 80);
  Result<FaultRates> changed = parse_fault_rates("realistic,malfunctions=0");
  ASSERT_TRUE(changed.has_value()) << changed.error().message;
  FaultRates expected = *fault_rate_profile("realistic");
  expected.malfunctions_per_hour = 0;
  EXPECT_EQ(*changed, expected);
  EXPECT_EQ(*parse_fault_rates("default"), FaultRates{});
  Result<FaultRates> unknown = parse_fault_rates("gentle,obstacles=1");
  ASSERT_FALSE(unknown.has_value());
  EXPECT_NE(unknown.error().message.find("unknown profile 'gentle' (known: default, realistic"),
            std::string::npos)
      << unknown.error().message;
  // Profiles are named in order of severity, by what blocks a kilometre of pipe.
  double last = -1;
  for (const FaultRateProfile& p : kFaultRateProfiles) {
    if (p.name == "default") continue;
    const double blocking =
        p.rates.obstacles_per_km * (1 - p.rates.transient_share / 2) + p.rates.danger_per_km;
    EXPECT_GT(blocking, last) << p.name;
    last = blocking;
  }
}

}  // namespace
}  // namespace sewerplan::campaign
