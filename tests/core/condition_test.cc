// SPDX-License-Identifier: MIT
#include "sewerplan/core/condition.h"

#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/map_isybau.h"
#include "sewerplan/core/map_json.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/text_file.h"

#include "support/map_checks.h"
#include "support/paths.h"

namespace sewerplan {
namespace {

using testing::has_warning;
using ::testing::HasSubstr;

SewerMap street(Diagnostics& d) {
  Result<SewerMap> map = read_map(testing::dataset_path("isybau/street-2017.xml"), d);
  EXPECT_TRUE(map.has_value());
  return map.has_value() ? std::move(*map) : SewerMap{};
}

std::string zustand() {
  Result<std::string> text = read_text_file(testing::dataset_path("isybau/street-zustand.xml"));
  EXPECT_TRUE(text.has_value());
  return text.has_value() ? *text : std::string();
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

const Finding* find(const SewerMap& map, std::string_view pipe, std::string_view code) {
  for (const Finding& f : map.findings(*map.find_pipe(pipe))) {
    if (f.code == code) return &f;
  }
  return nullptr;
}

// Every finding of the latest inspection of each Haltung, on its pipe, at its offset from the
// upstream end: counted from the file's text, not by the reader.
TEST(Condition, JoinsEveryFindingToItsPipeAtItsPosition) {
  Diagnostics d;
  Result<SewerMap> map =
      read_condition(street(d), testing::dataset_path("isybau/street-zustand.xml"), d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  // Every RZustand of the file, less those of the superseded inspection of S1 (1), of manhole
  // S2 (1) and of X9, no pipe of the map (1): datasets/isybau/README.md.
  const std::size_t records = occurrences(zustand(), "<RZustand>");
  ASSERT_EQ(records, 10U);
  EXPECT_EQ(map->finding_count(), records - 3);
  EXPECT_EQ(map->findings(*map->find_pipe("S1")).size(), 4U);
  EXPECT_EQ(map->findings(*map->find_pipe("S3")).size(), 2U);
  EXPECT_EQ(map->findings(*map->find_pipe("S2")).size(), 1U);
  // With the flow: the station is the offset.
  const Finding* roots = find(*map, "S1", "BBA");
  ASSERT_NE(roots, nullptr);
  EXPECT_DOUBLE_EQ(roots->offset_m, 7.5);
  EXPECT_EQ(roots->characterisation, "B");
  EXPECT_EQ(roots->quantity1, 10.0);
  // Against the flow (from S2): the offset from S3 is the length less the station.
  const Finding* deformation = find(*map, "S3", "BAA");
  ASSERT_NE(deformation, nullptr);
  EXPECT_NEAR(deformation->offset_m, 44.72 - 4.72, 1e-9);
  EXPECT_NEAR(find(*map, "S3", "BBB")->offset_m, 44.72 - 20.0, 1e-9);
  EXPECT_DOUBLE_EQ(find(*map, "S2", "BAC")->offset_m, 18.0);
  EXPECT_EQ(find(*map, "S1", "BBC"), nullptr);  // the 2015 inspection is superseded
  EXPECT_TRUE(has_warning(d, "1 findings name no pipe of the map (the first: 'X9')"));
  EXPECT_TRUE(has_warning(d, "1 inspected objects are laterals or manholes"));
  EXPECT_TRUE(has_warning(d, "1 findings are superseded by a later inspection"));
}

// Inline Zustandsdaten, in the map's own file, give the same findings as a second file.
TEST(Condition, ReadsZustandsdatenInTheMapsOwnFile) {
  Result<std::string> stamm = read_text_file(testing::dataset_path("isybau/street-2017.xml"));
  ASSERT_TRUE(stamm.has_value());
  const std::string z = zustand();
  const std::size_t from = z.find("    <Zustandsdatenkollektiv>");
  const std::size_t to = z.find("  </Datenkollektive>");
  std::string both = *stamm;
  both.insert(both.find("  </Datenkollektive>"), z.substr(from, to - from));
  Diagnostics d1;
  Result<SewerMap> inline_map = read_map_isybau(both, "street-2017.xml", d1);
  ASSERT_TRUE(inline_map.has_value()) << inline_map.error().message;
  Diagnostics d2;
  Result<SewerMap> joined = read_condition_isybau(street(d2), z, "z.xml", d2);
  ASSERT_TRUE(joined.has_value());
  EXPECT_EQ(*inline_map, *joined);
}

TEST(Condition, FindingsSurviveTheJsonFormat) {
  Diagnostics d;
  Result<SewerMap> map = read_condition_isybau(street(d), zustand(), "z.xml", d);
  ASSERT_TRUE(map.has_value());
  std::ostringstream out;
  write_map_json(*map, out);
  Diagnostics d2;
  Result<SewerMap> back = read_map_json(out.str(), "back.json", d2);
  ASSERT_TRUE(back.has_value()) << back.error().message;
  EXPECT_EQ(*back, *map);
}

std::string condition_error(const std::string& text) {
  Diagnostics d;
  SewerMap map = street(d);
  Result<SewerMap> joined = read_condition_isybau(std::move(map), text, "z.xml", d);
  EXPECT_FALSE(joined.has_value());
  return joined.has_value() ? "" : joined.error().message;
}

TEST(Condition, RefusesFilesWithoutFindingsAndOtherFormats) {
  EXPECT_THAT(condition_error("<Identifikation><Version>2017</Version></Identifikation>"),
              HasSubstr("no Zustandsdaten in this file"));
  EXPECT_THAT(condition_error("<DATA><HI/></DATA>"), HasSubstr("a DWA-M 150 file"));
  std::string bad = zustand();
  bad.replace(bad.find("<Station>7.50"), 13, "<Station>7,50");
  EXPECT_THAT(condition_error(bad), HasSubstr("RZustand[2]/Station: error: inspection of S1: "
                                              "Station is not a number: '7,50'"));
}

TEST(Condition, RefusesAnUnknownInspectionDirection) {
  std::string bad = zustand();
  bad.replace(bad.find("<Inspektionsrichtung>O"), 22, "<Inspektionsrichtung>X");
  EXPECT_THAT(condition_error(bad), HasSubstr("Inspektionsrichtung must be O"));
}

std::string complementary() {
  Result<std::string> text =
      read_text_file(testing::test_data_path("isybau/complementary-zustand.xml"));
  EXPECT_TRUE(text.has_value());
  return text.has_value() ? *text : std::string();
}

std::vector<std::pair<std::string, double>> findings_of(const SewerMap& map,
                                                        std::string_view pipe) {
  std::vector<std::pair<std::string, double>> out;
  for (const Finding& f : map.findings(*map.find_pipe(pipe))) out.emplace_back(f.code, f.offset_m);
  return out;
}

// Issue 31: one pipe inspected from both ends at one date and time (the camera could not pass),
// as in the official ISYBAU 2013 sample: both halves stand, each placed from its own end. Only
// the later entry was kept, and with it a BBE obstacle (a likely blockage) was lost.
TEST(Condition, Issue31InspectionsFromBothEndsComplementEachOther) {
  Diagnostics d;
  Result<SewerMap> map = read_condition_isybau(street(d), complementary(), "z.xml", d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  using F = std::pair<std::string, double>;
  // Sorted by offset: from S1 (O) BCD 0, BAJ 3, BDC 9.9; from S2 (U, 30 m less the station):
  // BBE and BDC at 10.2, BAJ 26, BCD 30.
  const std::vector<F> found = findings_of(*map, "S1");
  ASSERT_EQ(found.size(), 7U);
  EXPECT_EQ(found[0], F("BCD", 0.0));
  EXPECT_EQ(found[1], F("BAJ", 3.0));
  EXPECT_EQ(found[2], F("BDC", 9.9));
  EXPECT_EQ(found[3].first, "BBE");
  EXPECT_NEAR(found[3].second, 30 - 19.8, 1e-9);
  EXPECT_NEAR(found[5].second, 30 - 4.0, 1e-9);
  EXPECT_EQ(found[6], F("BCD", 30.0));
  EXPECT_FALSE(has_warning(d, "superseded"));
  // In the map's own file alike.
  Result<std::string> stamm = read_text_file(testing::dataset_path("isybau/street-2017.xml"));
  ASSERT_TRUE(stamm.has_value());
  const std::string z = complementary();
  const std::size_t from = z.find("    <Zustandsdatenkollektiv>");
  const std::size_t to = z.find("  </Datenkollektive>");
  std::string both = *stamm;
  both.insert(both.find("  </Datenkollektive>"), z.substr(from, to - from));
  Diagnostics d2;
  Result<SewerMap> inline_map = read_map_isybau(both, "street.xml", d2);
  ASSERT_TRUE(inline_map.has_value()) << inline_map.error().message;
  EXPECT_EQ(findings_of(*inline_map, "S1"), found);
}

// A later inspection supersedes the earlier findings only on the stretch it covered: a complete
// one (it reached the far node, BCE) all of them; one abandoned at 8 m those up to 8 m.
TEST(Condition, Issue31ALaterInspectionSupersedesOnlyTheStretchItCovered) {
  const std::string later_from_s1 =
      "      <InspizierteAbwassertechnischeAnlage>\n"
      "        <Objektbezeichnung>S1</Objektbezeichnung>\n"
      "        <Anlagentyp>1</Anlagentyp>\n"
      "        <OptischeInspektion>\n"
      "          <Inspektionsdatum>2021-06-01</Inspektionsdatum>\n"
      "          <Uhrzeit>09:00:00</Uhrzeit>\n"
      "          <Rohrleitung>\n"
      "            <Inspektionsrichtung>O</Inspektionsrichtung>\n"
      "            <Inspektionsdaten>\n"
      "              <RZustand><Station>0.00</Station><InspektionsKode>BCD</InspektionsKode>"
      "</RZustand>\n"
      "              <RZustand><Station>END</Station><InspektionsKode>LAST</InspektionsKode>"
      "</RZustand>\n"
      "            </Inspektionsdaten>\n"
      "          </Rohrleitung>\n"
      "        </OptischeInspektion>\n"
      "      </InspizierteAbwassertechnischeAnlage>\n";
  auto with_later = [&](std::string_view station, std::string_view code) {
    std::string later = later_from_s1;
    later.replace(later.find("END"), 3, station);
    later.replace(later.find("LAST"), 4, code);
    std::string text = complementary();
    text.insert(text.find("    </Zustandsdatenkollektiv>"), later);
    Diagnostics d;
    Result<SewerMap> map = read_condition_isybau(street(d), text, "z.xml", d);
    EXPECT_TRUE(map.has_value());
    return std::pair(
        map.has_value() ? findings_of(*map, "S1") : std::vector<std::pair<std::string, double>>{},
        d);
  };
  using F = std::pair<std::string, double>;
  {
    const auto [found, d] = with_later("30.00", "BCE");
    EXPECT_EQ(found, (std::vector<F>{{"BCD", 0.0}, {"BCE", 30.0}}));
    EXPECT_TRUE(has_warning(d, "7 findings are superseded by a later inspection"));
  }
  {
    // Abandoned at 8 m: the earlier BCD and BAJ from S1 are superseded; the BDC at 9.9 m and
    // everything seen from S2 (the BBE at 10.2 m) still stand.
    const auto [found, d] = with_later("8.00", "BDC");
    ASSERT_EQ(found.size(), 7U);
    EXPECT_EQ(found[0], F("BCD", 0.0));
    EXPECT_EQ(found[1], F("BDC", 8.0));
    EXPECT_EQ(found[2], F("BDC", 9.9));
    EXPECT_EQ(found[3].first, "BBE");
    EXPECT_TRUE(has_warning(d, "2 findings are superseded by a later inspection"));
  }
}

// The default table, for MAKRO (body width 0.22 m): a collapse and a deformation leaving 0.2 m
// of a 0.4 m pipe close their places; roots leaving 0.27 m may block; a displaced joint is a
// danger; the inspection's start and end markers mean nothing.
TEST(ConditionRisk, DefaultTableClosesCollapsesAndNarrowDeformations) {
  Diagnostics d;
  Result<SewerMap> map = read_condition_isybau(street(d), zustand(), "z.xml", d);
  ASSERT_TRUE(map.has_value());
  RobotProfile profile = *builtin_profile("makro-plus");
  profile.body_width_m = 0.22;
  const std::vector<FindingRisk> risks = assess_findings(*map, profile, default_risk_table());
  ASSERT_EQ(risks.size(), map->finding_count());
  auto risk_of = [&](std::string_view pipe, std::string_view code) {
    const Finding* f = find(*map, pipe, code);
    return risks[static_cast<std::size_t>(f - map->findings().data())];
  };
  EXPECT_EQ(risk_of("S2", "BAC").effect, RiskEffect::kImpassable);
  EXPECT_EQ(risk_of("S3", "BAA").effect, RiskEffect::kImpassable);
  EXPECT_THAT(risk_of("S3", "BAA").reason, HasSubstr("BAA deformation leaves 0.2 m"));
  EXPECT_EQ(risk_of("S1", "BBA").effect, RiskEffect::kBlockage);
  EXPECT_NEAR(risk_of("S1", "BBA").blockage_probability, 0.2 + 0.01 * 10, 1e-12);
  EXPECT_EQ(risk_of("S1", "BAJ").effect, RiskEffect::kDanger);
  EXPECT_EQ(risk_of("S1", "BCD").effect, RiskEffect::kNone);
  const std::vector<Blockage> closed = impassable_blockages(*map, risks);
  ASSERT_EQ(closed.size(), 2U);
  // A slimmer robot passes the deformation: only the collapse closes.
  profile.body_width_m = 0.15;
  EXPECT_EQ(impassable_blockages(*map, assess_findings(*map, profile, default_risk_table())).size(),
            1U);
  // The table is data: an empty one closes nothing.
  EXPECT_TRUE(impassable_blockages(*map, assess_findings(*map, profile, RiskTable{})).empty());
}

// What each risk mode makes of each finding (finding_use: the operator station draws it) is what
// close_findings adds to the mission: a blockage for each closed one, a hazard for each weighed.
TEST(ConditionRisk, CloseFindingsAppliesExactlyWhatFindingUseSaysInEveryMode) {
  Diagnostics d;
  Result<SewerMap> map = read_condition_isybau(street(d), zustand(), "z.xml", d);
  ASSERT_TRUE(map.has_value());
  RobotProfile profile = *builtin_profile("makro-plus");
  profile.body_width_m = 0.22;
  const std::vector<FindingRisk> risks = assess_findings(*map, profile, default_risk_table());
  const auto use_of = [&](RiskMode mode, std::string_view pipe, std::string_view code) {
    const Finding* f = find(*map, pipe, code);
    return finding_use(risks[static_cast<std::size_t>(f - map->findings().data())], mode);
  };
  using U = FindingUse;
  EXPECT_EQ(use_of(RiskMode::kImpassable, "S2", "BAC"), U::kClosed);
  EXPECT_EQ(use_of(RiskMode::kImpassable, "S1", "BBA"), U::kIgnored);
  EXPECT_EQ(use_of(RiskMode::kExpected, "S1", "BBA"), U::kWeighed);
  EXPECT_EQ(use_of(RiskMode::kExpected, "S2", "BAC"), U::kClosed);
  EXPECT_EQ(use_of(RiskMode::kExpected, "S1", "BAJ"), U::kIgnored);  // a danger is not weighed
  EXPECT_EQ(use_of(RiskMode::kAvoid, "S1", "BAJ"), U::kClosed);
  EXPECT_EQ(use_of(RiskMode::kAvoid, "S1", "BCD"), U::kIgnored);
  EXPECT_EQ(use_of(RiskMode::kIgnore, "S2", "BAC"), U::kIgnored);
  for (const RiskMode mode :
       {RiskMode::kIgnore, RiskMode::kImpassable, RiskMode::kAvoid, RiskMode::kExpected}) {
    Mission mission;
    mission.profile = profile;
    std::vector<Blockage> closed;
    std::vector<Hazard> weighed;
    for (const FindingRisk& r : risks) {
      const Finding& f = map->findings()[r.finding];
      if (finding_use(r, mode) == U::kClosed) closed.push_back({f.pipe, f.offset_m});
      if (finding_use(r, mode) == U::kWeighed) {
        weighed.push_back({f.pipe, f.offset_m, r.blockage_probability, r.reason});
      }
    }
    EXPECT_EQ(close_findings(*map, mission, mode, default_risk_table()), closed.size());
    EXPECT_EQ(mission.blockages, closed);
    EXPECT_EQ(mission.hazards, weighed);
  }
  EXPECT_EQ(to_string(U::kWeighed), "weighed");
}

TEST(Condition, NamesTheMainCodesOfDinEn13508_2) {
  EXPECT_EQ(finding_code_name("BBA"), "roots");
  EXPECT_EQ(finding_code_name("BAC"), "break or collapse");
  EXPECT_EQ(finding_code_name("BCD"), "start node");
  EXPECT_EQ(finding_code_name("BDC"), "inspection abandoned");
  EXPECT_EQ(finding_code_name("DAB"), "");  // a manhole's code: not a pipe's
  EXPECT_EQ(finding_code_name("bba"), "");  // as the risk table matches codes: case counts
  EXPECT_EQ(finding_code_name(""), "");
}

// DIN EN 13508-2 tells a break (A: pieces displaced, B: pieces missing) from a collapse (C) by
// the characterisation: only a collapse, or a BAC that does not say which, closes the pipe.
TEST(ConditionRisk, DefaultTableTellsABreakFromACollapse) {
  const std::string collapse =
      "<InspektionsKode>BAC</InspektionsKode>\n"
      "              <Charakterisierung1>C</Charakterisierung1>";
  const std::string text = zustand();
  const std::size_t at = text.find(collapse);
  ASSERT_NE(at, std::string::npos);
  auto bac_with = [&](std::string_view characterisation) {
    std::string changed = text;
    changed.replace(at, collapse.size(),
                    characterisation.empty()
                        ? std::string("<InspektionsKode>BAC</InspektionsKode>")
                        : "<InspektionsKode>BAC</InspektionsKode><Charakterisierung1>" +
                              std::string(characterisation) + "</Charakterisierung1>");
    Diagnostics d;
    Result<SewerMap> map = read_condition_isybau(street(d), changed, "z.xml", d);
    EXPECT_TRUE(map.has_value());
    if (!map.has_value()) return FindingRisk{};
    const std::vector<FindingRisk> risks =
        assess_findings(*map, *builtin_profile("makro-plus"), default_risk_table());
    const Finding* f = find(*map, "S2", "BAC");
    EXPECT_NE(f, nullptr);
    return f == nullptr ? FindingRisk{}
                        : risks[static_cast<std::size_t>(f - map->findings().data())];
  };
  EXPECT_EQ(bac_with("C").effect, RiskEffect::kImpassable);
  EXPECT_THAT(bac_with("C").reason, HasSubstr("collapse"));
  const FindingRisk missing_pieces = bac_with("B");
  EXPECT_EQ(missing_pieces.effect, RiskEffect::kBlockage);
  EXPECT_DOUBLE_EQ(missing_pieces.blockage_probability, 0.5);
  EXPECT_EQ(bac_with("A").effect, RiskEffect::kDanger);
  EXPECT_EQ(bac_with("").effect, RiskEffect::kImpassable);
}

}  // namespace
}  // namespace sewerplan
