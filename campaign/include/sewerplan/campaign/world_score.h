// SPDX-License-Identifier: MIT
// WorldScore: how well a robot knew where it was, and how well it measured its map, scored against
// the true world of a campaign run (issue 29's acceptance figures).
//
// With world errors (hal/world_errors.h) the robot plans on the map and drives a true world; the
// simulator knows where the robot really is (hal::SimRobot::pose(), in the world's terms), the
// robot does not. A WorldScorer watches one execution from outside the robot's loop: at each
// arrival the action controller verified (executor ArrivalEvent) it compares the manhole the
// controller believes with the one the simulated robot is truly at, and it measures the map as
// `simulate --corrected-map` does (executor/measuring.h) to score the measured lengths and the
// discrepancy report against the seeded truth. It only reads the simulated robot's pose: nothing
// of the truth reaches the executor, the Replanner or the measuring.
//
// The definitions (docs/campaign.md, "Localisation and the corrected map"):
//   - an arrival is correct when the believed manhole (ArrivalEvent::manhole) is the map manhole
//     the robot is truly at; when the robot is truly in a pipe (a false detection) or at a manhole
//     only the world has (an unmapped junction), when it believes no mapped manhole;
//   - length error of a measured map pipe: (measured - true) / true, the true length being the
//     world's, both pieces of a pipe an unmapped junction splits (hal::world_length_m);
//   - a seeded discrepancy is within reach when the robot truly passed it: length-off and
//     diameter-smaller on a map pipe it drove whole (into it at one mouth, out at the other),
//     unmapped-junction when it truly arrived at that junction, direction-off when it truly
//     drove through that slot's mouth (into its pipe, or out of it into the manhole: the issue's
//     "discrepancies on driven pipes"; a mouth only seen from another is seen to 8 degrees, as
//     far off as the realistic world's slots), unmapped-lateral and missing-lateral at a manhole
//     it truly arrived in; position-off never (a robot without
//     absolute positioning cannot tell a displaced manhole from a pipe longer than its chord, so
//     the measuring reports none: DiscrepancyThresholds::report_positions);
//   - it is found when a reported discrepancy is the same difference (same_difference(): the same
//     kind on the same object, an unmapped junction on the same pipe within 5 m); a report is
//     false when it is the same difference as no seeded discrepancy at all.
//
//   WorldScorer scorer(map, truth, robot);
//   scorer.watch(executor);
//   executor.run();
//   WorldScore s = scorer.score();
//
// Thread safety: plain values and pure functions; a WorldScorer is used on the thread that runs
// its execution.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include "sewerplan/core/map_discrepancy.h"
#include "sewerplan/core/map_measurements.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/executor/measuring.h"
#include "sewerplan/hal/sim_robot.h"
#include "sewerplan/hal/world_errors.h"

namespace sewerplan::campaign {

// The discrepancy counts of one kind (below).
struct KindScore {
  std::size_t in_reach = 0;       // seeded within reach
  std::size_t found = 0;          // of those, reported
  std::size_t reported = 0;       // reports of this kind
  std::size_t false_reports = 0;  // of those, matching no seeded one
  friend bool operator==(const KindScore&, const KindScore&) = default;
};
// Per Discrepancy::Kind, by its index: which kinds the robot finds and which it misses.
using ScoresByKind = std::array<KindScore, kDiscrepancyKinds>;

// One execution's figures, counts so that a campaign pools them exactly.
struct WorldScore {
  std::size_t arrivals = 0;          // arrivals the controller verified (ArrivalEvents)
  std::size_t correct_arrivals = 0;  // of those, believed manhole == true manhole
  std::size_t pipes_measured = 0;    // map pipes with a measured length
  double length_rms_pct = 0;         // RMS of (measured - true) / true over them, in %; 0 when none
  std::size_t seeded_in_reach = 0;   // seeded discrepancies the robot truly passed
  std::size_t found = 0;             // of those, reported
  std::size_t reported = 0;          // discrepancies the robot reported
  std::size_t false_reports = 0;     // of those, matching no seeded one
  ScoresByKind by_kind{};            // the four above, kind by kind
  friend bool operator==(const WorldScore&, const WorldScore&) = default;
};

// 100 * part / whole, or none when whole is 0 (the writers' null).
std::optional<double> percent(std::size_t part, std::size_t whole);

// Whether an arrival the controller believes is at map manhole `believed_manhole` (its name;
// empty: at no mapped manhole) is right, the robot truly being at `true_pose` in `world`, whose
// first map.manhole_count() manholes are the map's (hal/world_errors.h keeps their IDs).
bool arrival_correct(const SewerMap& map, const hal::SimPose& true_pose,
                     std::string_view believed_manhole);

// (measured - true) / true of each measured pipe of `measurements`, true lengths from `truth`.
std::vector<double> length_errors(const SewerMap& map, const hal::TrueWorld& truth,
                                  const MapMeasurements& measurements);
// The root mean square of `values` (0 for none).
double rms(const std::vector<double>& values);

// A map manhole's slot.
struct MouthOf {
  ManholeId manhole;
  SlotIndex slot;
  friend bool operator==(const MouthOf&, const MouthOf&) = default;
};

// What the robot truly passed (above): map pipes driven whole, map manholes arrived in, the map
// pipes whose unmapped junction it arrived at, and the mouths of map manholes it drove through.
struct Reach {
  std::vector<PipeId> pipes_driven_whole;
  std::vector<ManholeId> manholes_arrived;
  std::vector<PipeId> junctions_arrived;  // by the map pipe the junction splits
  std::vector<MouthOf> mouths_driven;
};
bool within_reach(const Discrepancy& seeded, const Reach& reach);

struct DiscrepancyScore {
  std::size_t in_reach = 0;
  std::size_t found = 0;
  std::size_t reported = 0;
  std::size_t false_reports = 0;
  ScoresByKind by_kind{};
  friend bool operator==(const DiscrepancyScore&, const DiscrepancyScore&) = default;
};
DiscrepancyScore score_discrepancies(const std::vector<Discrepancy>& seeded,
                                     const std::vector<FoundDiscrepancy>& reported,
                                     const Reach& reach);

// Watches one execution (above). `map`, `truth` and `robot` must outlive it; `robot` drives
// `truth.world`.
class WorldScorer {
 public:
  WorldScorer(const SewerMap& map, const hal::TrueWorld& truth, const hal::SimRobot& robot);
  WorldScorer(const WorldScorer&) = delete;
  WorldScorer& operator=(const WorldScorer&) = delete;

  // Subscribes to `executor`'s events and jobs; before its run(). The scorer must outlive the run.
  void watch(executor::Executor& executor);
  // The figures of what was watched: the measurements' discrepancies derived with the default
  // thresholds, as `simulate --corrected-map` reports them.
  WorldScore score() const;

  // What the robot truly passed so far, and what it measured.
  const Reach& reach() const { return reach_; }
  const MapMeasurements& measurements() const { return measurer_.measurements(); }

 private:
  void on_job(const executor::JobSeen& seen);
  std::optional<PipeId> map_pipe(PipeId world_pipe) const;
  // The robot went from world pipe `from` into `to` in one job: through the manhole they share,
  // by both its mouths (a manhole missed), which count as driven through.
  void through_unseen(PipeId from, PipeId to);

  const SewerMap& map_;
  const hal::TrueWorld& truth_;
  const hal::SimRobot& robot_;
  executor::Measurer measurer_;
  std::size_t arrivals_ = 0;
  std::size_t correct_ = 0;
  Reach reach_;
  std::optional<PipeId> in_pipe_;  // the world pipe the robot was truly in after the last job
  // The world pipe and end the robot last truly entered or arrived at.
  struct Mouth {
    PipeId pipe{0};
    std::uint8_t end = 0;
  };
  std::optional<Mouth> last_mouth_;
};

}  // namespace sewerplan::campaign
