// SPDX-License-Identifier: MIT
// Shapefiles and GeoPackages in (gdal_import.h). The fixtures are written here, at test time, by
// GDAL itself: no binary files in the repository.
#include "sewerplan/gis/gdal_import.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/map_checks.h"
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>
#include <unistd.h>

namespace sewerplan::gis {
namespace {

namespace fs = std::filesystem;
using testing::has_warning;
using ::testing::HasSubstr;

struct Row {
  std::string wkt;                  // empty: no geometry
  std::vector<std::string> values;  // empty: null
};

struct Layer {
  std::string name;
  OGRwkbGeometryType type;
  std::string srs;  // "EPSG:25832", a PROJ string, or empty
  std::vector<std::pair<std::string, OGRFieldType>> fields;
  std::vector<Row> rows;
  std::vector<std::string> options;  // layer creation options, such as ENCODING=ISO-8859-1
};

// Writes `layers` with GDAL's driver `driver` ("GPKG": one file; "ESRI Shapefile": a directory).
void write(const fs::path& path, const char* driver, const std::vector<Layer>& layers) {
  GDALAllRegister();
  GDALDriverH d = GDALGetDriverByName(driver);
  ASSERT_NE(d, nullptr) << driver;
  GDALDatasetH ds = GDALCreate(d, path.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  ASSERT_NE(ds, nullptr) << CPLGetLastErrorMsg();
  for (const Layer& l : layers) {
    OGRSpatialReferenceH srs = nullptr;
    if (!l.srs.empty()) {
      srs = OSRNewSpatialReference(nullptr);
      ASSERT_EQ(OSRSetFromUserInput(srs, l.srs.c_str()), OGRERR_NONE) << l.srs;
    }
    std::vector<const char*> options;
    for (const std::string& o : l.options) options.push_back(o.c_str());
    options.push_back(nullptr);
    OGRLayerH layer =
        GDALDatasetCreateLayer(ds, l.name.c_str(), srs, l.type, const_cast<char**>(options.data()));
    ASSERT_NE(layer, nullptr) << CPLGetLastErrorMsg();
    for (const auto& [name, type] : l.fields) {
      OGRFieldDefnH f = OGR_Fld_Create(name.c_str(), type);
      ASSERT_EQ(OGR_L_CreateField(layer, f, 1), OGRERR_NONE);
      OGR_Fld_Destroy(f);
    }
    for (const Row& r : l.rows) {
      OGRFeatureH f = OGR_F_Create(OGR_L_GetLayerDefn(layer));
      for (std::size_t i = 0; i < r.values.size(); ++i) {
        if (!r.values[i].empty()) OGR_F_SetFieldString(f, static_cast<int>(i), r.values[i].c_str());
      }
      if (!r.wkt.empty()) {
        OGRGeometryH g = nullptr;
        char* wkt = const_cast<char*>(r.wkt.c_str());
        ASSERT_EQ(OGR_G_CreateFromWkt(&wkt, srs, &g), OGRERR_NONE) << r.wkt;
        OGR_F_SetGeometryDirectly(f, g);
      }
      ASSERT_EQ(OGR_L_CreateFeature(layer, f), OGRERR_NONE) << CPLGetLastErrorMsg();
      OGR_F_Destroy(f);
    }
    if (srs != nullptr) OSRRelease(srs);
  }
  GDALClose(ds);
}

class GdalImport : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("sewerplan-gdal-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

Layer qgep_structures(const std::string& srs = "EPSG:2056") {
  return {
      .name = "vw_qgep_wastewater_structure",
      .type = wkbPoint25D,
      .srs = srs,
      .fields = {{"identifier", OFTString},
                 {"wn_obj_id", OFTString},
                 {"ws_type", OFTString},
                 {"co_level", OFTReal},
                 {"wn_bottom_level", OFTReal},
                 {"ma_dimension1", OFTInteger}},
      .rows = {
          {"POINT Z (2600000 1200000 407.5)", {"S1", "wn1", "manhole", "410", "407.5", "1000"}},
          {"POINT Z (2600020 1200000 407.3)", {"S2", "wn2", "manhole", "410", "407.3", "800"}},
          {"POINT Z (2600020 1200015 407)", {"S3", "wn3", "special_structure", "411", "407", ""}}}};
}

Layer qgep_reaches(const std::string& srs = "EPSG:2056") {
  return {.name = "vw_qgep_reach",
          .type = wkbLineString25D,
          .srs = srs,
          .fields = {{"identifier", OFTString},
                     {"rp_from_fk_wastewater_networkelement", OFTString},
                     {"rp_to_fk_wastewater_networkelement", OFTString},
                     {"rp_from_level", OFTReal},
                     {"rp_to_level", OFTReal},
                     {"clear_height", OFTInteger}},
          .rows = {{"LINESTRING Z (2600000 1200000 407.6, 2600020 1200000 407.4)",
                    {"R1", "wn1", "wn2", "407.6", "407.4", "300"}},
                   {"LINESTRING Z (2600020 1200000 407.3, 2600020 1200015 407.1)",
                    {"R2", "wn2", "wn3", "", "", "400"}}}};
}

TEST_F(GdalImport, AQgepGeoPackageIsReadWithItsCrsKeysLevelsAndSizes) {
  const fs::path gpkg = dir_ / "qgep.gpkg";
  write(gpkg, "GPKG", {qgep_structures(), qgep_reaches()});
  Diagnostics d;
  Result<SewerMap> map = read_gis_map(gpkg, d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_EQ(map->name(), "qgep");
  EXPECT_EQ(map->crs(), (Crs{"EPSG", 2056}));
  ASSERT_EQ(map->manhole_count(), 3u);
  ASSERT_EQ(map->pipe_count(), 2u);
  const Manhole& s2 = map->manhole(*map->find_manhole("S2"));
  EXPECT_DOUBLE_EQ(s2.position.x_m, 2600020);
  EXPECT_DOUBLE_EQ(s2.diameter_m, 0.8);
  EXPECT_FALSE(map->manhole(*map->find_manhole("S3")).exit);
  const Pipe& r2 = map->pipe(*map->find_pipe("R2"));
  EXPECT_DOUBLE_EQ(r2.diameter_m, 0.4);
  EXPECT_EQ(map->manhole(r2.ends[1].manhole.value()).name, "S3");
  // R2 has no levels: its ends' inverts are its line's z.
  EXPECT_DOUBLE_EQ(map->slot(r2.ends[1].manhole.value(), r2.ends[1].slot).invert_z_m, 407.1);
}

// A town's Shapefiles: no from/to fields (joined by distance), names in Latin-1.
std::vector<Layer> town(const std::string& encoding) {
  const std::string mueller = encoding == "UTF-8" ? "M\xC3\xBCller" : "M\xFCller";
  return {{.name = "schacht",
           .type = wkbPoint,
           .srs = "EPSG:25832",
           .fields = {{"NAME", OFTString}, {"SOHLHOEHE", OFTReal}, {"DIAMETER", OFTInteger}},
           .rows = {{"POINT (500000 5700000)", {"S-" + mueller, "50.2", "1000"}},
                    {"POINT (500030 5700000)", {"S2", "50.0", "1000"}}},
           .options = {"ENCODING=" + encoding}},
          {.name = "haltung",
           .type = wkbLineString,
           .srs = "EPSG:25832",
           .fields = {{"NAME", OFTString}, {"DN", OFTInteger}},
           .rows = {{"LINESTRING (500000.2 5700000.1, 500029.9 5700000)", {"H1", "300"}}},
           .options = {"ENCODING=" + encoding}}};
}

TEST_F(GdalImport, AShapefileDirectoryInLatin1IsReadAsUtf8AndJoinedByDistance) {
  const fs::path shp = dir_ / "town";
  write(shp, "ESRI Shapefile", town("ISO-8859-1"));
  for (const fs::path& source : {shp, shp / "haltung.shp"}) {
    Diagnostics d;
    Result<SewerMap> map = read_gis_map(source, d);
    ASSERT_TRUE(map.has_value()) << map.error().message;
    EXPECT_EQ(map->crs(), (Crs{"EPSG", 25832}));
    EXPECT_TRUE(map->find_manhole("S-M\xC3\xBCller").has_value());
    const Pipe& h1 = map->pipe(*map->find_pipe("H1"));
    EXPECT_EQ(map->manhole(h1.ends[1].manhole.value()).name, "S2");
    EXPECT_DOUBLE_EQ(h1.diameter_m, 0.3);
  }
}

TEST_F(GdalImport, TheSidecarMappingFileRenamesTheFields) {
  const fs::path gpkg = dir_ / "net.gpkg";
  std::vector<Layer> layers = town("UTF-8");
  layers[0].fields[0].first = "BEZEICHNUNG";
  for (Layer& l : layers) l.options.clear();  // no ENCODING: a GeoPackage is UTF-8
  write(gpkg, "GPKG", layers);
  Diagnostics d;
  Result<SewerMap> without = read_gis_map(gpkg, d);
  ASSERT_FALSE(without.has_value());
  EXPECT_THAT(without.error().message, HasSubstr("no field for the manhole name"));
  std::ofstream(dir_ / "net.fields.json") << R"({"manholes": {"name": "BEZEICHNUNG"}})";
  Diagnostics d2;
  Result<SewerMap> with = read_gis_map(gpkg, d2);
  ASSERT_TRUE(with.has_value()) << with.error().message;
  EXPECT_TRUE(with->find_manhole("S2").has_value());
}

TEST_F(GdalImport, AnUnknownCrsIsAWarningAndTheMapHasNone) {
  const std::string local =
      "+proj=tmerc +lat_0=0 +lon_0=7.123 +k=1 +x_0=1000 +y_0=0 +ellps=GRS80 "
      "+units=m +no_defs";
  const fs::path gpkg = dir_ / "local.gpkg";
  write(gpkg, "GPKG", {qgep_structures(local), qgep_reaches(local)});
  Diagnostics d;
  Result<SewerMap> map = read_gis_map(gpkg, d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_FALSE(map->crs().has_value());
  EXPECT_TRUE(has_warning(d, "has no AUTHORITY:CODE: the map has none (name it with --crs)"));
}

TEST_F(GdalImport, WrongGeometriesAreErrorsWithTheFeatureId) {
  Layer lines = qgep_reaches();
  lines.type = wkbMultiLineString25D;
  lines.rows[0].wkt = "MULTILINESTRING Z ((2600000 1200000 407.6, 2600020 1200000 407.4))";
  lines.rows[1].wkt =
      "MULTILINESTRING Z ((2600020 1200000 1, 2600020 1200007 1), (2600021 "
      "1200008 1, 2600020 1200015 1))";
  const fs::path gpkg = dir_ / "multi.gpkg";
  write(gpkg, "GPKG", {qgep_structures(), lines});
  Diagnostics d;
  Result<SewerMap> map = read_gis_map(gpkg, d);
  ASSERT_FALSE(map.has_value());
  EXPECT_THAT(map.error().message,
              HasSubstr("multi.gpkg:vw_qgep_reach: feature 2: error: the geometry is a "
                        "MULTILINESTRING of 2 parts: a pipe is a line"));
}

TEST_F(GdalImport, MissingLayersEmptyLayersAndMissingFieldsAreClearErrors) {
  Layer zones{.name = "zones",
              .type = wkbPolygon,
              .srs = "EPSG:2056",
              .fields = {{"name", OFTString}},
              .rows = {{"POLYGON ((0 0, 1 0, 1 1, 0 0))", {"Z"}}}};
  write(dir_ / "zones.gpkg", "GPKG", {qgep_structures(), zones});
  Diagnostics d;
  Result<SewerMap> no_lines = read_gis_map(dir_ / "zones.gpkg", d);
  ASSERT_FALSE(no_lines.has_value());
  EXPECT_THAT(no_lines.error().message,
              HasSubstr("no line layer for the pipes; the source has vw_qgep_wastewater_structure "
                        "(points), zones (other or mixed geometry)"));

  Layer empty = qgep_reaches();
  empty.rows.clear();
  write(dir_ / "empty.gpkg", "GPKG", {qgep_structures(), empty});
  Result<SewerMap> no_pipes = read_gis_map(dir_ / "empty.gpkg", d);
  ASSERT_FALSE(no_pipes.has_value());
  EXPECT_THAT(no_pipes.error().message,
              HasSubstr("layer vw_qgep_reach (the pipes) has no features"));

  Layer sizeless = qgep_reaches();
  sizeless.fields.back().first = "profile";
  write(dir_ / "sizeless.gpkg", "GPKG", {qgep_structures(), sizeless});
  Result<SewerMap> no_size = read_gis_map(dir_ / "sizeless.gpkg", d);
  ASSERT_FALSE(no_size.has_value());
  EXPECT_THAT(no_size.error().message,
              HasSubstr("sizeless.gpkg:vw_qgep_reach: error: no field for the pipe's clear height "
                        "(tried clear_height,"));
}

TEST_F(GdalImport, WhatGdalCannotOpenIsAnErrorNotACrash) {
  std::ofstream(dir_ / "text.gpkg") << "not a GeoPackage";
  Diagnostics d;
  Result<SewerMap> text = read_gis_map(dir_ / "text.gpkg", d);
  ASSERT_FALSE(text.has_value());
  EXPECT_EQ(text.error().code, ErrorCode::kParse);
  EXPECT_THAT(text.error().message, HasSubstr("text.gpkg: not a GeoJSON, GeoPackage or Shapefile"));
  Result<SewerMap> missing = read_gis_map(dir_ / "missing.gpkg", d);
  ASSERT_FALSE(missing.has_value());
  EXPECT_EQ(missing.error().code, ErrorCode::kIo);
  Result<SewerMap> no_shapefiles = read_gis_map(dir_, d);  // a directory without Shapefiles
  ASSERT_FALSE(no_shapefiles.has_value());
}

// A Los Angeles layer in US survey feet (EPSG:2229): 100 ft of pipe is 30.48 m, not 100 m, and
// the positions are metres too (docs/gis.md, "Units").
TEST_F(GdalImport, ALayerInUsSurveyFeetIsReadInMetres) {
  constexpr double kFtUs = 1200.0 / 3937.0;
  const Layer manholes{
      .name = "manholes",
      .type = wkbPoint,
      .srs = "EPSG:2229",
      .fields = {{"name", OFTString}, {"rim_elev", OFTReal}, {"invert_elev", OFTReal}},
      .rows = {{"POINT (6480000 1840000)", {"A", "300", "290"}},
               {"POINT (6480100 1840000)", {"B", "299", "289"}}}};
  const Layer pipes{
      .name = "pipes",
      .type = wkbLineString,
      .srs = "EPSG:2229",
      .fields = {{"name", OFTString},
                 {"from", OFTString},
                 {"to", OFTString},
                 {"diameter", OFTReal}},
      .rows = {{"LINESTRING (6480000 1840000,6480100 1840000)", {"P", "A", "B", "300"}}}};
  write(dir_ / "la.gpkg", "GPKG", {manholes, pipes});
  Diagnostics d;
  Result<SewerMap> map = read_gis_map(dir_ / "la.gpkg", d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_EQ(map->crs(), (Crs{"EPSG", 2229}));
  EXPECT_NEAR(map->pipe(*map->find_pipe("P")).length_m, 100 * kFtUs, 1e-6);
  const Manhole& a = map->manhole(*map->find_manhole("A"));
  EXPECT_NEAR(a.position.x_m, 6480000 * kFtUs, 1e-4);
  EXPECT_NEAR(a.position.z_m, 290 * kFtUs, 1e-9);
  EXPECT_NEAR(*a.depth_m, 10 * kFtUs, 1e-9);
  // The same through a Shapefile and its .prj.
  fs::create_directories(dir_ / "shp");
  write(dir_ / "shp", "ESRI Shapefile", {manholes, pipes});
  Result<SewerMap> shp = read_gis_map(dir_ / "shp", d);
  ASSERT_TRUE(shp.has_value()) << shp.error().message;
  EXPECT_NEAR(shp->pipe(*shp->find_pipe("P")).length_m, 100 * kFtUs, 1e-6);
}

// A GeoJSON of points and lines (WGS84, as RFC 7946 has it), by any name: read through GDAL's
// GeoJSON driver, its layer split by geometry, projected to the UTM zone it lies in.
TEST_F(GdalImport, APlainGeoJsonIsProjectedToItsUtmZone) {
  std::ofstream(dir_ / "plain.json") << R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "geometry": {"type": "Point", "coordinates": [9.0, 52.0]},
     "properties": {"name": "A", "invert_level": 50.0, "diameter": 1000}},
    {"type": "Feature", "geometry": {"type": "Point", "coordinates": [9.001, 52.0]},
     "properties": {"name": "B", "invert_level": 49.9, "diameter": 1000}},
    {"type": "Feature", "geometry": {"type": "LineString",
                                     "coordinates": [[9.0, 52.0], [9.001, 52.0]]},
     "properties": {"name": "P", "diameter": 300}}]})";
  Diagnostics d;
  Result<SewerMap> map = read_gis_map(dir_ / "plain.json", d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_EQ(map->crs(), (Crs{"EPSG", 32632}));
  EXPECT_TRUE(has_warning(d, "projected to EPSG:32632"));
  // 0.001 degrees of longitude at 52 degrees north: about 68.6 m (not 0.001).
  EXPECT_NEAR(map->pipe(*map->find_pipe("P")).length_m, 68.6, 0.5);
  EXPECT_DOUBLE_EQ(map->manhole(*map->find_manhole("B")).position.z_m, 49.9);
}

// sewerplan's own GeoJSON names the map's CRS ("sewerplan_crs"): it is read back into it.
TEST_F(GdalImport, SewerplansGeoJsonIsReadBackIntoTheCrsItNames) {
  std::ofstream(dir_ / "net.geojson") << R"({"type": "FeatureCollection", "name": "net",
    "sewerplan_crs": "EPSG:25832", "features": [
    {"type": "Feature", "geometry": {"type": "Point", "coordinates": [9.0, 52.0]},
     "properties": {"layer": "manhole", "name": "A", "diameter_m": 1.0, "shaft_l_m": 1.0,
                    "shaft_w_m": 1.0, "z_m": 50.0, "exit": true}},
    {"type": "Feature", "geometry": {"type": "Point", "coordinates": [9.001, 52.0]},
     "properties": {"layer": "manhole", "name": "B", "diameter_m": 0.8, "shaft_l_m": 1.2,
                    "shaft_w_m": 0.8, "z_m": 49.0, "exit": false}},
    {"type": "Feature", "geometry": {"type": "Point", "coordinates": [9.0005, 52.0]},
     "properties": {"layer": "inspection_point", "name": "W1", "pipe": "P", "offset_m": 30}},
    {"type": "Feature", "geometry": {"type": "LineString",
                                     "coordinates": [[9.0, 52.0], [9.001, 52.0]]},
     "properties": {"layer": "pipe", "name": "P", "from": "A", "to": "B", "length_m": 70.0,
                    "diameter_m": 0.3, "height_m": 0.3, "shape": "circular",
                    "from_lvl_m": 49.9, "to_lvl_m": 49.66, "from_az": 1.5, "to_az": -178.5}}]})";
  Diagnostics d;
  Result<SewerMap> map = read_gis_map(dir_ / "net.geojson", d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_EQ(map->crs(), (Crs{"EPSG", 25832}));
  EXPECT_FALSE(has_warning(d, "projected"));
  const ManholeId b = *map->find_manhole("B");
  EXPECT_EQ(map->manhole(b).shaft_length_m, 1.2);
  EXPECT_EQ(map->manhole(b).shaft_width_m, 0.8);
  EXPECT_DOUBLE_EQ(map->slot(b, SlotIndex{0}).invert_z_m, 49.66);
  EXPECT_DOUBLE_EQ(map->slot(b, SlotIndex{0}).azimuth_deg, -178.5);
  EXPECT_DOUBLE_EQ(map->pipe(*map->find_pipe("P")).length_m, 70.0);
  EXPECT_GT(map->manhole(b).position.x_m, 500000);  // UTM 32 eastings, not degrees
}

TEST(GisSource, HasItsFieldMappingBesideIt) {
  EXPECT_EQ(field_mapping_sidecar("a/net.gpkg"), fs::path("a/net.fields.json"));
}

}  // namespace
}  // namespace sewerplan::gis
