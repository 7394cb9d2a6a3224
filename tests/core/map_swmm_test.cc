// SPDX-License-Identifier: MIT
#include "sewerplan/core/map_swmm.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/map_io.h"
#include "sewerplan/core/map_queries.h"

#include "support/map_checks.h"
#include "support/paths.h"

namespace sewerplan {
namespace {

using testing::has_warning;
using ::testing::HasSubstr;
using testing::slot_of;

constexpr double kFt = 0.3048;

double deg(double dx, double dy) { return std::atan2(dy, dx) * 180 / std::numbers::pi; }

SewerMap load(const std::string& name, Diagnostics& d) {
  Result<SewerMap> map = read_map(sewerplan::testing::dataset_path("swmm/" + name), d);
  EXPECT_TRUE(map.has_value()) << (map.has_value() ? "" : map.error().message);
  return map.has_value() ? std::move(map).value() : SewerMap{};
}

TEST(MapSwmm, ReadsEpaExample1InMetres) {
  Diagnostics d;
  const SewerMap map = load("epa-example1.inp", d);
  // 13 [JUNCTIONS] + 1 [OUTFALLS]; 13 [CONDUITS].
  EXPECT_EQ(map.manhole_count(), 14U);
  EXPECT_EQ(map.pipe_count(), 13U);
  EXPECT_EQ(map.name(), "epa-example1");
  // FLOW_UNITS CFS: feet. Conduit 1: 9 -> 10, 400 ft, CIRCULAR 1.5 ft.
  const Pipe& p1 = map.pipe(*map.find_pipe("1"));
  EXPECT_DOUBLE_EQ(p1.length_m, 400 * kFt);
  EXPECT_DOUBLE_EQ(p1.diameter_m, 1.5 * kFt);
  EXPECT_EQ(p1.shape, PipeShape::kCircular);
  EXPECT_EQ(map.manhole(*p1.ends[0].manhole).name, "9");
  // Junction 21: invert 995? No: 990 ft; at (4926.32, 6105.26).
  const ManholeId j21 = *map.find_manhole("21");
  EXPECT_DOUBLE_EQ(map.manhole(j21).position.z_m, 990 * kFt);
  EXPECT_DOUBLE_EQ(map.manhole(j21).position.x_m, 4926.32 * kFt);
  EXPECT_DOUBLE_EQ(map.manhole(j21).diameter_m, 1.0);  // SWMM has none: the default
  EXPECT_TRUE(map.manhole(j21).exit);
  EXPECT_FALSE(map.manhole(*map.find_manhole("18")).exit);  // the outfall
  // Slots in [CONDUITS] order: 5 (20 -> 21), 6 (10 -> 21), 7 (21 -> 22).
  ASSERT_EQ(map.manhole(j21).slot_count, 3);
  EXPECT_EQ(map.pipe(map.slots(j21)[0].pipe).name, "5");
  EXPECT_EQ(map.pipe(map.slots(j21)[2].pipe).name, "7");
  // LINK_OFFSETS DEPTH: conduit 6's outlet offset 1 ft and conduit 7's inlet offset 1 ft lie
  // 1 ft above 21's invert; conduit 5 (offsets 0) on it.
  EXPECT_DOUBLE_EQ(slot_of(map, j21, "5").invert_z_m, 990 * kFt);
  EXPECT_DOUBLE_EQ(slot_of(map, j21, "6").invert_z_m, 990 * kFt + 1 * kFt);
  EXPECT_DOUBLE_EQ(slot_of(map, j21, "7").invert_z_m, 990 * kFt + 1 * kFt);
  EXPECT_NEAR(passage_step_m(map, j21, SlotIndex{0}, SlotIndex{2}), 0.3048, 1e-9);
  EXPECT_NEAR(passage_step_m(map, j21, SlotIndex{1}, SlotIndex{2}), 0.0, 1e-9);
  // Azimuths towards the other nodes: 20 at (5957.89, 6589.47), 22 at (4421.05, 4715.79).
  EXPECT_NEAR(slot_of(map, j21, "5").azimuth_deg, deg(5957.89 - 4926.32, 6589.47 - 6105.26), 1e-9);
  EXPECT_NEAR(slot_of(map, j21, "7").azimuth_deg, deg(4421.05 - 4926.32, 4715.79 - 6105.26), 1e-9);
  // About 25.1 and -110.0 degrees: 135.1 apart, so a 44.9 degree turn from 5 into 7.
  EXPECT_NEAR(passage_turn_deg(map, j21, SlotIndex{0}, SlotIndex{2}), 44.88, 0.01);
}

TEST(MapSwmm, AzimuthFollowsTheFirstVertex) {
  Diagnostics d;
  const SewerMap map = load("epa-example1.inp", d);
  // Conduit 10: 17 (6252.63, 2147.37) -> 18 (6631.58, 505.26) through (6673.68, 1368.42).
  const ManholeId n17 = *map.find_manhole("17");
  const ManholeId n18 = *map.find_manhole("18");
  EXPECT_NEAR(slot_of(map, n17, "10").azimuth_deg, deg(6673.68 - 6252.63, 1368.42 - 2147.37),
              1e-9);  // about -61.6, not -77.0 straight to 18
  EXPECT_NEAR(slot_of(map, n18, "10").azimuth_deg, deg(6673.68 - 6631.58, 1368.42 - 505.26),
              1e-9);  // about 87.2
}

TEST(MapSwmm, WarnsOnceForEachFallback) {
  Diagnostics d;
  load("epa-example1.inp", d);
  EXPECT_TRUE(has_warning(d, "14 nodes have no size in SWMM: manhole diameter 1 m assumed"));
  EXPECT_EQ(d.error_count(), 0U);
}

TEST(MapSwmm, ReadsBellingeInSiUnitsWithStorageDiameters) {
  Diagnostics d;
  const SewerMap map = load("bellinge-small.inp", d);
  EXPECT_EQ(map.manhole_count(), 16U);  // 15 [STORAGE] + 1 [OUTFALLS]
  EXPECT_EQ(map.pipe_count(), 15U);
  // G72F820_G72F810_l1: 47.4492480509699 m, CIRCULAR 0.35 m, offsets 0.0001 m above inverts
  // 23.369 (G72F820) and 22.879 (G72F810).
  const Pipe& p = map.pipe(*map.find_pipe("G72F820_G72F810_l1"));
  EXPECT_DOUBLE_EQ(p.length_m, 47.4492480509699);
  EXPECT_DOUBLE_EQ(p.diameter_m, 0.35);
  const ManholeId from = *map.find_manhole("G72F820");
  EXPECT_DOUBLE_EQ(slot_of(map, from, "G72F820_G72F810_l1").invert_z_m, 23.369 + 0.0001);
  // FUNCTIONAL 0 0 0.5: a constant plan area of 0.5 m2, a circle of 0.798 m.
  EXPECT_NEAR(map.manhole(from).diameter_m, std::sqrt(4 * 0.5 / std::numbers::pi), 1e-12);
  EXPECT_NEAR(map.manhole(from).diameter_m, 0.798, 1e-3);
  // Only the outfall has no size.
  EXPECT_TRUE(has_warning(d, "1 nodes have no size"));
}

TEST(MapSwmm, ReadsTheStatePlaneModel) {
  Diagnostics d;
  const SewerMap map = load("swmmio-state-plane.inp", d);
  EXPECT_EQ(map.manhole_count(), 45U);
  EXPECT_EQ(map.pipe_count(), 44U);
  // J1-025.1: J1-025 -> J1-026, 309.456216 ft, CIRCULAR 1.25 ft; MGD: feet.
  const Pipe& p = map.pipe(*map.find_pipe("J1-025.1"));
  EXPECT_DOUBLE_EQ(p.length_m, 309.456216 * kFt);
  EXPECT_DOUBLE_EQ(p.diameter_m, 1.25 * kFt);
  // Storage J1-035: FUNCTIONAL 15 0 0, 15 ft2 of plan area: a circle of 4.370 ft = 1.332 m.
  EXPECT_NEAR(map.manhole(*map.find_manhole("J1-035")).diameter_m,
              std::sqrt(4 * 15 / std::numbers::pi) * kFt, 1e-12);
  // Coordinates to scale: a pipe's length is close to its ends' distance.
  const Manhole& a = map.manhole(*p.ends[0].manhole);
  const Manhole& b = map.manhole(*p.ends[1].manhole);
  const double distance =
      std::hypot(a.position.x_m - b.position.x_m, a.position.y_m - b.position.y_m);
  EXPECT_NEAR(distance / p.length_m, 1.0, 0.1);
  EXPECT_EQ(connected_components(map).count, 1U);
}

// A small network with every feature the importer handles.
const std::string kSmall =
    "; a comment before the first section\n"
    "[TITLE]\n"
    "small test network\n"
    "[OPTIONS]\n"
    "FLOW_UNITS  CMS\n"
    "LINK_OFFSETS ELEVATION\n"
    "[JUNCTIONS]\n"
    ";;name invert maxdepth\n"
    "A  10.0  3\n"
    "B  9.5   3   ; trailing comment\n"
    "[OUTFALLS]\n"
    "OUT 9.0 FREE\n"
    "[STORAGE]\n"
    "S  9.8  4  0  CYLINDRICAL 1.2 1.5 0\n"
    "[CONDUITS]\n"
    "C1  A  B   20  0.013  10.2  *\n"  // ELEVATION: 10.2 absolute; '*' = B's invert
    "C2  B  OUT 15  0.013  9.6   9.0\n"
    "C3  S  B   12  0.013  *     9.9\n"
    "[PUMPS]\n"
    "P1  OUT  A  curve  ON\n"
    "[WEIRS]\n"
    "W1  S  OUT  TRANSVERSE 0 3.33\n"
    "[XSECTIONS]\n"
    "C1  EGG          0.9  0  0  0  1\n"
    "C2  RECT_CLOSED  0.6  0.4  0  0  2\n"
    "C3  CIRCULAR     0.5\n"
    "W1  RECT_OPEN    1  2\n"
    "[COORDINATES]\n"
    "A    0  0\n"
    "B   20  0\n"
    "OUT 20 -15\n"
    "[Polygons]\n"
    "sub1 1 1\n";

Result<SewerMap> parse(const std::string& text, Diagnostics& d) {
  return read_map_swmm(text, "net.inp", d);
}

TEST(MapSwmm, ReadsShapesElevationOffsetsAndFallbacks) {
  Diagnostics d;
  Result<SewerMap> map = parse(kSmall, d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_EQ(map->manhole_count(), 4U);
  EXPECT_EQ(map->pipe_count(), 3U);  // the pump and the weir are left out
  const Pipe& c1 = map->pipe(*map->find_pipe("C1"));
  EXPECT_EQ(c1.shape, PipeShape::kEgg);
  EXPECT_DOUBLE_EQ(c1.height_m, 0.9);
  EXPECT_DOUBLE_EQ(c1.diameter_m, 0.6);  // an egg is 2/3 as wide as high
  const Pipe& c2 = map->pipe(*map->find_pipe("C2"));
  EXPECT_EQ(c2.shape, PipeShape::kRectangular);
  EXPECT_DOUBLE_EQ(c2.diameter_m, 0.4);
  EXPECT_DOUBLE_EQ(c2.height_m, 0.6);
  const ManholeId b = *map->find_manhole("B");
  EXPECT_DOUBLE_EQ(slot_of(*map, *map->find_manhole("A"), "C1").invert_z_m, 10.2);
  EXPECT_DOUBLE_EQ(slot_of(*map, b, "C1").invert_z_m, 9.5);  // '*'
  EXPECT_DOUBLE_EQ(slot_of(*map, b, "C2").invert_z_m, 9.6);
  EXPECT_DOUBLE_EQ(slot_of(*map, b, "C3").invert_z_m, 9.9);
  EXPECT_DOUBLE_EQ(slot_of(*map, b, "C1").azimuth_deg, 180);  // towards A
  EXPECT_DOUBLE_EQ(slot_of(*map, b, "C2").azimuth_deg, -90);  // towards OUT
  // CYLINDRICAL 1.2 x 1.5: the smaller axis.
  EXPECT_DOUBLE_EQ(map->manhole(*map->find_manhole("S")).diameter_m, 1.2);
  EXPECT_TRUE(has_warning(d, "3 nodes have no size"));
  EXPECT_TRUE(has_warning(d, "2 pumps, orifices, weirs or outlets are not drivable: left out"));
  EXPECT_TRUE(has_warning(d, "1 conduits have several barrels"));
  EXPECT_TRUE(has_warning(d, "1 nodes have no [COORDINATES]"));
  // S has no coordinates: its one slot gets the fallback azimuth 0, and a warning.
  EXPECT_TRUE(has_warning(d, "2 pipe ends have no known direction"));
}

std::string error_text(const std::string& text) {
  Diagnostics d;
  Result<SewerMap> map = parse(text, d);
  EXPECT_FALSE(map.has_value());
  return map.has_value() ? "" : map.error().message;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

TEST(MapSwmm, ReportsBadRowsWithTheirLines) {
  // A truncated conduit row (line 16).
  EXPECT_THAT(error_text(replaced(kSmall, "C1  A  B   20  0.013  10.2  *\n", "C1  A  B  20\n")),
              HasSubstr("net.inp:16: error: [CONDUITS] row 'C1': too few fields"));
  EXPECT_THAT(error_text(replaced(kSmall, "B  9.5 ", "B  9,5 ")),
              HasSubstr("net.inp:10: error: B: invert elevation is not a number: '9,5'"));
  EXPECT_THAT(error_text(replaced(kSmall, "C3  CIRCULAR ", "C3  OVAL ")),
              HasSubstr("net.inp:26: error: link C3: unknown cross-section shape 'OVAL'"));
  EXPECT_THAT(error_text(replaced(kSmall, "C3  CIRCULAR     0.5\n", "")),
              HasSubstr("net.inp:18: error: conduit C3: no [XSECTIONS] row"));
  EXPECT_THAT(error_text(replaced(kSmall, "[TITLE]\n", "junk\n[TITLE]\n")),
              HasSubstr("net.inp:2: error: data before the first [SECTION]"));
}

TEST(MapSwmm, RejectsMixedUnits) {
  EXPECT_THAT(error_text(replaced(kSmall, "LINK_OFFSETS", "FLOW_UNITS CFS\nLINK_OFFSETS")),
              HasSubstr("net.inp:6: error: mixed units: FLOW_UNITS CFS here, but CMS at line 5"));
}

TEST(MapSwmm, ReportsBrokenReferencesAndDuplicatesAtTheirRows) {
  EXPECT_THAT(error_text(replaced(kSmall, "C2  B  OUT", "C2  B  NOWHERE")),
              HasSubstr("net.inp:17: error: pipe C2"));
  EXPECT_THAT(error_text(replaced(kSmall, "OUT 9.0 FREE", "A 9.0 FREE")),
              HasSubstr("duplicate manhole name 'A' (first defined at net.inp:9)"));
  EXPECT_THAT(error_text(replaced(kSmall, "P1  OUT", "C1  OUT")),
              HasSubstr("net.inp:20: error: duplicate link name 'C1': also a conduit"));
  EXPECT_THAT(error_text(replaced(kSmall, "OUT 20 -15\n", "OUT 20 -15\nA 1 1\n")),
              HasSubstr("net.inp:32: error: node A: coordinates given twice (first at line 29)"));
}

TEST(MapSwmm, WarnsAboutUnknownSectionsAndIgnoresThem) {
  Diagnostics d;
  Result<SewerMap> map =
      parse(replaced(kSmall, "[COORDINATES]", "[NEWTHING]\nx y\n[COORDINATES]"), d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_THAT(d.all().front().message, HasSubstr("unknown section [NEWTHING], ignored"));
  EXPECT_EQ(d.all().front().where, "net.inp:28");
}

TEST(MapSwmm, LeavesOutConduitsWithoutDimensions) {
  Diagnostics d;
  Result<SewerMap> map = parse(replaced(kSmall, "C3  CIRCULAR     0.5", "C3 IRREGULAR tr1"), d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_EQ(map->pipe_count(), 2U);
  EXPECT_TRUE(has_warning(d, "1 conduits with an IRREGULAR, CUSTOM, STREET or DUMMY"));
}

// Issue 15: a V-shaped trapezoidal channel (bottom width 0) and a DUMMY link are valid SWMM and
// no place for a robot: left out with a warning, not the whole file rejected.
TEST(MapSwmm, Issue15LeavesOutVChannelsAndDummyLinks) {
  Diagnostics d;
  Result<SewerMap> map =
      parse(replaced(replaced(kSmall, "C3  CIRCULAR     0.5", "C3  TRAPEZOIDAL  1.0  0  1  1"),
                     "C2  RECT_CLOSED  0.6  0.4  0  0  2", "C2  DUMMY  0  0  0  0"),
            d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_EQ(map->pipe_count(), 1U);
  EXPECT_TRUE(has_warning(d, "1 conduits have a cross-section of no clear size"));
  EXPECT_TRUE(has_warning(d, "1 conduits with an IRREGULAR, CUSTOM, STREET or DUMMY"));
  // Every shape with a zero width alike; a negative one is an error.
  Diagnostics d2;
  Result<SewerMap> open =
      parse(replaced(kSmall, "C3  CIRCULAR     0.5", "C3  RECT_OPEN  0.5  0"), d2);
  ASSERT_TRUE(open.has_value());
  EXPECT_TRUE(has_warning(d2, "1 conduits have a cross-section of no clear size"));
  EXPECT_THAT(error_text(replaced(kSmall, "C3  CIRCULAR     0.5", "C3  RECT_OPEN  0.5  -1")),
              HasSubstr("link C3: negative size"));
}

// Issue 15: a network of nodes without a drivable conduit is an error that says so.
TEST(MapSwmm, Issue15NodesWithoutConduitsAreAnError) {
  EXPECT_THAT(error_text("[JUNCTIONS]\nJ1 10 2\nJ2 9 2\n[COORDINATES]\nJ1 0 0\nJ2 1 1\n"),
              HasSubstr("net.inp: error: 2 nodes but no conduit a robot could drive"));
}

// Issue 15: Windows-1252 names are read, in UTF-8, with a warning.
TEST(MapSwmm, Issue15ReadsWindows1252Names) {
  Diagnostics d;
  const std::string latin1 =
      "C\xe4"
      "3";  // "Ca3" with an a-umlaut, in Windows-1252
  Result<SewerMap> map = parse(replaced(replaced(kSmall, "C3  S  B", latin1 + "  S  B"),
                                        "C3  CIRCULAR", latin1 + "  CIRCULAR"),
                               d);
  ASSERT_TRUE(map.has_value()) << (map.has_value() ? "" : map.error().message);
  EXPECT_TRUE(map->find_pipe("C\u00e4"
                             "3")
                  .has_value());
  EXPECT_TRUE(has_warning(d, "not UTF-8, and no encoding declared: read as Windows-1252"));
}

TEST(MapSwmm, IsNotWrittenButDetectedByContent) {
  Diagnostics d;
  Result<SewerMap> map = parse(kSmall, d);
  ASSERT_TRUE(map.has_value());
  const Result<void> written = write_map(*map, "/tmp/sewerplan-never-written.inp");
  ASSERT_FALSE(written.has_value());
  EXPECT_EQ(written.error().code, ErrorCode::kUnsupportedFormat);
  EXPECT_THAT(written.error().message, HasSubstr("does not write them"));
  Result<MapFormat> format = detect_map_format("net.txt", kSmall);
  ASSERT_TRUE(format.has_value());
  EXPECT_EQ(*format, MapFormat::kSwmm);
}

TEST(MapSwmm, RejectsAFileWithoutNodes) {
  EXPECT_THAT(error_text("[TITLE]\nnothing\n"), HasSubstr("not a SWMM network"));
  EXPECT_THAT(error_text(""), HasSubstr("not a SWMM network"));
}

std::size_t error_count(const Diagnostics& d) {
  return static_cast<std::size_t>(
      std::count_if(d.all().begin(), d.all().end(),
                    [](const Diagnostic& x) { return x.severity == Severity::kError; }));
}

// Issue 31: a schematic model ([MAP] Units None, as SWMM's GUI writes for a drawing on a canvas)
// whose drawing lies beyond 1e7 was refused whole. Its coordinates are no survey: the map is read
// with a warning, lengths from [CONDUITS], the drawing moved and shrunk to fit with its shape kept.
TEST(MapSwmm, Issue31ReadsASchematicDrawingBeyondTheCoordinateLimit) {
  const std::string schematic =
      replaced(replaced(kSmall, "[COORDINATES]\nA    0  0\nB   20  0\nOUT 20 -15\n",
                        "[COORDINATES]\nA    15000000  30000000\nB   35000000  30000000\n"
                        "OUT 35000000 10000000\n[VERTICES]\nC2 34000000 20000000\n"),
               "[Polygons]", "[MAP]\nDIMENSIONS 0 0 40000000 40000000\nUnits None\n[Polygons]");
  Diagnostics d;
  Result<SewerMap> map = parse(schematic, d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_TRUE(has_warning(d, "[MAP] UNITS NONE: the coordinates are a schematic drawing"));
  EXPECT_TRUE(has_warning(d, "the drawing reaches 35000000 m, beyond the 10000000 m"));
  EXPECT_EQ(map->crs(), std::nullopt);
  const Manhole& a = map->manhole(*map->find_manhole("A"));
  const Manhole& b = map->manhole(*map->find_manhole("B"));
  const Manhole& out = map->manhole(*map->find_manhole("OUT"));
  // Moved to start at (0, 0) and shrunk by 2 (the drawing is 2e7 wide and high).
  EXPECT_DOUBLE_EQ(a.position.x_m, 0);
  EXPECT_DOUBLE_EQ(a.position.y_m, 1e7);
  EXPECT_DOUBLE_EQ(b.position.x_m, 1e7);
  EXPECT_DOUBLE_EQ(out.position.y_m, 0);
  // Lengths from [CONDUITS], not from the drawing; directions as drawn (C2 through its vertex).
  EXPECT_DOUBLE_EQ(map->pipe(*map->find_pipe("C1")).length_m, 20);
  EXPECT_DOUBLE_EQ(slot_of(*map, *map->find_manhole("A"), "C1").azimuth_deg, 0);
  EXPECT_NEAR(slot_of(*map, *map->find_manhole("B"), "C2").azimuth_deg, deg(-1, -10), 1e-9);
  // Within the limit, the drawing stays where it is, with the same warning.
  Diagnostics d2;
  ASSERT_TRUE(
      parse(replaced(kSmall, "[Polygons]", "[MAP]\nUnits None\n[Polygons]"), d2).has_value());
  EXPECT_TRUE(has_warning(d2, "[MAP] UNITS NONE: the coordinates are a schematic drawing"));
  // Surveyed coordinates (Units Meters) beyond the limit are still an error: they would be wrong.
  EXPECT_THAT(error_text(replaced(schematic, "Units None", "Units Meters")),
              HasSubstr("x must be at most 10000000 m, got 15000000"));
}

// Issue 31: a storage unit wider than any manhole (a pond, a treatment tank) refused the model
// whole. No robot enters it: it is left out, naming it, and its conduits end blind there.
TEST(MapSwmm, Issue31LeavesOutAStorageUnitWiderThanAnyManhole) {
  // FUNCTIONAL, constant area 20000 m2 (A2 = 0): a pond 159.6 m across.
  Diagnostics d;
  Result<SewerMap> map = parse(
      replaced(kSmall, "S  9.8  4  0  CYLINDRICAL 1.2 1.5 0", "S  9.8  4  0  FUNCTIONAL 20000 0 0"),
      d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_FALSE(map->find_manhole("S").has_value());
  EXPECT_TRUE(has_warning(d, "storage unit S is 160 m across, more than the 100 m"));
  const Pipe& c3 = map->pipe(*map->find_pipe("C3"));
  EXPECT_FALSE(c3.ends[0].manhole.has_value());  // blind where the pond was
  EXPECT_EQ(map->manhole(*c3.ends[1].manhole).name, "B");
  EXPECT_DOUBLE_EQ(slot_of(*map, *map->find_manhole("B"), "C3").invert_z_m, 9.9);
  // A conduit between two such ponds has nowhere to lead: left out, named.
  Diagnostics d2;
  Result<SewerMap> two = parse(
      replaced(
          replaced(replaced(kSmall, "S  9.8  4  0  CYLINDRICAL 1.2 1.5 0",
                            "S  9.8  4  0  CYLINDRICAL 120 150 0\nT 9 4 0 CYLINDRICAL 200 200"),
                   "C3  S  B   12  0.013  *     9.9\n",
                   "C3  S  B   12  0.013  *     9.9\nC4 S T 50 0.013 * *\n"),
          "C3  CIRCULAR     0.5\n", "C3  CIRCULAR     0.5\nC4 CIRCULAR 1\n"),
      d2);
  ASSERT_TRUE(two.has_value()) << two.error().message;
  EXPECT_TRUE(has_warning(d2, "storage unit S is 120 m across"));
  EXPECT_TRUE(has_warning(d2, "conduit C4 joins two storage units that are left out"));
  EXPECT_FALSE(two->find_pipe("C4").has_value());
}

// Issue 31, the same class: a channel wider and higher than any pipe, and a Barrels count no plan
// needs, are warnings on the conduit, not a refusal.
TEST(MapSwmm, Issue31WarnsOnChannelsBeyondAnyPipeAndOnBadBarrels) {
  Diagnostics d;
  Result<SewerMap> map =
      parse(replaced(replaced(kSmall, "C3  CIRCULAR     0.5", "C3  RECT_OPEN  120  150"),
                     "C2  RECT_CLOSED  0.6  0.4  0  0  2", "C2  RECT_CLOSED  0.6  0.4  0  0  0.5"),
            d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_FALSE(map->find_pipe("C3").has_value());
  EXPECT_TRUE(has_warning(d, "conduit C3 is 120 m wide and high, more than the 100 m"));
  EXPECT_TRUE(has_warning(d, "1 conduits have a Barrels field that is not a whole number"));
  EXPECT_DOUBLE_EQ(map->pipe(*map->find_pipe("C2")).diameter_m, 0.4);
}

// Issue 31: a conduit from a node to itself gave three errors, two of them contradicting the
// first ("names pipe C4 a second time", "has no slot for it"): now one, at its row.
TEST(MapSwmm, Issue31AConduitFromANodeToItselfIsOneError) {
  Diagnostics d;
  Result<SewerMap> map =
      parse(replaced(replaced(kSmall, "C3  S  B   12  0.013  *     9.9\n",
                              "C3  S  B   12  0.013  *     9.9\nC4  A  A  5  0.013  10.0  10.0\n"),
                     "C3  CIRCULAR     0.5\n", "C3  CIRCULAR     0.5\nC4  CIRCULAR 0.5\n"),
            d);
  ASSERT_FALSE(map.has_value());
  EXPECT_EQ(error_count(d), 1U) << map.error().message;
  EXPECT_THAT(map.error().message,
              HasSubstr("net.inp:19: error: pipe C4: joins manhole A to itself"));
  // A pump (weir, ...) from a node to itself is left out like every pump, with a warning naming it.
  Diagnostics d2;
  ASSERT_TRUE(parse(replaced(kSmall, "P1  OUT  A", "P1  OUT  OUT"), d2).has_value());
  EXPECT_TRUE(has_warning(d2, "pump P1 joins node OUT to itself"));
}

// Issue 31: control characters of the input (a NUL in a name) are escaped in messages.
TEST(MapSwmm, Issue31EscapesControlCharactersInMessages) {
  const std::string nul("\0", 1);
  const std::string message =
      error_text(replaced(replaced(kSmall, "C3  S  B", "C" + nul + "3  S  B"), "C3  CIRCULAR",
                          "C" + nul + "3  CIRCULAR"));
  EXPECT_THAT(message, HasSubstr("pipe name 'C\\x003' is empty, contains white space or control"));
  EXPECT_EQ(message.find('\0'), std::string::npos);
  const std::string bell = error_text(replaced(kSmall, "B  9.5 ", "B  9\a5 "));
  EXPECT_THAT(bell, HasSubstr("invert elevation is not a number: '9\\x075'"));
}

}  // namespace
}  // namespace sewerplan
