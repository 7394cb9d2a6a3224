// SPDX-License-Identifier: MIT
#include "sewerplan/core/map_json.h"

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/map_queries.h"
#include "sewerplan/core/text_file.h"

#include "map_json_fast.h"
#include "support/paths.h"

namespace sewerplan {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

constexpr std::string_view kSmallMap = R"({
  "format": "sewerplan-map", "version": 1, "name": "small",
  "manholes": [
    {"name": "A", "x_m": 0, "y_m": 0, "z_m": 1.5, "diameter_m": 1, "exit": true,
     "slots": [{"pipe": "P1", "azimuth_deg": 0}]},
    {"name": "B", "x_m": 10, "y_m": 0, "z_m": 1.25, "diameter_m": 1.2, "variant": "B",
     "slots": [{"pipe": "P1", "azimuth_deg": 180, "invert_m": 1.35},
               {"pipe": "P2", "azimuth_deg": 90},
               {"pipe": "S", "azimuth_deg": 315.5}]},
    {"name": "C", "x_m": 10, "y_m": 7.5, "z_m": 1.0, "diameter_m": 1,
     "slots": [{"pipe": "P2", "azimuth_deg": 270}]}
  ],
  "pipes": [
    {"name": "P1", "from": "A", "to": "B", "length_m": 10, "diameter_m": 0.4, "blockage_risk": 0.25},
    {"name": "P2", "from": "B", "to": "C", "length_m": 7.5, "diameter_m": 0.5,
     "shape": "egg", "height_m": 0.75},
    {"name": "S", "from": "B", "to": null, "length_m": 1.1, "diameter_m": 0.3}
  ],
  "inspection_points": [{"name": "W", "pipe": "P2", "offset_m": 2.5}]
})";

Result<SewerMap> read(std::string_view text, Diagnostics& d) {
  return read_map_json(text, "t.json", d);
}

TEST(MapJson, ReadsEveryFieldWithItsUnit) {
  Diagnostics d;
  Result<SewerMap> map = read(kSmallMap, d);
  ASSERT_TRUE(map.has_value()) << map.error();
  EXPECT_EQ(d.warning_count(), 0U);
  const ManholeId b = *map->find_manhole("B");
  EXPECT_EQ(map->manhole(b).variant, 'B');
  EXPECT_DOUBLE_EQ(map->manhole(b).diameter_m, 1.2);
  EXPECT_DOUBLE_EQ(map->slot(b, SlotIndex{0}).invert_z_m, 1.35);
  EXPECT_DOUBLE_EQ(map->slot(b, SlotIndex{1}).invert_z_m, 1.25) << "invert defaults to the floor";
  EXPECT_DOUBLE_EQ(passage_turn_deg(*map, b, SlotIndex{0}, SlotIndex{1}), 90.0);
  const Pipe& p2 = map->pipe(*map->find_pipe("P2"));
  EXPECT_EQ(p2.shape, PipeShape::kEgg);
  EXPECT_DOUBLE_EQ(p2.height_m, 0.75);
  EXPECT_EQ(map->pipe(*map->find_pipe("P1")).blockage_risk, 0.25f);
  EXPECT_FALSE(map->pipe(*map->find_pipe("S")).ends[1].manhole.has_value());
  EXPECT_DOUBLE_EQ(map->point(*map->find_point("W")).offset_m, 2.5);
  EXPECT_TRUE(map->manhole(*map->find_manhole("A")).exit);
}

TEST(MapJson, RoundTripsExactly) {
  Diagnostics d;
  Result<SewerMap> map = read(kSmallMap, d);
  ASSERT_TRUE(map.has_value());
  std::ostringstream first;
  write_map_json(*map, first);
  Result<SewerMap> again = read(first.str(), d);
  ASSERT_TRUE(again.has_value()) << again.error();
  EXPECT_EQ(*again, *map);
  std::ostringstream second;
  write_map_json(*again, second);
  EXPECT_EQ(second.str(), first.str());
}

TEST(MapJson, RoundTripsNumbersThatHaveNoShortDecimalForm) {
  std::string text(kSmallMap);
  text.replace(text.find("\"length_m\": 10,"), 15,
               "\"length_m\": 0.1000000000000000055511151231257827,");
  Diagnostics d;
  Result<SewerMap> map = read(text, d);
  ASSERT_TRUE(map.has_value());
  std::ostringstream out;
  write_map_json(*map, out);
  Result<SewerMap> again = read(out.str(), d);
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(again->pipe(PipeId{0}).length_m, map->pipe(PipeId{0}).length_m);
}

TEST(MapJson, ReportsSyntaxErrorsWithLineAndColumn) {
  Diagnostics d;
  Result<SewerMap> map = read("{\n  \"format\": \"sewerplan-map\",\n  \"version\": 1 2\n}", d);
  ASSERT_FALSE(map.has_value());
  EXPECT_EQ(map.error().code, ErrorCode::kParse);
  EXPECT_THAT(map.error().message, HasSubstr("t.json:3:16: error: JSON syntax error"));
}

// Issue 31: a number beyond a double (1e999) was reported without a line, in the parser's words
// ("JSON error: [json.exception.out_of_range.406] number overflow parsing '1e999'").
TEST(MapJson, Issue31NamesTheLineOfANumberBeyondADouble) {
  Diagnostics d;
  Result<SewerMap> map = read(
      "{\n  \"format\": \"sewerplan-map\",\n  \"note\": \"1e999\",\n  \"version\": -2e999\n}", d);
  ASSERT_FALSE(map.has_value());
  EXPECT_EQ(map.error().code, ErrorCode::kParse);
  EXPECT_THAT(map.error().message,
              HasSubstr("t.json:4:14: error: number -2e999 is out of range: no number beyond about "
                        "1.8e308 can be read"));
  EXPECT_THAT(map.error().message, Not(HasSubstr("json.exception")));
  // Nested deeper than the parser goes: said in our words, not simdjson's.
  Diagnostics deep;
  Result<SewerMap> nested = read(std::string(2000, '[') + std::string(2000, ']'), deep);
  ASSERT_FALSE(nested.has_value());
  EXPECT_THAT(nested.error().message,
              HasSubstr("t.json:1:1025: error: the JSON nests arrays and objects more than 1024 "
                        "levels deep"));
}

// Issue 31: text of the file quoted in a message (a name, a shape, a key) holding control
// characters (JSON's \u0000, \u001b) is shown escaped, never as raw bytes.
TEST(MapJson, Issue31EscapesControlCharactersOfQuotedText) {
  std::string text(kSmallMap);
  std::string named(kSmallMap);
  named.replace(named.find(R"("name": "P1")"), 12, R"("name": "P\u0000")");
  Diagnostics names;
  Result<SewerMap> invalid = read(named, names);
  ASSERT_FALSE(invalid.has_value());
  EXPECT_THAT(invalid.error().message,
              HasSubstr("pipe name 'P\\x00' is empty, contains white space or control"));
  EXPECT_EQ(invalid.error().message.find('\0'), std::string::npos);
  text.replace(text.find(R"("shape": "egg")"), 14, R"("shape": "e\u001b[2Jgg")");
  text.replace(text.find(R"("length_m": 1.1)"), 15, R"("length_m": 1.1, "n\u0007": 1)");
  Diagnostics d;
  Result<SewerMap> map = read(text, d);
  ASSERT_FALSE(map.has_value());
  const std::string& m = map.error().message;
  EXPECT_THAT(m, HasSubstr("unknown shape 'e\\x1B[2Jgg' (circular, rectangular, egg, other)"));
  EXPECT_EQ(m.find('\x1b'), std::string::npos);
  bool key_escaped = false;
  for (const Diagnostic& x : d.all()) {
    EXPECT_EQ(x.where.find('\a'), std::string::npos) << x.where;
    key_escaped = key_escaped || x.message.find("unknown field 'n\\x07'") != std::string::npos;
  }
  EXPECT_TRUE(key_escaped);
}

// A pipe of 1e16 m passed validation and then stopped `plan` on an internal check: every number
// beyond core/limits.h is a validation error naming the field.
TEST(MapJson, NumbersBeyondTheLimitsLaterStagesHoldAreErrors) {
  std::string text(kSmallMap);
  text.replace(text.find("\"length_m\": 7.5"), 15, "\"length_m\": 1e16");
  const std::string c_at = R"("x_m": 10, "y_m": 7.5)";
  text.replace(text.find(c_at), c_at.size(), R"("x_m": 1e300, "y_m": 7.5)");
  Diagnostics d;
  Result<SewerMap> map = read(text, d);
  ASSERT_FALSE(map.has_value());
  EXPECT_THAT(map.error().message,
              HasSubstr("t.json:$.pipes[1].length_m: error: pipe P2: length must be at most"));
  EXPECT_THAT(map.error().message, HasSubstr("$.manholes[2].x_m: error: manhole C: x must be"));
}

TEST(MapJson, ReportsWrongTypesAndMissingFieldsByJsonPath) {
  std::string text(kSmallMap);
  text.replace(text.find("\"length_m\": 7.5"), 15, "\"length_m\": \"7.5\"");
  text.replace(text.find("\"diameter_m\": 1.2,"), 18, "");
  Diagnostics d;
  Result<SewerMap> map = read(text, d);
  ASSERT_FALSE(map.has_value());
  EXPECT_THAT(map.error().message,
              HasSubstr("t.json:$.pipes[1].length_m: error: expected a number, got \"7.5\""));
  EXPECT_THAT(map.error().message,
              HasSubstr("t.json:$.manholes[1]: error: missing required field 'diameter_m'"));
}

TEST(MapJson, ReportsBrokenReferencesByJsonPath) {
  std::string text(kSmallMap);
  text.replace(text.find("{\"pipe\": \"P2\", \"azimuth_deg\": 90}"), 33,
               "{\"pipe\": \"P9\", \"azimuth_deg\": 90}");
  Diagnostics d;
  Result<SewerMap> map = read(text, d);
  ASSERT_FALSE(map.has_value());
  EXPECT_EQ(map.error().code, ErrorCode::kInvalidMap);
  EXPECT_THAT(
      map.error().message,
      HasSubstr(
          "t.json:$.manholes[1].slots[1].pipe: error: manhole B slot 2 names unknown pipe 'P9'"));
  EXPECT_THAT(
      map.error().message,
      HasSubstr(
          "t.json:$.pipes[1].from: error: pipe P2 ends in manhole B, but B has no slot for it"));
}

TEST(MapJson, WarnsAboutMisspeltFields) {
  std::string text(kSmallMap);
  text.replace(text.find("\"blockage_risk\""), 15, "\"blockage_rsik\"");
  Diagnostics d;
  Result<SewerMap> map = read(text, d);
  ASSERT_TRUE(map.has_value());
  ASSERT_EQ(d.warning_count(), 1U);
  EXPECT_EQ(d.all()[0].where, "t.json:$.pipes[0].blockage_rsik");
  EXPECT_THAT(d.all()[0].message, HasSubstr("unknown field 'blockage_rsik' ignored"));
}

// simdjson would take a key's first value and drop the second without a word; which one the
// writer meant is unknown, so a field given twice is an error at its JSON path.
TEST(MapJson, AFieldGivenTwiceIsAnError) {
  std::string text(kSmallMap);
  text.replace(text.find(R"("length_m": 7.5)"), 15, R"("length_m": 7.5, "length_m": 75)");
  Diagnostics d;
  Result<SewerMap> map = read(text, d);
  ASSERT_FALSE(map.has_value());
  EXPECT_THAT(map.error().message,
              HasSubstr("t.json:$.pipes[1].length_m: error: field 'length_m' given twice"));
  EXPECT_EQ(d.error_count(), 1U) << map.error().message;
}

// A large object is checked by sorting its keys; every repeat is reported, in the object's order.
TEST(MapJson, FieldsGivenTwiceInALargeObjectAreEachReported) {
  std::string extra;
  for (int i = 0; i < 20; ++i) extra += "\"x" + std::to_string(i) + "\": 1, ";
  std::string text(kSmallMap);
  text.replace(text.find(R"("name": "small")"), 15,
               R"("name": "small", )" + extra + R"("x3": 2, "name": "big", "x3": 3)");
  Diagnostics d;
  Result<SewerMap> map = read(text, d);
  ASSERT_FALSE(map.has_value());
  ASSERT_EQ(d.error_count(), 3U) << map.error().message;
  std::vector<std::string> where;
  for (const Diagnostic& e : d.all()) {
    if (e.severity == Severity::kError) where.push_back(e.where);
  }
  EXPECT_EQ(where, (std::vector<std::string>{"t.json:$.x3", "t.json:$.name", "t.json:$.x3"}));
}

TEST(MapJson, RejectsAnotherFormatOrVersion) {
  std::string text(kSmallMap);
  text.replace(text.find("\"version\": 1"), 12, "\"version\": 7");
  Diagnostics d;
  Result<SewerMap> map = read(text, d);
  ASSERT_FALSE(map.has_value());
  EXPECT_THAT(map.error().message, HasSubstr("unsupported version 7"));
}

TEST(MapJson, NeverCrashesOnTruncatedInput) {
  const std::string text(kSmallMap);
  for (std::size_t n = 0; n < text.size(); n += 7) {
    Diagnostics d;
    Result<SewerMap> map = read(text.substr(0, n), d);
    EXPECT_FALSE(map.has_value()) << "prefix of " << n << " bytes";
    EXPECT_FALSE(map.error().message.empty());
  }
}

// The fast path (no document tree: a million manholes in a fraction of the memory) reads what
// the writer writes, and gives the same map and the same diagnostics as the document reader.
TEST(MapJsonFastPath, ReadsWrittenMapsAsTheDocumentReaderDoes) {
  Result<SewerMap> generated =
      // More manholes and pipes than the fast path reads before it reserves the rest.
      generate_network({.manholes = 3000, .seed = 3, .topology = Topology::kMeshed});
  ASSERT_TRUE(generated.has_value());
  std::ostringstream out;
  write_map_json(*generated, out);
  // The small map has every optional field; the slots of B come before its floor here, which
  // their default invert must still follow.
  std::string reordered(kSmallMap);
  const std::string floor = R"("z_m": 1.25, )";
  reordered.erase(reordered.find(floor), floor.size());
  reordered.replace(reordered.find(R"("slots": [{"pipe": "P1", "azimuth_deg": 180)"), 0, floor);
  for (const std::string& text : {out.str(), std::string(kSmallMap), reordered}) {
    std::optional<MapBuilder> fast = detail::read_map_json_fast(text, "t.json");
    ASSERT_TRUE(fast.has_value()) << text.substr(0, 200);
    Diagnostics fast_d, document_d;
    Result<SewerMap> a = std::move(*fast).build(fast_d);
    Result<SewerMap> b = detail::read_map_json_document(text, "t.json", document_d);
    ASSERT_TRUE(a.has_value() && b.has_value());
    EXPECT_EQ(*a, *b);
    EXPECT_EQ(fast_d.all(), document_d.all());
  }
  Diagnostics d;
  Result<SewerMap> reread = read(reordered, d);
  ASSERT_TRUE(reread.has_value());
  const ManholeId b = *reread->find_manhole("B");
  EXPECT_DOUBLE_EQ(reread->slot(b, SlotIndex{1}).invert_z_m, 1.25)
      << "invert defaults to the floor";
}

// What the fast path cannot read exactly as the document reader would goes to the document
// reader, which reports it by JSON path (the tests above) or reads it.
TEST(MapJsonFastPath, LeavesEverythingElseToTheDocumentReader) {
  const std::vector<std::pair<std::string, std::string>> edits = {
      {R"("name": "W")", R"("name": "W\u0031")"},                             // an escape
      {R"("offset_m": 2.5)", R"("offset_m": 2.5, "note": 1)"},                // an unknown field
      {R"("offset_m": 2.5)", R"("offset_m": "2.5")"},                         // a wrong type
      {R"("offset_m": 2.5)", R"("offset_m": 2.5, "offset_m": 3)"},            // a field twice
      {R"("x_m": 10, "y_m": 0)", R"("x_m": -0, "y_m": 0)"},                   // "-0"
      {R"("x_m": 10, "y_m": 0)", R"("x_m": 1e999, "y_m": 0)"},                // beyond double
      {R"("x_m": 10, "y_m": 0)", R"("x_m": 1234567890123456789, "y_m": 0)"},  // 19 digits
      {R"("variant": "B")", R"("variant": "BC")"},                            // an error to report
      {R"("version": 1)", R"("version": 1 2)"},                               // a syntax error
      {R"("exit": true)", R"("exit": truex)"},
  };
  for (const auto& [from, to] : edits) {
    std::string text(kSmallMap);
    ASSERT_NE(text.find(from), std::string::npos) << from;
    text.replace(text.find(from), from.size(), to);
    EXPECT_FALSE(detail::read_map_json_fast(text, "t.json").has_value()) << to;
    Diagnostics fast_path_unused;
    Diagnostics d;
    EXPECT_EQ(read(text, d).has_value(),
              detail::read_map_json_document(text, "t.json", fast_path_unused).has_value());
    EXPECT_EQ(d.all(), fast_path_unused.all()) << to;
  }
  EXPECT_FALSE(detail::read_map_json_fast(std::string(kSmallMap) + " x", "t.json").has_value());
  EXPECT_TRUE(detail::read_map_json_fast(std::string(kSmallMap) + " \n", "t.json").has_value());
}

TEST(MapIo, ReadsTheAisTestbedByPath) {
  Diagnostics d;
  Result<SewerMap> map = read_map(testing::dataset_path("ais-testbed/map.json"), d);
  ASSERT_TRUE(map.has_value()) << map.error();
  EXPECT_EQ(map->manhole_count(), 12U);
  EXPECT_EQ(map->pipe_count(), 14U);
  EXPECT_EQ(d.warning_count(), 0U);
}

TEST(MapIo, NamesAMissingFileAndTheReason) {
  Diagnostics d;
  Result<SewerMap> map = read_map("no/such/map.json", d);
  ASSERT_FALSE(map.has_value());
  EXPECT_EQ(map.error().code, ErrorCode::kIo);
  EXPECT_THAT(map.error().message, HasSubstr("cannot read no/such/map.json: No such file"));
}

TEST(MapIo, TellsAGisSourceByItsPath) {
  EXPECT_TRUE(is_gis_source_path("a/net.GPKG"));
  EXPECT_TRUE(is_gis_source_path("net.shp"));
  EXPECT_TRUE(is_gis_source_path(std::filesystem::temp_directory_path()));
  EXPECT_FALSE(is_gis_source_path("net.json"));
  EXPECT_FALSE(is_gis_source_path("no/such/directory"));
  Diagnostics d;
  Result<SewerMap> refused = read_map("net.gpkg", d);
  ASSERT_FALSE(refused.has_value());
  EXPECT_EQ(refused.error().code, ErrorCode::kUnsupportedFormat);
  EXPECT_THAT(refused.error().message, HasSubstr("net.gpkg: a GIS source"));
}

// A GeoJSON file is a GIS source by its content, whatever its name (export-geojson -o net.json),
// and core's read_map refuses it as one rather than as a JSON map without "format".
TEST(MapIo, TellsAGeoJsonFileByItsContent) {
  EXPECT_TRUE(is_gis_source_path("no/such/net.GeoJSON"));
  EXPECT_TRUE(
      looks_like_geojson("\xEF\xBB\xBF {\n \"type\": \"FeatureCollection\", \"features\": []}"));
  EXPECT_TRUE(looks_like_geojson(
      R"({"features": [{"type": "Feature", "geometry": {"type": "Point"}, "properties": {}}],)"));
  EXPECT_FALSE(looks_like_geojson(R"({"format": "sewerplan-map", "version": 1, "manholes": [)"));
  EXPECT_FALSE(looks_like_geojson(R"([{"type": "FeatureCollection"}])"));
  EXPECT_FALSE(looks_like_geojson("[TITLE]\n"));
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  const std::filesystem::path geojson = dir / "sewerplan_map_io_geojson_test.json";
  const std::filesystem::path native = dir / "sewerplan_map_io_native_test.json";
  std::ofstream(geojson) << R"({"type": "FeatureCollection", "name": "net", "features": []})";
  std::ofstream(native)
      << R"({"format": "sewerplan-map", "version": 1, "name": "FeatureCollection"})";
  EXPECT_TRUE(is_gis_source_path(geojson));
  EXPECT_FALSE(is_gis_source_path(native));
  Diagnostics d;
  Result<SewerMap> refused = read_map(geojson, d);
  ASSERT_FALSE(refused.has_value());
  EXPECT_EQ(refused.error().code, ErrorCode::kUnsupportedFormat);
  EXPECT_THAT(refused.error().message, HasSubstr("a GIS source (GeoJSON,"));
  Result<SewerMap> without_gis = read_map_without_gis(geojson, d);
  ASSERT_FALSE(without_gis.has_value());
  EXPECT_THAT(without_gis.error().message, HasSubstr("built without GIS support"));
  std::filesystem::remove(geojson);
  std::filesystem::remove(native);
}

TEST(MapIo, WithoutGisRefusesGisSourcesAndMappingsAndReadsTheRest) {
  Diagnostics d;
  Result<SewerMap> source = read_map_without_gis("exports/net.shp", d);
  ASSERT_FALSE(source.has_value());
  EXPECT_EQ(source.error().code, ErrorCode::kUnsupportedFormat);
  EXPECT_THAT(source.error().message,
              HasSubstr("exports/net.shp: a GIS source (GeoJSON, GeoPackage, Shapefile or a "
                        "directory of them), but this sewerplan is built without GIS support"));
  const std::string ais = testing::dataset_path("ais-testbed/map.json").string();
  Result<SewerMap> mapping = read_map_without_gis(ais, d, std::filesystem::path("town.json"));
  ASSERT_FALSE(mapping.has_value());
  EXPECT_EQ(mapping.error().code, ErrorCode::kUnsupportedFormat);
  EXPECT_THAT(mapping.error().message,
              HasSubstr("town.json: a GIS field mapping, but this sewerplan is built without GIS "
                        "support"));
  Result<SewerMap> map = read_map_without_gis(ais, d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_EQ(map->manhole_count(), read_map(ais, d)->manhole_count());
}

TEST(MapIo, DetectsTheFormatFromContentWhenTheExtensionIsUnknown) {
  EXPECT_EQ(*detect_map_format("x.txt", "  {\"format\": 1}"), MapFormat::kJson);
  EXPECT_EQ(*detect_map_format("x.db", "# comment\nsewerdb 1\n"), MapFormat::kAscii);
  Result<MapFormat> unknown = detect_map_format("x.db", "hello");
  ASSERT_FALSE(unknown.has_value());
  EXPECT_EQ(unknown.error().code, ErrorCode::kUnsupportedFormat);
}

}  // namespace
}  // namespace sewerplan
