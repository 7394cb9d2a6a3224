// SPDX-License-Identifier: MIT
// GIS features to a map (map_features.h), without GDAL: the layers are built here as values, as
// gis/gdal_import.cc hands them over (tests/gis has the same through real GeoPackages).
#include "sewerplan/core/map_features.h"

#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/map_checks.h"

namespace sewerplan {
namespace {

using testing::has_warning;
using ::testing::HasSubstr;
using ::testing::Not;

GisFeature point(std::int64_t fid, double x, double y, std::vector<GisValue> values) {
  return {.fid = fid,
          .geometry = GisGeometry::kPoint,
          .geometry_name = "Point",
          .points = {{x, y, 0}},
          .values = std::move(values)};
}

GisFeature line(std::int64_t fid, std::vector<std::array<double, 3>> points,
                std::vector<GisValue> values) {
  return {.fid = fid,
          .geometry = GisGeometry::kLine,
          .geometry_name = "LineString",
          .points = std::move(points),
          .values = std::move(values)};
}

// A QGEP/TEKSI export: three structures (one a special structure, not an exit) and two reaches
// joined through the wastewater node keys, sizes in millimetres.
GisLayer qgep_structures() {
  GisLayer l{.name = "vw_qgep_wastewater_structure",
             .fields = {"identifier", "wn_obj_id", "ws_type", "co_level", "wn_bottom_level",
                        "ma_dimension1"},
             .crs = Crs{"EPSG", 2056}};
  l.features.push_back(point(1, 0, 0, {"S1", "wn1", "manhole", 410.0, 407.5, 1000.0}));
  l.features.push_back(point(2, 20, 0, {"S2", "wn2", "manhole", 410.0, 407.3, 800.0}));
  l.features.push_back(point(3, 20, 15, {"S3", "wn3", "special_structure", 411.0, 407.0, {}}));
  return l;
}

GisLayer qgep_reaches() {
  GisLayer l{.name = "vw_qgep_reach",
             .fields = {"identifier", "rp_from_fk_wastewater_networkelement",
                        "rp_to_fk_wastewater_networkelement", "rp_from_level", "rp_to_level",
                        "clear_height"},
             .crs = Crs{"EPSG", 2056}};
  l.features.push_back(
      line(10, {{0, 0, 0}, {20, 0, 0}}, {"R1", "wn1", "wn2", 407.6, 407.4, 300.0}));
  // Drawn from S3 to S2 although it runs from S2 to S3: read reversed.
  l.features.push_back(
      line(11, {{20, 15, 0}, {25, 7.5, 0}, {20, 0, 0}}, {"R2", "wn2", "wn3", 407.3, 407.1, 400.0}));
  return l;
}

Result<SewerMap> build(const GisLayer& manholes, const GisLayer& pipes, Diagnostics& d,
                       const GisFieldMapping& mapping = GisFieldMapping::defaults()) {
  return map_from_gis_layers(manholes, pipes, mapping, "net.gpkg", "net", d);
}

TEST(MapFeatures, QgepLayersBecomeTheNetworkWithTheirKeysLevelsAndSizes) {
  Diagnostics d;
  Result<SewerMap> map = build(qgep_structures(), qgep_reaches(), d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_EQ(map->crs(), (Crs{"EPSG", 2056}));
  ASSERT_EQ(map->manhole_count(), 3u);
  ASSERT_EQ(map->pipe_count(), 2u);
  const Manhole& s1 = map->manhole(*map->find_manhole("S1"));
  EXPECT_DOUBLE_EQ(s1.diameter_m, 1.0);
  EXPECT_DOUBLE_EQ(s1.position.z_m, 407.5);
  EXPECT_NEAR(*s1.depth_m, 2.5, 1e-9);
  EXPECT_TRUE(s1.exit);
  const Manhole& s3 = map->manhole(*map->find_manhole("S3"));
  EXPECT_FALSE(s3.exit);                 // a special structure
  EXPECT_DOUBLE_EQ(s3.diameter_m, 1.0);  // no size: the default, counted
  EXPECT_TRUE(has_warning(d, "manholes have no size"));
  const Pipe& r2 = map->pipe(*map->find_pipe("R2"));
  EXPECT_DOUBLE_EQ(r2.diameter_m, 0.4);
  EXPECT_EQ(map->manhole(r2.ends[0].manhole.value()).name, "S2");
  EXPECT_EQ(map->manhole(r2.ends[1].manhole.value()).name, "S3");
  EXPECT_NEAR(r2.length_m, 2 * std::hypot(5.0, 7.5), 1e-9);  // along its line
  EXPECT_TRUE(has_warning(d, "read reversed"));
}

TEST(MapFeatures, WithoutFromAndToFieldsEndsJoinTheNearestManholeWithinTheTolerance) {
  GisLayer manholes{.name = "manholes", .fields = {"name"}};
  manholes.features = {point(1, 0, 0, {"A"}), point(2, 10, 0, {"B"}), point(3, 10.4, 0, {"C"})};
  GisLayer pipes{.name = "pipes", .fields = {"name", "diameter"}};
  pipes.features = {line(1, {{0.3, 0, 0}, {9.9, 0, 0}}, {"P1", 300.0}),
                    line(2, {{0.1, 0.1, 0}, {0, 8, 0}}, {"P2", 300.0})};
  Diagnostics d;
  Result<SewerMap> map = build(manholes, pipes, d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  const Pipe& p1 = map->pipe(*map->find_pipe("P1"));
  EXPECT_EQ(map->manhole(p1.ends[0].manhole.value()).name, "A");
  EXPECT_EQ(map->manhole(p1.ends[1].manhole.value()).name, "B");  // 0.1 m, not C at 0.5 m
  EXPECT_TRUE(has_warning(d, "pipe P2: no manhole within 0.5 m of its last point: a blind end"));
}

TEST(MapFeatures, AShapefileFieldNameCutToTenCharactersStillMatches) {
  GisLayer reaches = qgep_reaches();
  reaches.fields[1] = "rp_from_fk";
  reaches.fields[2] = "rp_to_fk_w";
  Diagnostics d;
  Result<SewerMap> map = build(qgep_structures(), reaches, d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_EQ(map->manhole(map->pipe(*map->find_pipe("R1")).ends[1].manhole.value()).name, "S2");
}

TEST(MapFeatures, AMissingNameFieldIsOneErrorThatListsTheNamesTried) {
  GisLayer manholes = qgep_structures();
  manholes.fields[0] = "bezeichnung";
  Diagnostics d;
  Result<SewerMap> map = build(manholes, qgep_reaches(), d);
  ASSERT_FALSE(map.has_value());
  EXPECT_THAT(map.error().message,
              HasSubstr("net.gpkg:vw_qgep_wastewater_structure: error: no field for the manhole "
                        "name (tried identifier, name,"));
}

TEST(MapFeatures, BadFeaturesAreErrorsThatNameTheLayerTheFeatureAndTheField) {
  GisLayer manholes = qgep_structures();
  manholes.features[0].geometry = GisGeometry::kOther;
  manholes.features[0].geometry_name = "Polygon";
  manholes.features[2].values[3] = std::string("hoch");
  GisLayer reaches = qgep_reaches();
  reaches.features[0].values[2] = std::string("wn9");
  reaches.features.push_back(line(12, {{20, 0, 0}, {20, 5, 0}}, {"R3", "wn2", {}, {}, {}, {}}));
  Diagnostics d;
  Result<SewerMap> map = build(manholes, reaches, d);
  ASSERT_FALSE(map.has_value());
  const std::string& m = map.error().message;
  EXPECT_THAT(m, HasSubstr("net.gpkg:vw_qgep_wastewater_structure: feature 1: error: the geometry "
                           "is a Polygon: a manhole is a point"));
  EXPECT_THAT(m, HasSubstr("feature 3: error: field co_level: 'hoch' is not a number"));
  EXPECT_THAT(m, HasSubstr("net.gpkg:vw_qgep_reach: feature 10: error: pipe R1: field "
                           "rp_to_fk_wastewater_networkelement: 'wn9' names no manhole (by "
                           "wn_obj_id of layer vw_qgep_wastewater_structure)"));
  EXPECT_THAT(m, HasSubstr("feature 12: error: pipe R3: no clear height or width"));
  // R1's S1 and R2's S3 were left out for their own errors: no second error about them.
  EXPECT_THAT(m, Not(HasSubstr("'wn1'")));
  EXPECT_THAT(m, Not(HasSubstr("'wn3'")));
}

TEST(MapFeatures, LayersInDifferentCrsAreAnError) {
  GisLayer reaches = qgep_reaches();
  reaches.crs = Crs{"EPSG", 21781};
  Diagnostics d;
  Result<SewerMap> map = build(qgep_structures(), reaches, d);
  ASSERT_FALSE(map.has_value());
  EXPECT_THAT(map.error().message,
              HasSubstr("is in EPSG:2056 but layer vw_qgep_reach in EPSG:21781"));
}

TEST(MapFeatures, ACrsWithoutCodeIsAWarningAndTheMapHasNone) {
  GisLayer manholes = qgep_structures();
  GisLayer reaches = qgep_reaches();
  manholes.crs.reset();
  reaches.crs.reset();
  manholes.unnamed_crs = "Local engineering grid";
  Diagnostics d;
  Result<SewerMap> map = build(manholes, reaches, d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_FALSE(map->crs().has_value());
  EXPECT_TRUE(has_warning(d, "its CRS 'Local engineering grid' has no AUTHORITY:CODE"));
}

TEST(MapFeatures, AMappingFileRenamesFieldsWithTheirUnitsAndExitTypes) {
  const std::string text = R"({
    "manholes": {"layer": "schacht", "name": "SCHACHT_NR", "id": null, "type": "ART",
                 "dimension1": {"field": "DM", "unit": "m"}, "exit_types": ["Normschacht"]},
    "pipes": {"from": "VON", "to": "BIS", "height": "DN"},
    "tolerance_m": 0
  })";
  Diagnostics d;
  Result<GisFieldMapping> mapping = parse_gis_field_mapping(text, "net.fields.json", d);
  ASSERT_TRUE(mapping.has_value()) << mapping.error().message;
  EXPECT_EQ(mapping->manhole_layer, "schacht");
  GisLayer manholes{.name = "schacht", .fields = {"SCHACHT_NR", "ART", "DM"}};
  manholes.features = {point(1, 0, 0, {"A", "Normschacht", 1.2}),
                       point(2, 9, 0, {"B", "Bauwerk", 2.0})};
  GisLayer pipes{.name = "haltung", .fields = {"identifier", "VON", "BIS", "DN"}};
  pipes.features = {line(5, {{0, 0, 0}, {9, 0, 0}}, {"H1", "A", "B", 250.0})};
  Result<SewerMap> map = build(manholes, pipes, d, *mapping);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_DOUBLE_EQ(map->manhole(*map->find_manhole("A")).diameter_m, 1.2);
  EXPECT_TRUE(map->manhole(*map->find_manhole("A")).exit);
  EXPECT_FALSE(map->manhole(*map->find_manhole("B")).exit);
  EXPECT_DOUBLE_EQ(map->pipe(*map->find_pipe("H1")).diameter_m, 0.25);
}

TEST(MapFeatures, ABadMappingFileIsAnErrorAtItsJsonPath) {
  Diagnostics d;
  Result<GisFieldMapping> mapping = parse_gis_field_mapping(
      R"({"pipes": {"height": {"field": "DN", "unit": "furlong"}}, "tolerance": 1})", "f.json", d);
  ASSERT_FALSE(mapping.has_value());
  EXPECT_THAT(mapping.error().message,
              HasSubstr("f.json:$.pipes.height.unit: error: field height: unknown unit 'furlong' "
                        "(mm, cm, m, inch, foot or us_survey_foot)"));
  EXPECT_TRUE(has_warning(d, "tolerance"));
}

TEST(MapFeatures, AUnitOnAFieldThatIsNoMeasureOrAnAzimuthInAnotherUnitIsAnError) {
  Diagnostics d;
  Result<GisFieldMapping> mapping = parse_gis_field_mapping(
      R"({"manholes": {"name": {"field": "N", "unit": "m"}},
          "pipes": {"from_azimuth": {"field": "AZ", "unit": "grad"}}})",
      "f.json", d);
  ASSERT_FALSE(mapping.has_value());
  EXPECT_THAT(mapping.error().message,
              HasSubstr("f.json:$.manholes.name.unit: error: field name is not a measure"));
  EXPECT_THAT(mapping.error().message,
              HasSubstr("f.json:$.pipes.from_azimuth.unit: error: field from_azimuth: an "
                        "azimuth's unit is deg, not 'grad'"));
}

TEST(MapFeatures, EveryMeasuredFieldTakesItsUnitFromTheMappingFile) {
  EXPECT_DOUBLE_EQ(*gis_unit_to_metres("inch"), 0.0254);
  EXPECT_DOUBLE_EQ(*gis_unit_to_metres("ft"), 0.3048);
  EXPECT_NEAR(*gis_unit_to_metres("us_survey_foot"), 0.3048006096, 1e-10);
  EXPECT_FALSE(gis_unit_to_metres("Inch").has_value());
  // A US layer: diameters in inches, lengths and levels in feet, the shaft in cm.
  Diagnostics d;
  Result<GisFieldMapping> mapping = parse_gis_field_mapping(
      R"({"manholes": {"name": "MH", "invert_level": {"field": "INV", "unit": "foot"},
                       "dimension1": {"field": "DIA", "unit": "cm"}},
          "pipes": {"from": "US", "to": "DS", "height": {"field": "DIAM", "unit": "inch"},
                    "length": {"field": "LEN", "unit": "foot"},
                    "from_level": {"field": "UP", "unit": "foot"},
                    "to_level": {"field": "DN", "unit": "foot"}}})",
      "us.fields.json", d);
  ASSERT_TRUE(mapping.has_value()) << mapping.error().message;
  GisLayer manholes{.name = "manholes", .fields = {"MH", "INV", "DIA"}};
  manholes.features = {point(1, 0, 0, {"A", 100.0, 120.0}), point(2, 30, 0, {"B", 99.0, 120.0})};
  GisLayer pipes{.name = "pipes", .fields = {"identifier", "US", "DS", "DIAM", "LEN", "UP", "DN"}};
  pipes.features = {line(5, {{0, 0, 0}, {30, 0, 0}}, {"P", "A", "B", 12.0, 100.0, 100.5, 99.5})};
  Result<SewerMap> map = build(manholes, pipes, d, *mapping);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  const Manhole& a = map->manhole(*map->find_manhole("A"));
  EXPECT_NEAR(a.position.z_m, 30.48, 1e-9);
  EXPECT_NEAR(a.diameter_m, 1.2, 1e-9);
  const Pipe& p = map->pipe(*map->find_pipe("P"));
  EXPECT_NEAR(p.diameter_m, 0.3048, 1e-9);
  EXPECT_NEAR(p.length_m, 30.48, 1e-9);
  EXPECT_NEAR(map->slot(*map->find_manhole("A"), SlotIndex{0}).invert_z_m, 100.5 * 0.3048, 1e-9);
}

// A layer in US survey feet (EPSG:2229, as a Los Angeles sewer layer): its points, its z and the
// fields measured in the CRS's unit come in metres; fields whose name says "_m" stay metres.
TEST(MapFeatures, ALayerInFeetIsReadInMetresThroughItsCrsUnit) {
  constexpr double kFtUs = 1200.0 / 3937.0;
  GisLayer manholes{.name = "manholes",
                    .fields = {"name", "rim_elev", "invert_elev", "depth_m"},
                    .crs = Crs{"EPSG", 2229},
                    .unit_m = kFtUs};
  manholes.features = {point(1, 6500000, 1800000, {"A", 110.0, 100.0, {}}),
                       point(2, 6500100, 1800000, {"B", 110.0, 99.0, 3.5})};
  GisLayer pipes{.name = "pipes",
                 .fields = {"name", "from", "to", "diameter", "length"},
                 .crs = Crs{"EPSG", 2229},
                 .unit_m = kFtUs};
  pipes.features = {
      line(7, {{6500000, 1800000, 0}, {6500100, 1800000, 0}}, {"P", "A", "B", 300.0, {}}),
      line(8, {{6500100, 1800000, 0}, {6500100, 1800050, 0}}, {"Q", "B", {}, 300.0, 50.0})};
  Diagnostics d;
  Result<SewerMap> map = build(manholes, pipes, d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_EQ(map->crs(), (Crs{"EPSG", 2229}));
  const Manhole& a = map->manhole(*map->find_manhole("A"));
  EXPECT_NEAR(a.position.x_m, 6500000 * kFtUs, 1e-6);
  EXPECT_NEAR(a.position.y_m, 1800000 * kFtUs, 1e-6);
  EXPECT_NEAR(a.position.z_m, 100 * kFtUs, 1e-9);
  EXPECT_NEAR(*a.depth_m, 10 * kFtUs, 1e-9);  // rim less invert, both in feet
  EXPECT_NEAR(*map->manhole(*map->find_manhole("B")).depth_m, 3.5, 1e-12);  // depth_m: metres
  // A 100 ft line is 30.48 m, not 100 m; a length field in the CRS's unit likewise.
  EXPECT_NEAR(map->pipe(*map->find_pipe("P")).length_m, 100 * kFtUs, 1e-9);
  EXPECT_NEAR(map->pipe(*map->find_pipe("Q")).length_m, 50 * kFtUs, 1e-9);
  EXPECT_NEAR(map->pipe(*map->find_pipe("P")).diameter_m, 0.3, 1e-12);  // mm: not the CRS's
}

// The planner's slot numbers (the paper's DRIVE_MANHOLE_TYPE_3_FROM_1_TO_3) come back in the order
// the slot fields give, not in the order of the pipes; numbers that are not 0..k-1, each once, are
// a warning and the pipes' order.
TEST(MapFeatures, SlotNumberFieldsKeepTheSlotOrder) {
  GisLayer manholes{.name = "manholes", .fields = {"name"}};
  manholes.features = {point(1, 0, 0, {"A"}), point(2, 10, 0, {"B"}), point(3, 0, 10, {"C"})};
  GisLayer pipes{.name = "pipes",
                 .fields = {"name", "from", "to", "height_m", "from_slot", "to_slot"}};
  pipes.features = {line(4, {{0, 0, 0}, {10, 0, 0}}, {"P", "A", "B", 0.3, 1.0, 0.0}),
                    line(5, {{0, 0, 0}, {0, 10, 0}}, {"Q", "A", "C", 0.3, 0.0, 0.0})};
  Diagnostics d;
  Result<SewerMap> map = build(manholes, pipes, d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  const ManholeId a = *map->find_manhole("A");
  EXPECT_EQ(map->pipe(map->slot(a, SlotIndex{0}).pipe).name, "Q");
  EXPECT_EQ(map->pipe(map->slot(a, SlotIndex{1}).pipe).name, "P");
  EXPECT_DOUBLE_EQ(map->slot(a, SlotIndex{0}).azimuth_deg, 90.0);
  pipes.features[1].values[4] = 1.0;  // two slots numbered 1
  Diagnostics twice;
  Result<SewerMap> kept = build(manholes, pipes, twice);
  ASSERT_TRUE(kept.has_value()) << kept.error().message;
  EXPECT_EQ(kept->pipe(kept->slot(a, SlotIndex{0}).pipe).name, "P");
  EXPECT_TRUE(has_warning(twice, "slot numbers that are not 0..k-1"));
}

TEST(MapFeatures, SlotAzimuthFieldsWinOverTheLinesDirection) {
  GisLayer manholes{.name = "manholes", .fields = {"name"}};
  manholes.features = {point(1, 0, 0, {"A"}), point(2, 10, 0, {"B"})};
  GisLayer pipes{.name = "pipes", .fields = {"name", "from", "to", "height_m", "from_az", "to_az"}};
  pipes.features = {line(3, {{0, 0, 0}, {10, 0, 0}}, {"P", "A", "B", 0.3, 12.5, -170.0}),
                    line(4, {{10, 0, 0}, {0, 0, 0}}, {"Q", "B", "A", 0.3, {}, {}})};
  Diagnostics d;
  Result<SewerMap> map = build(manholes, pipes, d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  const ManholeId a = *map->find_manhole("A");
  const ManholeId b = *map->find_manhole("B");
  EXPECT_DOUBLE_EQ(map->slot(a, SlotIndex{0}).azimuth_deg, 12.5);
  EXPECT_DOUBLE_EQ(map->slot(b, SlotIndex{0}).azimuth_deg, -170.0);
  EXPECT_DOUBLE_EQ(map->slot(b, SlotIndex{1}).azimuth_deg, 180.0);  // no field value: the line
  pipes.features[0].values[4] = 400.0;
  Diagnostics bad;
  Result<SewerMap> refused = build(manholes, pipes, bad);
  ASSERT_FALSE(refused.has_value());
  EXPECT_THAT(
      refused.error().message,
      HasSubstr("net.gpkg:pipes: feature 3: error: pipe P: field from_az: azimuth 400 is not an "
                "angle in degrees (-360..360)"));
}

TEST(MapFeatures, TheLayersAreChosenByGeometryThenByName) {
  const GisFieldMapping defaults = GisFieldMapping::defaults();
  const std::vector<GisLayerInfo> qgep = {{"vw_qgep_reach", GisGeometry::kLine, 4},
                                          {"od_cover", GisGeometry::kPoint, 3},
                                          {"vw_qgep_wastewater_structure", GisGeometry::kPoint, 3}};
  Result<GisLayerChoice> chosen = choose_gis_layers(qgep, defaults, "q.gpkg");
  ASSERT_TRUE(chosen.has_value()) << chosen.error().message;
  EXPECT_EQ(chosen->manholes, 2u);
  EXPECT_EQ(chosen->pipes, 0u);
  const std::vector<GisLayerInfo> two = {
      {"a", GisGeometry::kPoint, 1}, {"b", GisGeometry::kPoint, 1}, {"c", GisGeometry::kLine, 1}};
  Result<GisLayerChoice> ambiguous = choose_gis_layers(two, defaults, "x.gpkg");
  ASSERT_FALSE(ambiguous.has_value());
  EXPECT_THAT(ambiguous.error().message,
              HasSubstr("x.gpkg: 2 point layers could hold the manholes (a (points), b (points), "
                        "c (lines)): name the layer in a field mapping file"));
  EXPECT_TRUE(choose_gis_layers(two, defaults, "x.shp", "b").has_value());  // the .shp named
  const std::vector<GisLayerInfo> empty = {{"m", GisGeometry::kPoint, 0},
                                           {"p", GisGeometry::kLine, 2}};
  Result<GisLayerChoice> none = choose_gis_layers(empty, defaults, "e.gpkg");
  ASSERT_FALSE(none.has_value());
  EXPECT_THAT(none.error().message, HasSubstr("e.gpkg: layer m (the manholes) has no features"));
  Result<GisLayerChoice> no_lines = choose_gis_layers(
      {{"m", GisGeometry::kPoint, 2}, {"zones", GisGeometry::kOther, 2}}, defaults, "z.gpkg");
  ASSERT_FALSE(no_lines.has_value());
  EXPECT_THAT(no_lines.error().message,
              HasSubstr("no line layer for the pipes; the source has m (points), zones (other or "
                        "mixed geometry)"));
}

}  // namespace
}  // namespace sewerplan
