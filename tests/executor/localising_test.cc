// SPDX-License-Identifier: MIT
// The action controller's manhole verification (executor/src/localising.h): an update the filter
// refuses must not switch the verification off for the rest of the mission.
#include "localising.h"

#include <gtest/gtest.h>

#include "sewerplan/core/manhole_signature.h"
#include "sewerplan/core/map_queries.h"

#include "support/small_map.h"

namespace sewerplan::executor::detail {
namespace {

using testing::SmallMap;

// M1 -P1 (40 m)- M2 -P2 (30 m)- M3 -P3 (30 m)- M4, east; a lateral P4 north from M3 to N3, so M3
// looks unlike M2 and M4.
struct Street {
  SewerMap map = SmallMap()
                     .manhole("M1", 0, 0, /*exit=*/true)
                     .manhole("M2", 40, 0)
                     .manhole("M3", 70, 0)
                     .manhole("M4", 100, 0)
                     .manhole("N3", 70, 30)
                     .pipe("P1", "M1", "M2")
                     .pipe("P2", "M2", "M3")
                     .pipe("P3", "M3", "M4")
                     .pipe("P4", "M3", "N3", 0.3)
                     .build();
  PipeId pipe(const char* name) const { return *map.find_pipe(name); }
  domain::AtSlot at(const char* manhole, const char* pipe) const {
    const ManholeId m = *map.find_manhole(manhole);
    const PipeId p = this->pipe(pipe);
    return domain::AtSlot{m, map.pipe(p).ends[*end_in_manhole(map, p, m)].slot};
  }
  ManholeSignature seen(const char* manhole, const char* pipe) const {
    const domain::AtSlot a = at(manhole, pipe);
    return expected_signature(map, a.manhole, a.slot);
  }
};

hal::JobReport driven(double progress_m, std::optional<ManholeSignature> observation = {}) {
  hal::JobReport r;
  r.progress_m = progress_m;
  r.duration_s = progress_m / 0.3;
  r.observation = std::move(observation);
  return r;
}

TEST(Localising, ARefusedUpdateRestartsTheFilterFromTheTrackingAndLaterArrivalsAreStillChecked) {
  Street s;
  Localising localising(s.map, 0.03);
  localising.reset(s.at("M2", "P1"), 0);
  // The robot arrived at M2 front first; the tracking then has a forward drive of 10 m into P2
  // (a controller and a filter that disagree on how the robot faces: the filter refuses to drive
  // forward into the manhole).
  const domain::InPipe in_p2{s.pipe("P2"), 10};
  EXPECT_FALSE(localising
                   .follow(DriveForward{.speed_mps = 0.3, .distance_m = 10}, driven(10),
                           s.at("M2", "P1"), in_p2, 1)
                   .has_value());
  EXPECT_EQ(localising.restarts(), 1);
  ASSERT_FALSE(localising.estimate().lost());
  EXPECT_EQ(localising.estimate().best().pose.position, domain::RobotPosition(in_p2));

  // On to M4 by the tracking; the robot sees M3 (its lateral) 20 m on: the arrival is checked,
  // and found to be not at M4.
  const std::optional<Arrival> wrong =
      localising.follow(DriveForward{.speed_mps = 0.3, .distance_m = 20, .to_manhole = true},
                        driven(20, s.seen("M3", "P2")), in_p2, s.at("M4", "P3"), 1);
  ASSERT_TRUE(wrong.has_value());
  EXPECT_FALSE(wrong->verification.matches());
  ASSERT_TRUE(wrong->verification.believed.has_value());
  EXPECT_EQ(wrong->verification.believed->position, domain::RobotPosition(s.at("M3", "P2")))
      << wrong->verification.reason;
  EXPECT_EQ(localising.restarts(), 1);
}

TEST(Localising, AnUpdateTheFilterAcceptsNeverRestartsIt) {
  Street s;
  Localising localising(s.map, 0.03);
  localising.reset(domain::InPipe{s.pipe("P2"), 0}, 1);
  const std::optional<Arrival> at_m3 = localising.follow(
      DriveForward{.speed_mps = 0.3, .distance_m = 30, .to_manhole = true},
      driven(30, s.seen("M3", "P2")), domain::InPipe{s.pipe("P2"), 0}, s.at("M3", "P2"), 1);
  ASSERT_TRUE(at_m3.has_value());
  EXPECT_TRUE(at_m3->verification.matches()) << at_m3->verification.reason;
  EXPECT_EQ(localising.restarts(), 0);
}

}  // namespace
}  // namespace sewerplan::executor::detail
