// SPDX-License-Identifier: MIT
#include "sewerplan/core/crs.h"

#include <regex>
#include <sstream>
#include <string>
#include <utility>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/map_builder.h"
#include "sewerplan/core/map_isybau.h"
#include "sewerplan/core/map_json.h"

#include "map_json_fast.h"
#include "support/isybau_georeferenced.h"

namespace sewerplan {
namespace {

using ::testing::HasSubstr;

TEST(Crs, ReadsAuthorityAndCodeInAnyCaseAndTheOgcUrn) {
  for (const char* text : {"EPSG:25832", "epsg:25832", "urn:ogc:def:crs:EPSG::25832"}) {
    Result<Crs> crs = parse_crs(text);
    ASSERT_TRUE(crs.has_value()) << text << ": " << crs.error();
    EXPECT_EQ(crs->to_string(), "EPSG:25832") << text;
  }
}

TEST(Crs, RejectsWhatIsNotAuthorityColonPositiveCode) {
  for (const char* text : {"", "25832", "EPSG:", "EPSG:x", "EPSG:-5", "EPSG:0", "EPSG:258 32",
                           "EP5G:25832", ":25832", "EPSG:99999999999"}) {
    Result<Crs> crs = parse_crs(text);
    ASSERT_FALSE(crs.has_value()) << text;
    EXPECT_EQ(crs.error().code, ErrorCode::kInvalidArgument);
    EXPECT_THAT(crs.error().message, HasSubstr("expected AUTHORITY:CODE")) << text;
  }
}

constexpr std::string_view kMapWithCrs = R"({
  "format": "sewerplan-map", "version": 1, "name": "utm", "crs": "EPSG:25832",
  "manholes": [
    {"name": "A", "x_m": 477000, "y_m": 5760000, "diameter_m": 1,
     "slots": [{"pipe": "P", "azimuth_deg": 0}]},
    {"name": "B", "x_m": 477010, "y_m": 5760000, "diameter_m": 1,
     "slots": [{"pipe": "P", "azimuth_deg": 180}]}
  ],
  "pipes": [{"name": "P", "from": "A", "to": "B", "length_m": 10, "diameter_m": 0.4}]
})";

TEST(Crs, MapJsonKeepsItThroughAWriteAndARead) {
  Diagnostics d;
  Result<SewerMap> map = read_map_json(kMapWithCrs, "t.json", d);
  ASSERT_TRUE(map.has_value()) << map.error();
  ASSERT_TRUE(map->crs().has_value());
  EXPECT_EQ(map->crs()->to_string(), "EPSG:25832");
  std::ostringstream out;
  write_map_json(*map, out);
  EXPECT_THAT(out.str(), HasSubstr("\"crs\": \"EPSG:25832\""));
  Result<SewerMap> again = read_map_json(out.str(), "again.json", d);
  ASSERT_TRUE(again.has_value()) << again.error();
  EXPECT_EQ(*again, *map);
  // Both readers agree, and a map without one has none.
  Diagnostics document_d;
  Result<SewerMap> document = detail::read_map_json_document(kMapWithCrs, "t.json", document_d);
  ASSERT_TRUE(document.has_value());
  EXPECT_EQ(*document, *map);
  EXPECT_FALSE(MapBuilder::with_crs(*map, std::nullopt).crs().has_value());
}

TEST(Crs, AnInvalidOneInMapJsonIsAnErrorAtItsPath) {
  std::string text(kMapWithCrs);
  text.replace(text.find("EPSG:25832"), 10, "UTM32");
  EXPECT_FALSE(detail::read_map_json_fast(text, "t.json").has_value());
  Diagnostics d;
  Result<SewerMap> map = read_map_json(text, "t.json", d);
  ASSERT_FALSE(map.has_value());
  EXPECT_THAT(map.error().message, HasSubstr("$.crs"));
  EXPECT_THAT(map.error().message, HasSubstr("\"UTM32\""));
}

bool says(const Diagnostics& d, const std::string& text) {
  for (const Diagnostic& w : d.all()) {
    if (w.message.find(text) != std::string::npos) return true;
  }
  return false;
}

Result<SewerMap> read_isybau(const std::string& text, Diagnostics& d) {
  return read_map_isybau(text, "street.xml", d);
}

TEST(Crs, IsybauTakesItFromTheLagesystem) {
  struct Case {
    const char* lagesystem;
    const char* crs;
  };
  for (const auto& [lagesystem, crs] :
       {Case{"ETRS89_UTM32", "EPSG:25832"}, Case{"DE_DHDN_3GK3_NW177", "EPSG:31467"},
        Case{"EPSG:25833", "EPSG:25833"}, Case{"31468", "EPSG:31468"}}) {
    Diagnostics d;
    Result<SewerMap> map = read_isybau(testing::georeferenced_street(lagesystem), d);
    ASSERT_TRUE(map.has_value()) << map.error();
    ASSERT_TRUE(map->crs().has_value()) << lagesystem;
    EXPECT_EQ(map->crs()->to_string(), crs) << lagesystem;
    EXPECT_DOUBLE_EQ(map->manhole(*map->find_manhole("S1")).position.x_m, testing::kStreetEasting);
  }
}

// The official ISYBAU 2013 and 2017 samples, and real exports, name the reference system in
// Geometrie/CRSLage; reading only Lagesystem left them without a CRS.
TEST(Crs, IsybauTakesItFromCrsLageAsTheOfficialSamplesWriteIt) {
  for (const auto& [lagesystem, crs] :
       {std::pair{"ETRS89_UTM32", "EPSG:25832"}, std::pair{"DE_DHDN_3GK2", "EPSG:31466"}}) {
    Diagnostics d;
    Result<SewerMap> map = read_isybau(testing::georeferenced_street(lagesystem, "CRSLage"), d);
    ASSERT_TRUE(map.has_value()) << map.error();
    ASSERT_TRUE(map->crs().has_value()) << lagesystem;
    EXPECT_EQ(map->crs()->to_string(), crs) << lagesystem;
  }
  Diagnostics unknown_d;
  Result<SewerMap> unknown =
      read_isybau(testing::georeferenced_street("Stadtnetz 7", "CRSLage"), unknown_d);
  ASSERT_TRUE(unknown.has_value()) << unknown.error();
  EXPECT_FALSE(unknown->crs().has_value());
  EXPECT_TRUE(says(unknown_d, "CRSLage \"Stadtnetz 7\" is not a reference system"));
}

// The official samples (and most German exports in UTM) write the zone before the easting:
// Rechtswert 32570429.702 is easting 570429.702 in zone 32. Read as it stands, every manhole was
// 32,000 km off and the whole file was rejected.
TEST(Crs, IsybauReadsUtmRechtswerteWithTheirZoneInFront) {
  const std::string text =
      std::regex_replace(testing::georeferenced_street("ETRS89_UTM32", "CRSLage"),
                         std::regex("<Rechtswert>4"), "<Rechtswert>324");
  ASSERT_NE(text.find("<Rechtswert>32477000"), std::string::npos);
  Diagnostics d;
  Result<SewerMap> map = read_isybau(text, d);
  ASSERT_TRUE(map.has_value()) << map.error();
  EXPECT_EQ(map->crs()->to_string(), "EPSG:25832");
  EXPECT_DOUBLE_EQ(map->manhole(*map->find_manhole("S1")).position.x_m, testing::kStreetEasting);
  EXPECT_DOUBLE_EQ(map->manhole(*map->find_manhole("S2")).position.x_m,
                   testing::kStreetEasting + 30);
  EXPECT_TRUE(says(d, "Rechtswerte carry the UTM zone number 32 in front"));
  // Lengths from the line (S4 has one) and directions are those of the unprefixed network.
  EXPECT_NEAR(map->pipe(*map->find_pipe("S1")).length_m, 30.0, 1e-9);
  // Gauss-Krueger Rechtswerte carry their zone by definition (EPSG:31466's false easting): kept.
  Diagnostics gk_d;
  Result<SewerMap> gk = read_isybau(testing::georeferenced_street("DE_DHDN_3GK2", "CRSLage"), gk_d);
  ASSERT_TRUE(gk.has_value()) << gk.error();
  EXPECT_DOUBLE_EQ(gk->manhole(*gk->find_manhole("S1")).position.x_m, testing::kStreetEasting);
  EXPECT_FALSE(says(gk_d, "UTM zone number"));
}

TEST(Crs, IsybauWithoutALagesystemOrAnUnknownOneHasNone) {
  Diagnostics d;
  Result<SewerMap> plain = read_isybau(testing::georeferenced_street(""), d);
  ASSERT_TRUE(plain.has_value()) << plain.error();
  EXPECT_FALSE(plain->crs().has_value());
  Diagnostics unknown_d;
  Result<SewerMap> unknown = read_isybau(testing::georeferenced_street("Stadtnetz 7"), unknown_d);
  ASSERT_TRUE(unknown.has_value()) << unknown.error();
  EXPECT_FALSE(unknown->crs().has_value());
  EXPECT_TRUE(says(unknown_d, "Lagesystem \"Stadtnetz 7\" is not a reference system"));
  EXPECT_TRUE(says(unknown_d, "give one with --crs"));
}

TEST(Crs, IsybauWithTwoLagesystemsHasNone) {
  std::string text = testing::georeferenced_street("ETRS89_UTM32");
  const std::size_t last = text.rfind("ETRS89_UTM32");
  text.replace(last, 12, "ETRS89_UTM33");
  Diagnostics d;
  Result<SewerMap> map = read_isybau(text, d);
  ASSERT_TRUE(map.has_value()) << map.error();
  EXPECT_FALSE(map->crs().has_value());
  EXPECT_TRUE(says(d, "differs from EPSG:25832"));
}

}  // namespace
}  // namespace sewerplan
