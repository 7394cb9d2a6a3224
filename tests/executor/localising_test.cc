// SPDX-License-Identifier: MIT
// The action controller's manhole verification (executor/src/localising.h): an update the filter
// refuses must not switch the verification off for the rest of the mission.
#include "localising.h"

#include <gtest/gtest.h>

#include "sewerplan/core/manhole_signature.h"
#include "sewerplan/core/map_queries.h"
#include "sewerplan/executor/learnt.h"

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
  // (a controller and a filter that disagree on how the robot faces: to the filter, a forward
  // drive goes on into the manhole, where the pipe's end holds the robot, and 10 m driven rules
  // that out: the filter is lost).
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

// A drive from M3 20 m into P3 (30 m, towards M4) that ends at a manhole, `seen` as a three-way
// manhole the map lacks (a lateral north) or detected without its signature: the odds the filter
// gives a junction there against every other explanation (M4 reached early, a false detection).
double odds_of_p3_junction(const Street& s, Localising& localising, bool seen) {
  const domain::InPipe start{s.pipe("P3"), 0};
  localising.reset(start, 1);
  std::optional<ManholeSignature> junction;
  if (seen) {
    junction = s.seen("M3", "P2");
    junction->slots.push_back({.relative_deg = 270, .step_m = 0, .diameter_m = 0.3});
    junction->shaft_diameter_m = 1.2;
  }
  const std::optional<Arrival> arrival =
      localising.follow(DriveForward{.speed_mps = 0.3, .distance_m = 30, .to_manhole = true},
                        driven(20, junction), start, s.at("M4", "P3"), 1);
  EXPECT_TRUE(arrival.has_value());
  double p = 0;
  double others = 0;
  for (const localisation::Hypothesis& h : localising.estimate().hypotheses) {
    (h.pose.at_unmapped_junction ? p : others) += h.probability;
  }
  return p / others;
}

// Issue 29: what the filter remembered of the pipes is saved with what the robot learnt, and the
// next mission's filter starts from it: an arrival at the junction the first mission found weighs
// as it would at the first mission's end, not as at a fresh start.
TEST(Localising, ASecondMissionFromTheSavedBeliefWeighsTheRememberedJunctionAsTheFirstEnded) {
  Street s;
  Localising first(s.map, 0.03);
  EXPECT_GT(odds_of_p3_junction(s, first, true), 100);  // seen, and remembered
  ASSERT_EQ(first.memory().junctions.size(), 1u);
  Learnt learnt;
  learnt.junctions = first.memory();
  Diagnostics d;
  const Result<Learnt> saved =
      read_learnt_json(learnt_json(learnt, s.map), "learnt.json", s.map, d);
  ASSERT_TRUE(saved.has_value()) << d.error_summary();

  // Then an arrival there whose signature was not observed: only the memory tells the junction.
  Localising fresh(s.map, 0.03);
  Localising second(s.map, 0.03, saved->junctions);
  EXPECT_EQ(second.memory(), saved->junctions);
  const double from_nothing = odds_of_p3_junction(s, fresh, false);
  const double remembered = odds_of_p3_junction(s, second, false);
  const double first_again = odds_of_p3_junction(s, first, false);  // the first mission going on
  EXPECT_GT(remembered / from_nothing, 100) << from_nothing << " " << remembered;
  EXPECT_NEAR(remembered / first_again, 1, 1e-6) << first_again << " " << remembered;
}

}  // namespace
}  // namespace sewerplan::executor::detail
