// SPDX-License-Identifier: MIT
// The Measurer fed with synthetic job reports (what a robot in a world unlike its map would send),
// and watching a whole mission of the Executor on the exact simulated world.
#include "sewerplan/executor/measuring.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>

#include <gtest/gtest.h>

#include "sewerplan/executor/event_json.h"
#include "sewerplan/hal/sim_robot.h"

#include "support/ais_testbed.h"
#include "support/small_map.h"

namespace sewerplan::executor {
namespace {

using testing::SmallMap;
using Kind = Discrepancy::Kind;

// M1 -P1 (10 m)- M2 -P2 (10 m)- M3, M2 a straight-through manhole.
SewerMap line() {
  return SmallMap()
      .manhole("M1", 0, 0, true)
      .manhole("M2", 10, 0)
      .manhole("M3", 20, 0)
      .pipe("P1", "M1", "M2")
      .pipe("P2", "M2", "M3")
      .build();
}

class MeasurerTest : public ::testing::Test {
 protected:
  MeasurerTest()
      : map_(line()),
        p1_(*map_.find_pipe("P1")),
        m1_(*map_.find_manhole("M1")),
        m2_(*map_.find_manhole("M2")),
        measurer_(map_, {"makro", "test", "2026-12-06T07:00:00Z"}) {}

  // Lowered into M1, into P1.
  void enter() {
    const domain::RobotPosition before = domain::InManhole{m1_};
    const domain::RobotPosition after = domain::InPipe{p1_, 0};
    measurer_.observe(EnterPipeFromManhole{0, 5}, hal::JobReport{}, before, after, 0);
  }

  // A drive to M2 (to_manhole) of `odometry` metres along P1 from `from_m`, which the controller
  // tracks onto the map (clamped at its length: at M2's mouth).
  void drive(double from_m, double odometry, hal::JobReport report = {}, double direction = 1) {
    report.progress_m = odometry;
    const double to = std::clamp(from_m + direction * odometry, 0.0, 10.0);
    const domain::RobotPosition before = domain::InPipe{p1_, from_m};
    const domain::RobotPosition after =
        to >= 10.0 && report.ok() ? domain::RobotPosition{domain::AtSlot{m2_, SlotIndex{0}}}
                                  : domain::RobotPosition{domain::InPipe{p1_, to}};
    measurer_.observe(DriveForward{0.3, odometry, true}, report, before, after, direction);
  }

  // A scan of the whole of P1 (a drive of the map's distance, not to a manhole) whose odometry
  // read `odometry` metres: the controller tracks it to M2's mouth.
  void scan(double odometry, hal::JobReport report = {}) {
    report.progress_m = odometry;
    measurer_.observe(Scan{0.1, 10.0}, report, domain::InPipe{p1_, 0},
                      domain::AtSlot{m2_, SlotIndex{0}}, 1);
  }

  ManholeSignature m2_seen() const { return expected_signature(map_, m2_, SlotIndex{0}); }

  SewerMap map_;
  PipeId p1_;
  ManholeId m1_;
  ManholeId m2_;
  Measurer measurer_;
};

TEST_F(MeasurerTest, AWholePipeDrivenIsALengthMeasurement) {
  enter();
  hal::JobReport arrived;
  arrived.observation = m2_seen();
  drive(0, 12.0, arrived);  // the wheels counted 12 m where the map says 10
  const MapMeasurements& m = measurer_.measurements();
  ASSERT_EQ(m.pipes.size(), 1u);
  EXPECT_EQ(m.pipes[0].pipe, p1_);
  EXPECT_DOUBLE_EQ(m.pipes[0].length_m.mean, 12.0);
  EXPECT_NEAR(m.pipes[0].length_m.variance, 0.30 * 0.30 + 0.05 * 0.05, 1e-12);  // 3 % of 10 m
  ASSERT_EQ(m.manholes.size(), 1u);
  EXPECT_EQ(m.manholes[0].manhole, m2_);
  ASSERT_EQ(m.manholes[0].observations.size(), 1u);
  EXPECT_EQ(m.manholes[0].observations[0].arrival, SlotIndex{0});
  ASSERT_TRUE(m.manholes[0].position.has_value());
  EXPECT_NEAR(m.manholes[0].position->x_m.mean, 12.0, 1e-12);  // along P1's chord, scaled
  const auto found = discrepancies(m, map_);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].discrepancy.kind, Kind::kLengthOff);
  EXPECT_EQ(found[0].sources, (SourceList{0}));
}

// In a pipe that falls more than 2 % the wheels slip twice as much: the leg's standard deviation
// is twice the flat pipe's, and a length within it is no discrepancy (on the 1,000-manhole meshed
// network such legs were 5 of 11 false length reports).
TEST(Measurer, ALegInASteepPipeIsTwiceAsUncertain) {
  const SewerMap map = SmallMap()
                           .manhole("M1", 0, 0, true)
                           .manhole("M2", 10, 0)
                           .pipe("P1", "M1", "M2")
                           .invert("M1", "P1", 0.5)  // 0.5 m over 10 m: 5 %
                           .build();
  Measurer measurer(map, {"makro", "test", "2026-12-06T07:00:00Z"});
  const PipeId p1 = *map.find_pipe("P1");
  const ManholeId m1 = *map.find_manhole("M1");
  const ManholeId m2 = *map.find_manhole("M2");
  measurer.observe(EnterPipeFromManhole{0, 5}, hal::JobReport{}, domain::InManhole{m1},
                   domain::InPipe{p1, 0}, 0);
  hal::JobReport arrived;
  arrived.progress_m = 11.2;
  arrived.observation = expected_signature(map, m2, SlotIndex{0});
  measurer.observe(DriveForward{0.3, 10}, arrived, domain::InPipe{p1, 0},
                   domain::AtSlot{m2, SlotIndex{0}}, 1);
  const MapMeasurements& m = measurer.measurements();
  ASSERT_EQ(m.pipes.size(), 1U);
  EXPECT_NEAR(m.pipes[0].length_m.variance, 0.6 * 0.6 + 0.05 * 0.05, 1e-12);
  // 1.2 m off is 2 sigma here (3.9 sigma in a flat pipe): not reported.
  for (const FoundDiscrepancy& f : discrepancies(m, map)) {
    EXPECT_NE(f.discrepancy.kind, Kind::kLengthOff) << describe(f.discrepancy, map);
  }
}

// In water the wheels slip twice as much: a leg with a drive that reported water
// (hal::JobReport::in_water) is twice as uncertain, and a length within that is no discrepancy
// (on AIS, 200 runs of the realistic world, such legs were 15 of 18 false length reports).
TEST_F(MeasurerTest, ALegDrivenInWaterIsTwiceAsUncertain) {
  enter();
  hal::JobReport wet;
  wet.in_water = true;
  drive(0, 6.0, wet);
  hal::JobReport arrived;
  arrived.observation = m2_seen();
  drive(6.0, 5.0, arrived);  // dry from here, but the leg had water: 11 m where the map says 10
  const MapMeasurements& m = measurer_.measurements();
  ASSERT_EQ(m.pipes.size(), 1U);
  EXPECT_NEAR(m.pipes[0].length_m.variance, 0.6 * 0.6 + 0.05 * 0.05, 1e-12);
  // 1 m off is 1.7 sigma here (3.3 sigma dry, beyond 3 and the floor): not reported.
  for (const FoundDiscrepancy& f : discrepancies(m, map_)) {
    EXPECT_NE(f.discrepancy.kind, Kind::kLengthOff) << describe(f.discrepancy, map_);
  }
}

TEST_F(MeasurerTest, ADryLegOffAsMuchIsALengthOff) {
  enter();
  hal::JobReport arrived;
  arrived.observation = m2_seen();
  drive(0, 11.2, arrived);
  const auto found = discrepancies(measurer_.measurements(), map_);
  ASSERT_EQ(found.size(), 1U);
  EXPECT_EQ(found[0].discrepancy.kind, Kind::kLengthOff);
}

// Every pass of a pipe drives the same length: its sigma is of the pipe's mapped length, not of
// what the pass read, so two passes weigh alike. With the reading's sigma a pass that slipped short
// weighed more and pulled the pooled mean down (on the meshed 1,000-manhole network, seed 1, run
// 12: passes of 11.2 and 14.7 m of a 16.6 m pipe pooled to 12.5 m; with the three seeds' other
// such pipes the length RMS of seeds 1-3 went 2.68 -> 2.28 %).
TEST_F(MeasurerTest, PassesOfAPipeWeighAlikeWhateverTheyRead) {
  hal::JobReport arrived;
  arrived.observation = m2_seen();
  enter();
  drive(0, 8.0, arrived);
  enter();
  drive(0, 12.0, arrived);
  const MapMeasurements& m = measurer_.measurements();
  ASSERT_EQ(m.pipes.size(), 1U);
  EXPECT_EQ(m.pipes[0].length_m.count, 2U);
  EXPECT_NEAR(m.pipes[0].length_m.mean, 10.0, 1e-12);
  EXPECT_NEAR(m.pipes[0].length_m.variance, (0.30 * 0.30 + 0.05 * 0.05) / 2, 1e-12);
}

TEST_F(MeasurerTest, DrivesBackAndForthAreSummedWithTheirSign) {
  enter();
  drive(0, 6.0);
  drive(6.0, 1.0, {}, -1);  // a scan backward
  drive(5.0, 5.5);
  ASSERT_EQ(measurer_.measurements().pipes.size(), 1u);
  EXPECT_DOUBLE_EQ(measurer_.measurements().pipes[0].length_m.mean, 10.5);
}

// A scan of the map's distance that saw no manhole is at the far mouth only by the map's length:
// in a pipe longer than mapped it stopped short of it, and the drive to the manhole that follows
// drives the rest. The leg ends where the robot arrives by its own report (a sighting, or a drive
// to the manhole it finished), as the localisation's arrivals do. Ended at the scan, the leg
// measured the map's length: on AIS (200 runs of the realistic world, seed 4) three legs of P4,
// a pipe 8 m on the map and 9.4 to 9.8 m truly, were 8.1 to 8.4 m.
TEST_F(MeasurerTest, ALegEndsWhereTheRobotArrivesNotWhereTheMapsLengthPutsIt) {
  enter();
  scan(10.1);  // the map's 10 m, and no manhole seen
  EXPECT_TRUE(measurer_.measurements().pipes.empty());
  hal::JobReport arrived;
  arrived.observation = m2_seen();
  drive(10.0, 1.5, arrived);  // the controller planned the rest from the end: 0 m by the map
  ASSERT_EQ(measurer_.measurements().pipes.size(), 1U);
  EXPECT_DOUBLE_EQ(measurer_.measurements().pipes[0].length_m.mean, 11.6);
  EXPECT_EQ(measurer_.measurements().manholes.at(0).observations.size(), 1U);

  // A scan that stopped at the manhole and saw it (a pipe shorter than mapped) ends its leg.
  enter();
  scan(9.2, arrived);
  ASSERT_EQ(measurer_.measurements().pipes.size(), 1U);
  EXPECT_EQ(measurer_.measurements().pipes[0].length_m.count, 2U);
  // And a drive to the manhole that the robot finished ends it, seen or not (a manhole missed at
  // a pipe's end stops the robot all the same; a robot without a manhole sensor sees none).
  enter();
  drive(0, 10.3);
  EXPECT_EQ(measurer_.measurements().pipes[0].length_m.count, 3U);
}

TEST_F(MeasurerTest, ALateralTheMapLacksIsAnUnmappedLateral) {
  enter();
  hal::JobReport arrived;
  ManholeSignature seen = m2_seen();
  seen.slots.insert(seen.slots.begin() + 1, SlotSighting{90, 0, 0.2});
  arrived.observation = seen;
  drive(0, 10.0, arrived);
  const auto found = discrepancies(measurer_.measurements(), map_);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].discrepancy.kind, Kind::kUnmappedLateral);
  EXPECT_EQ(found[0].discrepancy.manhole, m2_);
  // Arriving from the west (P1 leaves M2 at 180°), 90° counter-clockwise is south: 270°.
  EXPECT_NEAR(found[0].discrepancy.value, 270, 1e-9);
}

// A drive stopped short by an obstacle (or a danger, a fault, its bound) counted what it drove, and
// recovery backs up and drives on by drives the robot reports: the leg is their sum. Such legs were
// not measured: on the 1,000-manhole meshed network (40 runs of the realistic world, seed 3) 45 of
// the 485 whole passes of a pipe were lost so (measured, the length RMS of seeds 1-3 went 2.92 ->
// 2.68 %; on AIS, seeds 1-4, 2.20 -> 2.20 %).
// A manhole seen where the controller has the robot at the far end of the pipe, unlike the far
// manhole (the controller took it for a false detection): an arrival there that the robot does not
// see rests on the controller's word against its own sighting, and does not end the leg. On AIS
// (200 runs of the realistic world, seed 4, run 83) the robot passed M9 unseen into P14 and saw
// M12; the controller held it in P8 at 10 m, a drive of 0 m "arrived" at M9 unseen, and P8's 10 m
// measured 13.8 m: 39 % of the campaign's sum of squares (length RMS 2.60 -> 2.03 % without it).
TEST_F(MeasurerTest, AnArrivalUnseenWhereTheRobotSawAnotherManholeEndsNoLeg) {
  enter();
  hal::JobReport other;
  other.progress_m = 13.8;
  other.observation = ManholeSignature{.slots = {{0, 0, 0.3}}, .shaft_diameter_m = 1.0};
  measurer_.observe(DriveForward{0.3, 10.0, true}, other, domain::InPipe{p1_, 0},
                    domain::InPipe{p1_, 10.0}, 1);
  drive(10.0, 0.0);  // the controller's drive to M2 from there: 0 m, and nothing seen
  EXPECT_TRUE(measurer_.measurements().pipes.empty());
  hal::JobReport arrived;
  arrived.observation = m2_seen();
  enter();
  measurer_.observe(DriveForward{0.3, 10.0, true}, other, domain::InPipe{p1_, 0},
                    domain::InPipe{p1_, 10.0}, 1);
  drive(10.0, 0.4, arrived);  // it was a false detection after all: M2 seen 0.4 m on
  ASSERT_EQ(measurer_.measurements().pipes.size(), 1U);
  EXPECT_DOUBLE_EQ(measurer_.measurements().pipes[0].length_m.mean, 14.2);
}

TEST_F(MeasurerTest, ADriveStoppedShortAndDrivenOnIsOneLeg) {
  enter();
  drive(0, 4.0,
        {.error = hal::RobotError{hal::RobotErrorCause::kObstacle, "obstacle in P1 at 4.2 m"}});
  drive(4.0, 0.1, {}, -1);  // backing up, and on when the obstacle is gone
  hal::JobReport arrived;
  arrived.observation = m2_seen();
  drive(3.9, 6.4, arrived);
  ASSERT_EQ(measurer_.measurements().pipes.size(), 1U);
  EXPECT_DOUBLE_EQ(measurer_.measurements().pipes[0].length_m.mean, 10.3);
}

TEST_F(MeasurerTest, ALegWithAPushALostReportOrABadOdometryIsNotMeasured) {
  enter();
  drive(0, 4.0, {.error = hal::RobotError{hal::RobotErrorKind::kBlockage, "obstacle"}});
  hal::JobReport pushed;
  pushed.progress_m = 0.5;
  measurer_.observe(Push{0.1, 6.0}, pushed, domain::InPipe{p1_, 4.0}, domain::InPipe{p1_, 4.5}, 1);
  drive(4.5, 5.5);
  EXPECT_TRUE(measurer_.measurements().pipes.empty());
  enter();
  drive(0, 4.0, {.error = hal::RobotError{hal::RobotErrorCause::kLink, "no answer"}});
  drive(4.0, 6.0);
  EXPECT_TRUE(measurer_.measurements().pipes.empty());
  enter();
  drive(0, std::numeric_limits<double>::quiet_NaN());
  drive(0, 10.0);
  EXPECT_TRUE(measurer_.measurements().pipes.empty());
  ASSERT_EQ(measurer_.rejected().size(), 1u);
  EXPECT_NE(measurer_.rejected()[0].find("P1: odometry"), std::string::npos);
  // An observation that is no signature is refused, named.
  enter();
  hal::JobReport empty;
  empty.observation = ManholeSignature{};
  drive(0, 10.0, empty);
  EXPECT_TRUE(measurer_.measurements().manholes.empty() ||
              measurer_.measurements().manholes[0].observations.empty());
  EXPECT_NE(measurer_.rejected().back().find("M2: signature"), std::string::npos);
}

TEST_F(MeasurerTest, AManholeSeenInThePipeIsAJunctionOrTheFarOneArrivedEarly) {
  enter();
  hal::JobReport junction;
  ManholeSignature three = m2_seen();
  three.slots.push_back(SlotSighting{270, 0, 0.3});
  junction.observation = three;
  drive(0, 4.0, junction);  // a manhole at 4 m the map lacks: the controller has it in P1
  ASSERT_EQ(measurer_.measurements().junctions.size(), 1u);
  EXPECT_DOUBLE_EQ(measurer_.measurements().junctions[0].offset_m, 4.0);
  EXPECT_TRUE(measurer_.measurements().pipes.empty());
  // The pipe is 9 m, not 10: M2 seen (its signature) 1 m early ends the leg there.
  hal::JobReport early;
  early.observation = m2_seen();
  drive(4.0, 5.0, early);
  ASSERT_EQ(measurer_.measurements().pipes.size(), 1u);
  EXPECT_DOUBLE_EQ(measurer_.measurements().pipes[0].length_m.mean, 9.0);
  EXPECT_EQ(measurer_.measurements().manholes.at(0).observations.size(), 1u);
}

// A manhole seen within the odometry's reach of a pipe's end manhole is that manhole, not a
// junction the map lacks (issue 29: such sightings were most of the false junction reports).
TEST_F(MeasurerTest, AManholeSeenNearAnEndOfThePipeIsNoJunction) {
  enter();
  hal::JobReport seen;
  ManholeSignature three = m2_seen();
  three.slots.push_back(SlotSighting{270, 0, 0.3});  // unlike M2: not its early arrival
  seen.observation = three;
  drive(0, 0.3, seen);    // the mouth just left
  drive(0.3, 9.3, seen);  // 0.4 m short of M2, within 3 sigma of 9.6 m of odometry (0.87 m)
  EXPECT_TRUE(measurer_.measurements().junctions.empty());
  ASSERT_EQ(measurer_.rejected().size(), 2u);
  EXPECT_NE(measurer_.rejected()[1].find("too near to tell from it"), std::string::npos)
      << measurer_.rejected()[1];
  drive(9.6, 4.6, seen, -1);  // back to 5 m: a junction
  EXPECT_EQ(measurer_.measurements().junctions.size(), 1u);
}

// A turn the robot measured (JobReport::turn_measured_deg) is a measurement of the angle between
// the two slots of the manhole the controller had it in; with the turns through a T junction whose
// lateral leaves 8 degrees off the map, the lateral's direction is reported. Without them (a robot
// that does not measure its turns) the sightings alone, 8 degrees of noise each, do not show it.
TEST(Measurer, TurnsTheRobotMeasuredFindASlotAFewDegreesOff) {
  // M2: P1 from the west, P2 to the east, P3 to the north (truly at 98 degrees).
  const SewerMap map = SmallMap()
                           .manhole("M1", 0, 0, true)
                           .manhole("M2", 10, 0)
                           .manhole("M3", 20, 0)
                           .manhole("M4", 10, 10)
                           .pipe("P1", "M1", "M2")
                           .pipe("P2", "M2", "M3")
                           .pipe("P3", "M2", "M4")
                           .build();
  const ManholeId m2 = *map.find_manhole("M2");
  const auto slot_of = [&](const char* pipe) {
    const auto slots = map.slots(m2);
    for (std::uint16_t i = 0; i < slots.size(); ++i) {
      if (slots[i].pipe == *map.find_pipe(pipe)) return i;
    }
    return std::uint16_t{0};
  };
  const auto run = [&](bool measured) {
    Measurer measurer(map, {"makro", "test", "2026-12-06T07:00:00Z"});
    const std::uint16_t west = slot_of("P1");
    const std::uint16_t east = slot_of("P2");
    const std::uint16_t north = slot_of("P3");
    // Three passes: arriving from the west (the north mouth seen 8 degrees off), into the north
    // lateral, back out of it to the east; the joints measure 278 + 1, 278 - 1, ... for the
    // 270 degrees mapped from the west, and 262 -+ 1 for 270 from the north to the east.
    for (int pass = 0; pass < 3; ++pass) {
      hal::JobReport arrived;
      arrived.progress_m = 10;
      arrived.observation = expected_signature(map, m2, SlotIndex{west});
      for (SlotSighting& seen : arrived.observation->slots) {
        if (seen.relative_deg == 270) seen.relative_deg = 278;
      }
      measurer.observe(DriveForward{0.3, 10, true}, arrived,
                       domain::InPipe{*map.find_pipe("P1"), 0}, domain::AtSlot{m2, SlotIndex{west}},
                       1);
      for (const auto& [from, to, mapped] :
           {std::tuple{west, north, 270.0}, std::tuple{north, east, 270.0}}) {
        const double truly = to == north ? mapped + 8 : mapped - 8;
        hal::JobReport report;
        if (measured) report.turn_measured_deg = truly + (pass % 2 == 0 ? 1 : -1);
        const domain::RobotPosition before = domain::AtSlot{m2, SlotIndex{from}};
        const PipeId into = map.slot(m2, SlotIndex{to}).pipe;
        const domain::RobotPosition after = domain::InPipe{
            into, domain::end_offset_m(map.pipe(into), map.slot(m2, SlotIndex{to}).pipe_end)};
        measurer.observe(TurnInManhole{.from_slot = from, .to_slot = to}, report, before, after, 0);
      }
    }
    MapMeasurements m = measurer.measurements();
    return discrepancies(m, map);
  };
  EXPECT_TRUE(run(false).empty());
  const std::vector<FoundDiscrepancy> found = run(true);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].discrepancy.kind, Kind::kDirectionOff);
  EXPECT_EQ(found[0].discrepancy.manhole, m2);
  EXPECT_EQ(found[0].discrepancy.slot, SlotIndex{slot_of("P3")});
  EXPECT_NEAR(found[0].discrepancy.value, 98, 1);
}

// A turn measured at a manhole the controller does not know (one the map lacks, by sighting), one
// that failed, and one whose angle is not a direction are not measurements.
TEST(Measurer, OnlyATurnDoneThroughAMappedManholeIsMeasured) {
  const SewerMap map = line();
  const ManholeId m2 = *map.find_manhole("M2");
  Measurer measurer(map, {"makro", "test", "2026-12-06T07:00:00Z"});
  const domain::RobotPosition before = domain::AtSlot{m2, SlotIndex{0}};
  const domain::RobotPosition after = domain::InPipe{*map.find_pipe("P2"), 0};
  hal::JobReport report;
  report.turn_measured_deg = 181;
  measurer.observe(TurnInManhole{.from_slot = kBySighting, .to_slot = 1}, report, before, after, 0);
  hal::JobReport failed = report;
  failed.error = hal::RobotError{hal::RobotErrorCause::kDangerousPassage, "dangerous passage"};
  measurer.observe(TurnInManhole{.from_slot = 0, .to_slot = 1}, failed, before, before, 0);
  hal::JobReport bad = report;
  bad.turn_measured_deg = std::numeric_limits<double>::quiet_NaN();
  measurer.observe(TurnInManhole{.from_slot = 0, .to_slot = 1}, bad, before, after, 0);
  EXPECT_TRUE(measurer.measurements().manholes.empty());
  ASSERT_EQ(measurer.rejected().size(), 1u);
  EXPECT_NE(measurer.rejected()[0].find("M2: a turn measured at nan"), std::string::npos)
      << measurer.rejected()[0];
  measurer.observe(TurnInManhole{.from_slot = 0, .to_slot = 1}, report, before, after, 0);
  ASSERT_EQ(measurer.measurements().manholes.size(), 1u);
  ASSERT_EQ(measurer.measurements().manholes[0].turns.size(), 1u);
  EXPECT_EQ(measurer.measurements().manholes[0].turns[0],
            (TurnMeasurement{SlotIndex{0}, SlotIndex{1}, 181, 1.0, 0}));
}

// On the exact world of today's simulator, the mission's measurements are the map's: every pipe
// driven whole measures its map length, and nothing differs.
TEST(MeasuringMission, AnExactWorldMeasuresTheMapAndChangesNothingOfTheRun) {
  const testing::AisTestbed ais = testing::load_ais_testbed();
  auto run = [&](bool measure) {
    ManualClock clock;
    Replanner replanner(ais.map, ais.mission, {.clock = &clock});
    const auto& start = std::get<domain::InPipe>(replanner.progress().position);
    hal::SimRobot robot(ais.map, ais.mission.profile,
                        hal::InPipe{start.pipe, start.offset_m, hal::Heading::kTowardsEnd1}, {});
    Executor executor(ais.map, replanner, robot);
    std::ostringstream log;
    executor.subscribe(json_lines_writer(log));
    Measurer measurer(ais.map, {"makro", "paper", ""});
    if (measure) executor.subscribe_jobs(measurer.observer());
    executor.run();
    return std::pair{log.str(), measurer.measurements()};
  };
  const auto [plain_log, nothing] = run(false);
  const auto [log, m] = run(true);
  EXPECT_EQ(log, plain_log);
  EXPECT_TRUE(nothing.pipes.empty());
  ASSERT_GE(m.pipes.size(), 3u);
  for (const PipeMeasurement& p : m.pipes) {
    EXPECT_NEAR(p.length_m.mean, ais.map.pipe(p.pipe).length_m, 1e-9) << ais.map.pipe(p.pipe).name;
  }
  EXPECT_TRUE(discrepancies(m, ais.map).empty());
}

}  // namespace
}  // namespace sewerplan::executor
