// SPDX-License-Identifier: MIT
// The campaign's figures against the true world (issue 29): an arrival is right only at the true
// manhole, length errors are against the world's lengths, seeded discrepancies count only within
// the robot's reach and match by same_difference, and a campaign pools runs exactly. Each figure
// is computed on hand-made inputs whose answer is known.
#include "sewerplan/campaign/world_score.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <variant>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "sewerplan/campaign/campaign.h"
#include "sewerplan/campaign/record.h"
#include "sewerplan/campaign/summary.h"
#include "sewerplan/core/clock.h"
#include "sewerplan/executor/replanner.h"

#include "support/ais_testbed.h"

namespace sewerplan::campaign {
namespace {

const SewerMap& ais() {
  static const SewerMap map = testing::load_ais_testbed().map;
  return map;
}

const std::string& name(ManholeId m) { return ais().manhole(m).name; }

TEST(WorldScore, AnArrivalIsRightOnlyAtTheTrueManhole) {
  const SewerMap& map = ais();
  const ManholeId m0{0}, m1{1};
  EXPECT_TRUE(arrival_correct(map, hal::AtSlot{m0, SlotIndex{0}}, name(m0)));
  EXPECT_FALSE(arrival_correct(map, hal::AtSlot{m0, SlotIndex{0}}, name(m1)));
  EXPECT_FALSE(arrival_correct(map, hal::AtSlot{m0, SlotIndex{0}}, ""));
  EXPECT_TRUE(arrival_correct(map, hal::InManhole{m1}, name(m1)));
  // A false detection: truly in a pipe, right only when the robot believes no mapped manhole.
  EXPECT_TRUE(arrival_correct(map, hal::InPipe{PipeId{0}, 3.0}, ""));
  EXPECT_FALSE(arrival_correct(map, hal::InPipe{PipeId{0}, 3.0}, name(m0)));
  // A manhole only the world has (appended after the map's): an unmapped junction.
  const ManholeId junction{static_cast<std::uint32_t>(map.manhole_count())};
  EXPECT_TRUE(arrival_correct(map, hal::AtSlot{junction, SlotIndex{0}}, ""));
  EXPECT_FALSE(arrival_correct(map, hal::AtSlot{junction, SlotIndex{0}}, name(m0)));
}

TEST(WorldScore, LengthErrorsAreAgainstTheWorldsLengths) {
  const SewerMap& map = ais();
  const Result<hal::TrueWorld> truth =
      hal::make_true_world(map, *hal::parse_world_errors("lengths=1,length_rel=0.2"), 3);
  ASSERT_TRUE(truth.has_value()) << truth.error().message;
  const double true0 = truth->world.pipe(PipeId{0}).length_m;
  const double true1 = truth->world.pipe(PipeId{1}).length_m;
  ASSERT_GT(std::abs(true0 - map.pipe(PipeId{0}).length_m), 0.01);
  MapMeasurements m = measurements_of(map, {.robot = "r", .mission = "m", .date = "d"});
  // Measured to a millimetre, far from the map: the corrected length is the measurement.
  add_length(m, PipeId{0}, true0 * 1.03, 1e-6, 0);
  add_length(m, PipeId{1}, true1 * 0.96, 1e-6, 0);
  const std::vector<double> errors = length_errors(map, *truth, m);
  ASSERT_EQ(errors.size(), 2U);
  EXPECT_NEAR(errors[0], 0.03, 1e-9);
  EXPECT_NEAR(errors[1], -0.04, 1e-9);
  EXPECT_NEAR(rms(errors), std::sqrt((0.03 * 0.03 + 0.04 * 0.04) / 2), 1e-9);
  EXPECT_EQ(rms({}), 0);
  // The map's length measured exactly is wrong by the world's error.
  MapMeasurements as_mapped = measurements_of(map, {.robot = "r", .mission = "m", .date = "d"});
  add_length(as_mapped, PipeId{0}, map.pipe(PipeId{0}).length_m, 0.01, 0);
  EXPECT_NEAR(length_errors(map, *truth, as_mapped)[0],
              (map.pipe(PipeId{0}).length_m - true0) / true0, 1e-12);
}

TEST(WorldScore, APipeSplitByAJunctionIsAsLongAsBothPieces) {
  const SewerMap& map = ais();
  const Result<hal::TrueWorld> truth =
      hal::make_true_world(map, *hal::parse_world_errors("junctions=1"), 5);
  ASSERT_TRUE(truth.has_value()) << truth.error().message;
  ASSERT_FALSE(truth->splits.empty());
  for (const hal::PipeSplit& s : truth->splits) {
    const double piece = truth->world.pipe(s.pipe).length_m;
    EXPECT_LT(piece, map.pipe(s.pipe).length_m);
    EXPECT_NEAR(hal::world_length_m(*truth, s.pipe), piece + truth->world.pipe(s.rest).length_m,
                1e-12);
    EXPECT_NEAR(hal::world_length_m(*truth, s.pipe), map.pipe(s.pipe).length_m, 1e-9);
  }
}

Discrepancy length_off(std::uint32_t pipe) {
  return {.kind = Discrepancy::Kind::kLengthOff, .pipe = PipeId{pipe}};
}

TEST(WorldScore, SeededDiscrepanciesCountWithinReachAndMatchBySameDifference) {
  using Kind = Discrepancy::Kind;
  const std::vector<Discrepancy> seeded{
      length_off(0),                                                                 // driven whole
      {.kind = Kind::kDirectionOff, .manhole = ManholeId{1}, .slot = SlotIndex{0}},  // driven
      {.kind = Kind::kUnmappedJunction, .pipe = PipeId{2}, .offset_m = 10},          // arrived
      {.kind = Kind::kPositionOff, .manhole = ManholeId{1}},  // never within reach
      length_off(5),                                          // not driven whole
      {.kind = Kind::kMissingLateral, .manhole = ManholeId{4}, .slot = SlotIndex{2}},  // not there
      // In a manhole arrived in, but only seen: not on a driven pipe.
      {.kind = Kind::kDirectionOff, .manhole = ManholeId{1}, .slot = SlotIndex{2}},
  };
  const Reach reach{.pipes_driven_whole = {PipeId{0}, PipeId{7}},
                    .manholes_arrived = {ManholeId{1}},
                    .junctions_arrived = {PipeId{2}},
                    .mouths_driven = {{ManholeId{1}, SlotIndex{0}}, {ManholeId{1}, SlotIndex{1}}}};
  EXPECT_TRUE(within_reach(seeded[0], reach));
  EXPECT_TRUE(within_reach(seeded[1], reach));
  EXPECT_TRUE(within_reach(seeded[2], reach));
  EXPECT_FALSE(within_reach(seeded[3], reach));
  EXPECT_FALSE(within_reach(seeded[4], reach));
  EXPECT_FALSE(within_reach(seeded[5], reach));
  EXPECT_FALSE(within_reach(seeded[6], reach));
  const auto found = [](Discrepancy d) { return FoundDiscrepancy{.discrepancy = d}; };
  const std::vector<FoundDiscrepancy> reported{
      found(length_off(0)),                                                         // found
      found({.kind = Kind::kUnmappedJunction, .pipe = PipeId{2}, .offset_m = 13}),  // within 5 m
      found({.kind = Kind::kDirectionOff, .manhole = ManholeId{1}, .slot = SlotIndex{1}}),  // false
      found(length_off(5)),  // seeded, out of reach: not false
      found(length_off(7)),  // driven, not seeded: false
  };
  const DiscrepancyScore s = score_discrepancies(seeded, reported, reach);
  ScoresByKind by_kind{};
  by_kind[static_cast<std::size_t>(Kind::kLengthOff)] = {
      .in_reach = 1, .found = 1, .reported = 3, .false_reports = 1};
  by_kind[static_cast<std::size_t>(Kind::kDirectionOff)] = {
      .in_reach = 1, .found = 0, .reported = 1, .false_reports = 1};
  by_kind[static_cast<std::size_t>(Kind::kUnmappedJunction)] = {
      .in_reach = 1, .found = 1, .reported = 1, .false_reports = 0};
  EXPECT_EQ(s,
            (DiscrepancyScore{
                .in_reach = 3, .found = 2, .reported = 5, .false_reports = 2, .by_kind = by_kind}));
  // A junction reported 6 m from the seeded one is another junction.
  const DiscrepancyScore far = score_discrepancies(
      seeded, {found({.kind = Kind::kUnmappedJunction, .pipe = PipeId{2}, .offset_m = 16})}, reach);
  EXPECT_EQ(far.in_reach, 3U);
  EXPECT_EQ(far.found, 0U);
  EXPECT_EQ(far.false_reports, 1U);
  EXPECT_EQ(far.by_kind[static_cast<std::size_t>(Kind::kUnmappedJunction)],
            (KindScore{.in_reach = 1, .found = 0, .reported = 1, .false_reports = 1}));
}

// A direction-off the robot could not pin on one slot (`or_slot`) finds a seeded one at either
// slot, and is false only when neither is seeded off.
TEST(WorldScore, ADirectionOffOnOneOfTwoSlotsFindsEither) {
  using Kind = Discrepancy::Kind;
  const auto direction = [](std::uint16_t slot) {
    return Discrepancy{
        .kind = Kind::kDirectionOff, .manhole = ManholeId{1}, .slot = SlotIndex{slot}};
  };
  Discrepancy either = direction(0);
  either.or_slot = SlotIndex{1};
  const Reach reach{.manholes_arrived = {ManholeId{1}},
                    .mouths_driven = {{ManholeId{1}, SlotIndex{0}}, {ManholeId{1}, SlotIndex{1}}}};
  for (const std::uint16_t seeded_slot : {std::uint16_t{0}, std::uint16_t{1}}) {
    const DiscrepancyScore s = score_discrepancies(
        {direction(seeded_slot)}, {FoundDiscrepancy{.discrepancy = either}}, reach);
    EXPECT_EQ(s.found, 1U) << seeded_slot;
    EXPECT_EQ(s.false_reports, 0U) << seeded_slot;
  }
  const DiscrepancyScore neither =
      score_discrepancies({direction(2)}, {FoundDiscrepancy{.discrepancy = either}}, reach);
  EXPECT_EQ(neither.false_reports, 1U);
}

ScoresByKind kinds(std::initializer_list<std::pair<Discrepancy::Kind, KindScore>> scores) {
  ScoresByKind by_kind{};
  for (const auto& [kind, score] : scores) by_kind[static_cast<std::size_t>(kind)] = score;
  return by_kind;
}

RunRecord scored(std::size_t index, WorldScore w) {
  RunResult r;
  r.index = index;
  r.oracle_can_end = true;
  r.could_reach_exit = true;
  r.ours.world = w;
  return RunRecord{.index = index, .result = r};
}

TEST(WorldScore, ACampaignPoolsItsRunsAndSaysNullWithoutWorldErrors) {
  CampaignSpec spec;
  spec.map_name = "map.json";
  spec.mission_name = "mission.json";
  spec.runs = 3;
  const std::vector<RunRecord> records{
      scored(0, {.arrivals = 10,
                 .correct_arrivals = 9,
                 .pipes_measured = 2,
                 .length_rms_pct = 3,
                 .seeded_in_reach = 4,
                 .found = 3,
                 .reported = 5,
                 .false_reports = 1,
                 .by_kind = kinds({{Discrepancy::Kind::kLengthOff, {4, 3, 4, 1}},
                                   {Discrepancy::Kind::kMissingLateral, {0, 0, 1, 0}}})}),
      scored(1, {.arrivals = 10,
                 .correct_arrivals = 10,
                 .pipes_measured = 6,
                 .length_rms_pct = 1,
                 .seeded_in_reach = 6,
                 .found = 6,
                 .reported = 5,
                 .false_reports = 0,
                 .by_kind = kinds({{Discrepancy::Kind::kLengthOff, {6, 6, 5, 0}}})}),
      scored(2, {}),  // a run with no arrival and nothing measured
  };
  const Summary s = summarize(spec, records);
  ASSERT_TRUE(s.world.has_value());
  EXPECT_EQ(s.world->runs, 3U);
  EXPECT_DOUBLE_EQ(*s.world->correct_arrivals_pct(), 95.0);
  // Over all 8 pipes: sqrt((2 * 3^2 + 6 * 1^2) / 8), not the mean of the runs' RMS.
  EXPECT_DOUBLE_EQ(*s.world->length_rms_pct(), std::sqrt(3.0));
  EXPECT_DOUBLE_EQ(*s.world->discrepancies_found_pct(), 90.0);
  EXPECT_DOUBLE_EQ(*s.world->false_reports_pct(), 10.0);
  std::ostringstream json;
  write_summary_json(s, json);
  const auto j = nlohmann::json::parse(json.str());
  EXPECT_DOUBLE_EQ(j["localisation"]["correct_arrivals_pct"].get<double>(), 95.0);
  EXPECT_DOUBLE_EQ(j["corrected_map"]["length_rms_pct"].get<double>(), std::sqrt(3.0));
  EXPECT_DOUBLE_EQ(j["corrected_map"]["discrepancies_found_pct"].get<double>(), 90.0);
  EXPECT_DOUBLE_EQ(j["corrected_map"]["false_reports_pct"].get<double>(), 10.0);
  // Kind by kind: pooled, every kind named, null where there is nothing to share.
  const auto& length = j["corrected_map"]["by_kind"]["length-off"];
  EXPECT_EQ(length["found"].get<int>(), 9);
  EXPECT_EQ(length["in_reach"].get<int>(), 10);
  EXPECT_DOUBLE_EQ(length["found_pct"].get<double>(), 90.0);
  EXPECT_DOUBLE_EQ(length["false_reports_pct"].get<double>(), 100.0 / 9);
  EXPECT_TRUE(j["corrected_map"]["by_kind"]["missing-lateral"]["found_pct"].is_null());
  EXPECT_EQ(j["corrected_map"]["by_kind"]["direction-off"]["reported"].get<int>(), 0);
  std::ostringstream md;
  write_summary_markdown(s, md);
  EXPECT_NE(md.str().find("| 95.0 % (19 of 20) |"), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("| length-off | 90.0 % (9 of 10) | 11.1 % (1 of 9) |"), std::string::npos)
      << md.str();
  EXPECT_NE(md.str().find("| missing-lateral | none (none within reach) | 0.0 % (0 of 1) |"),
            std::string::npos)
      << md.str();
  EXPECT_EQ(md.str().find("| direction-off |"), std::string::npos) << md.str();
  // Each line reads back with its score (the shares are derived, not read).
  for (const RunRecord& r : records) {
    const std::string line = run_json_line(r);
    const Result<RunRecord> back = parse_run_line(line, "runs.jsonl", r.index + 1);
    ASSERT_TRUE(back.has_value()) << back.error().message;
    EXPECT_EQ(back->result->ours.world, r.result->ours.world);
    EXPECT_EQ(run_json_line(*back), line);
  }
  EXPECT_NE(run_json_line(records[2]).find("\"correct_arrivals_pct\":null"), std::string::npos);
  // A count that cannot be is refused, naming it.
  std::string bad = run_json_line(records[0]);
  bad.replace(bad.find("\"correct_arrivals\":9"), 20, "\"correct_arrivals\":11");
  const Result<RunRecord> refused = parse_run_line(bad, "runs.jsonl", 1);
  ASSERT_FALSE(refused.has_value());
  EXPECT_NE(refused.error().message.find("correct_arrivals"), std::string::npos);
  std::string bad_kind = run_json_line(records[0]);
  bad_kind.replace(bad_kind.find("\"found\":3,\"reported\":4"), 9, "\"found\":5");
  const Result<RunRecord> kind_refused = parse_run_line(bad_kind, "runs.jsonl", 1);
  ASSERT_FALSE(kind_refused.has_value());
  EXPECT_NE(kind_refused.error().message.find("by_kind.length-off"), std::string::npos)
      << kind_refused.error().message;
  // Without scores (world errors "none"): null, both.
  RunRecord plain = records[0];
  plain.result->ours.world.reset();
  std::ostringstream none;
  write_summary_json(summarize(spec, {plain}), none);
  const auto n = nlohmann::json::parse(none.str());
  EXPECT_TRUE(n["localisation"].is_null());
  EXPECT_TRUE(n["corrected_map"].is_null());
}

// A real run: with every pipe's length off and exact odometry the robot measures the world's
// lengths, not the map's, and every arrival it verifies is at the true manhole; with "none" ours
// is not scored.
TEST(WorldScore, ARunInATrueWorldIsScoredAgainstIt) {
  const auto ais_testbed = testing::load_ais_testbed();
  CampaignSpec spec;
  spec.seed = 3;
  spec.runs = 4;
  spec.rates = *parse_fault_rates("obstacles=0,danger=0,passages=0,malfunctions=0");
  spec.world_errors = "lengths=1,length_rel=0.2";
  const Result<RunResult> r = run_one(ais_testbed.map, ais_testbed.mission, run_settings(spec), 1);
  ASSERT_TRUE(r.has_value()) << r.error().message;
  ASSERT_TRUE(r->ours.world.has_value());
  const WorldScore& w = *r->ours.world;
  EXPECT_GT(w.arrivals, 3U);
  EXPECT_EQ(w.correct_arrivals, w.arrivals);
  EXPECT_GT(w.pipes_measured, 2U);
  // The map's lengths are 5 to 20 % off; the corrected map assumes 9 in 10 are right and keeps
  // the map's length where one pass (3 % noise, by the measuring's own account) agrees with it
  // within that noise, so a pipe 5 % off measured once stays near its map length.
  EXPECT_LT(w.length_rms_pct, 4.0);
  EXPECT_GT(w.seeded_in_reach, 2U);  // length-off on every pipe driven whole
  EXPECT_LE(w.found, w.seeded_in_reach);
  EXPECT_FALSE(r->baseline.world.has_value());
  spec.world_errors = "none";
  EXPECT_FALSE(
      run_one(ais_testbed.map, ais_testbed.mission, run_settings(spec), 1)->ours.world.has_value());
}

// What the scorer counts as reached, on the paper mission in an exact world: both mouths of every
// pipe driven whole were driven through, every mouth driven through is of a manhole arrived in
// or of the pipe the robot started in, and a mouth only seen (the robot arrived in its manhole
// and left by another) is not driven through.
TEST(WorldScore, TheMouthsDrivenThroughAreThoseOfTheRobotsWay) {
  const auto ais_testbed = testing::load_ais_testbed();
  const SewerMap& map = ais_testbed.map;
  const Result<hal::TrueWorld> truth = hal::make_true_world(map, hal::WorldErrorProfile{}, 1);
  ASSERT_TRUE(truth.has_value()) << truth.error().message;
  ManualClock clock;
  executor::Replanner replanner(map, ais_testbed.mission, {.clock = &clock});
  const auto& start = std::get<domain::InPipe>(replanner.progress().position);
  hal::SimRobot robot(truth->world, ais_testbed.mission.profile,
                      hal::InPipe{start.pipe, start.offset_m, hal::Heading::kTowardsEnd1}, {});
  executor::Executor executor(map, replanner, robot);
  WorldScorer scorer(map, *truth, robot);
  scorer.watch(executor);
  executor.run();
  const Reach& reach = scorer.reach();
  ASSERT_GE(reach.pipes_driven_whole.size(), 3U);
  const auto driven = [&](ManholeId m, SlotIndex s) {
    return std::find(reach.mouths_driven.begin(), reach.mouths_driven.end(), MouthOf{m, s}) !=
           reach.mouths_driven.end();
  };
  for (PipeId p : reach.pipes_driven_whole) {
    for (const PipeEnd& end : map.pipe(p).ends) {
      ASSERT_TRUE(end.manhole.has_value());
      EXPECT_TRUE(driven(*end.manhole, end.slot)) << map.pipe(p).name;
    }
  }
  std::size_t seen_only = 0;
  for (ManholeId m : reach.manholes_arrived) {
    for (std::size_t s = 0; s < map.slots(m).size(); ++s) {
      if (!driven(m, SlotIndex{static_cast<std::uint16_t>(s)})) ++seen_only;
    }
  }
  EXPECT_GT(seen_only, 0U);
  for (const MouthOf& mouth : reach.mouths_driven) {
    const PipeId pipe = map.slot(mouth.manhole, mouth.slot).pipe;
    const bool arrived = std::find(reach.manholes_arrived.begin(), reach.manholes_arrived.end(),
                                   mouth.manhole) != reach.manholes_arrived.end();
    EXPECT_TRUE(arrived || pipe == start.pipe) << map.manhole(mouth.manhole).name;
  }
}

}  // namespace
}  // namespace sewerplan::campaign
