// SPDX-License-Identifier: MIT
#include "sewerplan/core/isybau_correction.h"

#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/core/passage_motion.h"
#include "sewerplan/core/text_file.h"

#include "support/paths.h"
#include "support/small_map.h"

namespace sewerplan {
namespace {

struct Source {
  std::string file;
  std::string text;
  SewerMap map;
};

Source source(const std::string& name) {
  const std::string file = testing::dataset_path("isybau/" + name).string();
  Result<std::string> text = read_text_file(file);
  EXPECT_TRUE(text.has_value());
  Diagnostics d;
  Result<SewerMap> map = read_map_isybau(*text, file, d);
  EXPECT_TRUE(map.has_value()) << (map.has_value() ? "" : map.error().message);
  return {file, *text, std::move(*map)};
}

// Lengths of pipes S1, S2 and S4 (where the file has them) off by a metre or more, manhole S1
// 3 m east and 2 m south: the corrected map (positions reported) and its measurements.
struct Measured {
  MapMeasurements measurements;
  CorrectedMap corrected;
};

Measured measure(const SewerMap& map, bool move_s1 = true) {
  MapMeasurements m = measurements_of(
      map, {.robot = "makro-plus", .mission = "street--check", .date = "2026-12-06T07:00:00Z"});
  const std::vector<std::pair<const char*, double>> lengths{
      {"S1", 31.234}, {"S2", 28.9}, {"S4", 13.5}};
  for (const auto& [name, length] : lengths) {
    if (auto p = map.find_pipe(name)) add_length(m, *p, length, 0.0004, 0);
  }
  if (move_s1) {
    const Manhole& s1 = map.manhole(*map.find_manhole("S1"));
    add_position(m, *map.find_manhole("S1"), s1.position.x_m + 3, s1.position.y_m - 2, 0.01, 0);
  }
  DiscrepancyThresholds thresholds;
  thresholds.report_positions = true;
  m.discrepancies = discrepancies(m, map, thresholds);
  Result<CorrectedMap> corrected = corrected_map(map, m);
  EXPECT_TRUE(corrected.has_value());
  return {std::move(m), std::move(*corrected)};
}

std::vector<std::string> lines_of(const std::string& text, bool without_our_comments) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  bool in_comment = false;
  while (std::getline(in, line)) {
    if (without_our_comments) {
      if (line.find("<!-- sewerplan: ") != std::string::npos) in_comment = true;
      if (in_comment) {
        in_comment = line.find("-->") == std::string::npos;
        continue;
      }
    }
    lines.push_back(line);
  }
  return lines;
}

class IsybauCorrectionRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(IsybauCorrectionRoundTrip, ReadsBackWithTheCorrectedValuesAndEverythingElseAsItWas) {
  const Source s = source(GetParam());
  const Measured m = measure(s.map);
  Diagnostics d;
  Result<IsybauCorrection> out = correct_isybau(s.text, s.file, m.corrected, m.measurements, d);
  ASSERT_TRUE(out.has_value()) << out.error().message;
  EXPECT_EQ(out->positions, 1U);
  EXPECT_EQ(out->lengths, s.map.find_pipe("S4") ? 3U : 2U);
  Diagnostics again;
  Result<SewerMap> back = read_map_isybau(out->text, s.file, again);
  ASSERT_TRUE(back.has_value()) << back.error().message;
  const SewerMap& fixed = m.corrected.map;
  ASSERT_EQ(back->pipe_count(), s.map.pipe_count());
  ASSERT_EQ(back->manhole_count(), s.map.manhole_count());
  EXPECT_EQ(back->crs(), s.map.crs());
  for (PipeId p : s.map.pipe_ids()) {
    const Pipe& was = s.map.pipe(p);
    const Pipe& got = back->pipe(p);
    SCOPED_TRACE(was.name);
    EXPECT_EQ(got.name, was.name);
    EXPECT_NEAR(got.length_m, fixed.pipe(*fixed.find_pipe(was.name)).length_m, 0.005);
    EXPECT_EQ(got.diameter_m, was.diameter_m);
    EXPECT_EQ(got.height_m, was.height_m);
    EXPECT_EQ(got.shape, was.shape);
    EXPECT_EQ(got.ends, was.ends);
  }
  EXPECT_NEAR(back->pipe(*back->find_pipe("S1")).length_m, 31.23, 1e-9);
  const ManholeId s1 = *s.map.find_manhole("S1");
  for (ManholeId id : s.map.manhole_ids()) {
    const Manhole& was = s.map.manhole(id);
    const Manhole& got = back->manhole(id);
    SCOPED_TRACE(was.name);
    EXPECT_EQ(got.name, was.name);
    const Position want = fixed.manhole(*fixed.find_manhole(was.name)).position;
    EXPECT_NEAR(got.position.x_m, want.x_m, 0.005);
    EXPECT_NEAR(got.position.y_m, want.y_m, 0.005);
    EXPECT_EQ(got.position.z_m, was.position.z_m);
    EXPECT_EQ(got.diameter_m, was.diameter_m);
    EXPECT_EQ(got.exit, was.exit);
    const auto got_slots = back->slots(id);
    const auto was_slots = s.map.slots(id);
    ASSERT_EQ(got_slots.size(), was_slots.size());
    for (std::size_t i = 0; i < was_slots.size(); ++i) {
      EXPECT_EQ(got_slots[i].pipe, was_slots[i].pipe);
      EXPECT_EQ(got_slots[i].invert_z_m, was_slots[i].invert_z_m);
      // A moved node's directions follow from the pipes' lines, which stay (the header).
      if (id != s1) {
        EXPECT_EQ(got_slots[i].azimuth_deg, was_slots[i].azimuth_deg);
      }
    }
  }
  EXPECT_EQ(back->findings().size(), s.map.findings().size());
  EXPECT_NEAR(back->manhole(s1).position.x_m, s.map.manhole(s1).position.x_m + 3, 0.005);
}

INSTANTIATE_TEST_SUITE_P(EveryDialect, IsybauCorrectionRoundTrip,
                         ::testing::Values("street-2017.xml", "street-2013.xml", "street-2006.xml",
                                           "street-latin1.xml", "street-optional.xml",
                                           "street-polyline.xml"));

// Byte for byte: only the changed values' lines differ, besides our comments.
TEST(IsybauCorrectionText, ChangesOnlyTheMeasuredValuesLines) {
  const Source s = source("street-2017.xml");
  const Measured m = measure(s.map);
  Diagnostics d;
  Result<IsybauCorrection> out = correct_isybau(s.text, s.file, m.corrected, m.measurements, d);
  ASSERT_TRUE(out.has_value()) << out.error().message;
  const std::vector<std::string> was = lines_of(s.text, false);
  const std::vector<std::string> got = lines_of(out->text, true);
  ASSERT_EQ(got.size(), was.size());
  std::vector<std::string> changed;
  for (std::size_t i = 0; i < was.size(); ++i) {
    if (got[i] != was[i]) changed.push_back(got[i]);
  }
  // S1's one Punkt (Rechtswert 0.0 -> 3.00, Hochwert 0.0 -> -2.00), then S1, S2, S4's lengths.
  EXPECT_EQ(changed,
            (std::vector<std::string>{
                "                <Rechtswert>3.00</Rechtswert>",
                "                <Hochwert>-2.00</Hochwert>", "          <Laenge>31.23</Laenge>",
                "          <Laenge>28.90</Laenge>", "          <Laenge>13.50</Laenge>"}))
      << out->text;
  EXPECT_NE(out->text.find("<!-- sewerplan: length measured 31.23 m (sigma 0.02 m, 1 drives); "
                           "the map said 30.00 m -->"),
            std::string::npos);
  EXPECT_NE(out->text.find("robot makro-plus, mission street- -check, 2026-12-06T07:00:00Z"),
            std::string::npos)
      << "the provenance, with its \"--\" made a valid comment";
}

TEST(IsybauCorrectionText, NothingMeasuredIsTheSourceAndTheProvenanceComment) {
  const Source s = source("street-2013.xml");
  MapMeasurements none = measurements_of(s.map, {.robot = "makro", .mission = "m", .date = "d"});
  Result<CorrectedMap> corrected = corrected_map(s.map, none);
  ASSERT_TRUE(corrected.has_value());
  Diagnostics d;
  Result<IsybauCorrection> out = correct_isybau(s.text, s.file, *corrected, none, d);
  ASSERT_TRUE(out.has_value());
  const std::size_t begin = out->text.find("<!-- sewerplan: ");
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = out->text.find("-->", begin) + 4;  // and its line break
  EXPECT_EQ(out->text.substr(0, begin) + out->text.substr(end), s.text);
}

TEST(IsybauCorrectionText, ALatin1FileStaysLatin1) {
  const Source s = source("street-latin1.xml");
  const Measured m = measure(s.map);
  Diagnostics d;
  Result<IsybauCorrection> out = correct_isybau(s.text, s.file, m.corrected, m.measurements, d);
  ASSERT_TRUE(out.has_value()) << out.error().message;
  EXPECT_NE(out->text.find("S\xFC"
                           "d3"),
            std::string::npos);
  EXPECT_EQ(out->text.find("S\xC3\xBC"
                           "d3"),
            std::string::npos);
  EXPECT_EQ(lines_of(out->text, true).size(), lines_of(s.text, false).size());
}

TEST(IsybauCorrectionText, AHaltungWithoutALengthGainsALaengeBeforeItsProfil) {
  const Source s = source("street-optional.xml");  // S4: no Laenge, its line's 12 m
  const Measured m = measure(s.map, false);
  Diagnostics d;
  Result<IsybauCorrection> out = correct_isybau(s.text, s.file, m.corrected, m.measurements, d);
  ASSERT_TRUE(out.has_value()) << out.error().message;
  EXPECT_NE(out->text.find("<Laenge>13.50</Laenge>\n          <Profil>"), std::string::npos)
      << out->text;
  // S2 has a DMPLaenge and no Laenge: the importer's length, written there.
  EXPECT_NE(out->text.find("<DMPLaenge>28.90</DMPLaenge>"), std::string::npos);
}

TEST(IsybauCorrectionText, MeasurementsOfAnotherMapAreANamedError) {
  const Source s = source("street-2017.xml");
  const SewerMap other = testing::SmallMap()
                             .manhole("M1", 0, 0, true)
                             .manhole("M2", 10, 0)
                             .pipe("P1", "M1", "M2")
                             .build();
  const Measured m = measure(other, false);
  Diagnostics d;
  Result<IsybauCorrection> out = correct_isybau(s.text, s.file, m.corrected, m.measurements, d);
  ASSERT_FALSE(out.has_value());
  EXPECT_EQ(out.error().code, ErrorCode::kInvalidArgument);
  const std::string& message = out.error().message;
  EXPECT_NE(message.find("street-2017.xml: the measurements are of map '" + other.name() +
                         "' (geometry fingerprint " + map_geometry_fingerprint(other) + ")"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("'street-2017' (fingerprint " + map_geometry_fingerprint(s.map) + ")"),
            std::string::npos)
      << message;
}

TEST(IsybauCorrectionText, ACorrectedMapOfAnotherNetworkIsANamedError) {
  const Source s = source("street-2017.xml");
  const Measured right = measure(s.map, false);
  const SewerMap other = testing::SmallMap()
                             .manhole("M1", 0, 0, true)
                             .manhole("M2", 10, 0)
                             .pipe("P1", "M1", "M2")
                             .build();
  Measured wrong = measure(other, false);
  Diagnostics d;
  Result<IsybauCorrection> out =
      correct_isybau(s.text, s.file, wrong.corrected, right.measurements, d);
  ASSERT_FALSE(out.has_value());
  EXPECT_EQ(out.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(out.error().message.find("has no pipe S1 of this ISYBAU file"), std::string::npos)
      << out.error().message;
}

}  // namespace
}  // namespace sewerplan
