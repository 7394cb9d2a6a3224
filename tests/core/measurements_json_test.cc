// SPDX-License-Identifier: MIT
#include "sewerplan/core/measurements_json.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "support/small_map.h"

namespace sewerplan {
namespace {

using testing::SmallMap;

SewerMap line(double east_y = 0) {
  return SmallMap()
      .manhole("M1", 0, 0, true)
      .manhole("M2", 10, east_y)
      .manhole("M3", 20, 0)
      .pipe("P1", "M1", "M2")
      .pipe("P2", "M2", "M3")
      .invert("M2", "P2", 0.1)
      .build();
}

MapMeasurements sample(const SewerMap& map) {
  MapMeasurements m = measurements_of(map, {"makro", "paper", "2026-12-06T07:00:00Z"});
  add_length(m, *map.find_pipe("P1"), 11.5, 0.0925, 0);
  add_position(m, *map.find_manhole("M2"), 11.5, 0, 0.0925, 0);
  ManholeSignature seen = expected_signature(map, *map.find_manhole("M2"), SlotIndex{0});
  seen.slots[1].relative_deg = 171.5;
  add_observation(m, *map.find_manhole("M2"), SlotIndex{0}, seen, 0);
  m.junctions.push_back({*map.find_pipe("P2"), 3.5, 0.25, seen, 0});
  add_turn(m, *map.find_manhole("M2"),
           {.from = SlotIndex{0}, .to = SlotIndex{1}, .relative_deg = 172.25, .sigma_deg = 1});
  m.discrepancies = discrepancies(m, map);
  return m;
}

TEST(MeasurementsJson, RoundTripsEveryMeasurement) {
  const SewerMap map = line();
  const MapMeasurements m = sample(map);
  ASSERT_FALSE(m.discrepancies.empty());
  // M2's two mouths turned 7.75 degrees off the map: one of the two is off (map_measurements.h).
  ASSERT_TRUE(std::any_of(m.discrepancies.begin(), m.discrepancies.end(),
                          [](const FoundDiscrepancy& f) { return f.discrepancy.or_slot; }));
  const std::string text = measurements_json(m, map);
  Diagnostics d;
  const Result<MapMeasurements> back = read_measurements_json(text, "m.json", map, d);
  ASSERT_TRUE(back.has_value()) << back.error().message;
  EXPECT_EQ(*back, m);
  EXPECT_EQ(measurements_json(*back, map), text);
}

// The first error of reading `text`, which must fail.
std::string first_error(const std::string& text, const SewerMap& map) {
  Diagnostics d;
  const Result<MapMeasurements> r = read_measurements_json(text, "bad.json", map, d);
  EXPECT_FALSE(r.has_value());
  return r.has_value() ? "" : r.error().message;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(MeasurementsJson, AFileOfAnotherMapIsAnErrorAtItsFingerprint) {
  const SewerMap map = line();
  const std::string text = measurements_json(sample(map), map);
  const std::string e = first_error(text, line(1.0));
  EXPECT_NE(e.find("bad.json:$.map.fingerprint"), std::string::npos) << e;
  EXPECT_NE(e.find("not of map"), std::string::npos) << e;
}

TEST(MeasurementsJson, EveryProblemNamesFileAndJsonPath) {
  const SewerMap map = line();
  const std::string text = measurements_json(sample(map), map);
  struct Case {
    std::string from, to, where;
  };
  const Case cases[] = {
      {"\"pipe\": \"P1\"", "\"pipe\": \"P9\"", "bad.json:$.pipes[0].pipe"},
      {"\"variance_m2\": 0.0925,\n      \"count\"", "\"variance_m2\": -1,\n      \"count\"",
       "bad.json:$.pipes[0].variance_m2"},
      {"\"count\": 1,\n      \"sources\"", "\"count\": 0,\n      \"sources\"",
       "bad.json:$.pipes[0].count"},
      {"\"arrival_slot\": 1", "\"arrival_slot\": 5",
       "bad.json:$.manholes[0].observations[0]"
       ".arrival_slot"},
      {"\"source\": 0", "\"source\": 3", "bad.json:$.manholes[0].observations[0].source"},
      {"\"offset_m\": 3.5", "\"offset_m\": 30.5", "bad.json:$.junctions[0].offset_m"},
      {"\"to_slot\": 2", "\"to_slot\": 3", "bad.json:$.manholes[0].turns[0].to_slot"},
      {"\"to_slot\": 2", "\"to_slot\": 1", "bad.json:$.manholes[0].turns[0].to_slot"},
      {"\"direction_deg\": 172.25", "\"direction_deg\": 372.25",
       "bad.json:$.manholes[0].turns[0].direction_deg"},
      {"\"sigma_deg\": 1", "\"sigma_deg\": 0", "bad.json:$.manholes[0].turns[0].sigma_deg"},
      {"\"kind\": \"", "\"kind\": \"x", "bad.json:$.discrepancies[0].kind"},
      {"\"or_slot\": 2", "\"or_slot\": 1", "bad.json:$.discrepancies[1].or_slot"},
      {"\"or_slot\": 2", "\"or_slot\": 3", "bad.json:$.discrepancies[1].or_slot"},
      {"\"kind\": \"length-off\",", "\"kind\": \"length-off\", \"or_slot\": 1,",
       "bad.json:$.discrepancies[0].or_slot"},
      {"\"format\": \"sewerplan-measurements\"", "\"format\": \"sewerplan-learnt\"",
       "bad.json:$.format"},
      {"\"version\": 1", "\"version\": 2", "bad.json:$.version"},
      {"\"sources\": [\n    {", "\"sourcez\": 1, \"sources\": [\n    {", "bad.json:$.sourcez"},
  };
  for (const Case& c : cases) {
    const std::string e = first_error(replaced(text, c.from, c.to), map);
    EXPECT_NE(e.find(c.where), std::string::npos) << c.to << "\n" << e;
  }
}

TEST(MeasurementsJson, ASignatureWithNoSlotsIsAnError) {
  const SewerMap map = line();
  MapMeasurements m = sample(map);
  m.discrepancies.clear();
  const std::string text = measurements_json(m, map);
  const std::size_t slots = text.find("\"slots\": [");
  const std::size_t end = text.find(']', slots);
  const std::string bad = text.substr(0, slots) + "\"slots\": [" + text.substr(end);
  const std::string e = first_error(bad, map);
  EXPECT_NE(e.find("bad.json:$.manholes[0].observations[0].signature"), std::string::npos) << e;
  EXPECT_NE(e.find("at least one slot"), std::string::npos) << e;
  EXPECT_NE(first_error("{\"format\": ", map).find("bad.json:1:"), std::string::npos);
}

TEST(MeasurementsJson, TheDiscrepancyReportSaysWhatWasApplied) {
  const SewerMap map = line();
  const MapMeasurements m = sample(map);
  const Result<CorrectedMap> fixed = corrected_map(map, m);
  ASSERT_TRUE(fixed.has_value()) << fixed.error().message;
  const std::string report = discrepancy_report_json(*fixed, m, map);
  EXPECT_NE(report.find("\"format\": \"sewerplan-discrepancies\""), std::string::npos);
  EXPECT_NE(report.find("\"description\": \"P1: length 11.50 m, the map says 10.00 m\""),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("\"applied\": false"), std::string::npos) << report;  // the junction
  EXPECT_NE(report.find("\"mission\": \"paper\""), std::string::npos);
}

}  // namespace
}  // namespace sewerplan
