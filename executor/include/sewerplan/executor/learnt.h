// SPDX-License-Identifier: MIT
// Learnt: what the robot found out about the sewer on its missions, owned by the Replanner.
//
// The operator's Mission says what to do; what the robot met that its recovery could not clear
// (blockages, danger spots in pipes, dangerous passages through manholes) is knowledge of the
// sewer, kept apart from it in a Learnt, which the Replanner adds to its view of the mission
// when it plans. So is what the robot's drives taught about the hazards of the condition data
// (Mission::hazards, risk-aware planning): each hazard passed safely, or met as a blockage, has
// its probability updated (HazardBelief, a Beta belief whose prior is the risk table's
// probability; docs/executor.md, "Probabilities that learn"). Saved as JSON, it lets a second
// mission in the same sewer start from what the first learnt (CLI: `simulate --learnt FILE`; the
// format is in docs/executor.md).
//
//   Diagnostics d;
//   Result<Learnt> learnt = read_learnt("learnt.json", map, d);  // "learnt.json:$.danger[0].pipe:
//   ..." if (learnt.has_value()) (void)replanner.learn(*learnt);
//   ... after the mission:  write_text_file("learnt.json", learnt_json(replanner.learnt(), map));
//
// Thread safety: A Learnt is a plain value: safe to copy and to read from several threads, not
// to change while read. The free functions share nothing.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/localisation/topological_filter.h"

namespace sewerplan::executor {

inline constexpr std::string_view kLearntJsonFormat = "sewerplan-learnt";
// Version 2 added "hazards", version 3 "junction_memory", version 4 its "mouths"; files of
// earlier versions (without them) are read as before.
inline constexpr int kLearntJsonVersion = 4;

// The prior strength of a hazard's belief when none is given (ReplannerOptions::hazard_learning):
// the risk table's probability weighs as much as this many observations.
inline constexpr double kDefaultHazardPriorStrength = 2;

// What the robot learnt about one hazard of the mission (Mission::hazards, the same pipe, offset
// and reason): the probability that it stops the robot, a Beta(a, b) belief. Its prior is the
// risk table's probability p0 with a strength of k pseudo-observations (a = k p0, b = k (1 - p0));
// each safe pass is an observation of "not blocked" (b + 1), so after n passes the probability,
// the belief's mean, is k p0 / (k + n) (hazard_probability_after_pass). A hazard the robot met as
// a blockage is certain: probability 1, `blocked`, and a learnt blockage (Learnt::blockages).
struct HazardBelief {
  PipeId pipe{0};
  double offset_m = 0;     // from the pipe's ends[0], as the hazard's
  std::string reason;      // the hazard's ("BBA roots"): two findings at one place stay apart
  double probability = 0;  // of being stopped there now, 0..1
  std::size_t passes = 0;  // safe passes observed since the risk table's prior
  bool blocked = false;    // met as a blockage: probability 1
  friend bool operator==(const HazardBelief&, const HazardBelief&) = default;
};

struct Learnt {
  std::vector<Blockage> blockages;             // obstacles recovery could not clear
  std::vector<Blockage> danger_spots;          // spots in pipes the robot must not drive onto
  std::vector<ClosedPassage> closed_passages;  // dangerous passages, closed both ways
  std::vector<HazardBelief> hazards;           // hazards passed or met, with what that taught
  // What the topological filter remembered of the pipes (localisation::JunctionMemory): the
  // manholes the map lacks it became confident of, and the stretches driven without one. The
  // next mission's filter starts from it (TopologicalFilter::recall).
  localisation::JunctionMemory junctions;
  bool empty() const {
    return blockages.empty() && danger_spots.empty() && closed_passages.empty() &&
           hazards.empty() && junctions.empty();
  }
  friend bool operator==(const Learnt&, const Learnt&) = default;
};

// The probability of a hazard after one more safe pass, from `probability` after `passes` passes
// with a prior of strength `prior_strength` (HazardBelief): the Beta belief's mean
// a / (a + b + 1), where a = probability x (prior_strength + passes) and a + b = prior_strength +
// passes. 1 stays 1 only for a prior strength of infinity; 0 stays 0.
double hazard_probability_after_pass(double probability, std::size_t passes, double prior_strength);

// Whether `belief` is about `hazard`: the same pipe and reason, the offset within a micrometre.
bool same_hazard(const HazardBelief& belief, const Hazard& hazard);

// `mission` as the planner sees it with `learnt`: every blockage and danger spot a blockage,
// every dangerous passage closed, and every hazard of the mission that a belief is about
// (same_hazard) with the belief's probability. A belief about no hazard of the mission (another
// risk table, planning without --risk expected) changes nothing.
Mission with_learnt(Mission mission, const Learnt& learnt);

// Whether `belief` can be learnt on `map`: a known pipe, a finite offset within it, a probability
// from 0 to 1 (not NaN), and 1 if it is blocked. The error names the hazard and what is wrong.
Result<void> check_hazard_belief(const HazardBelief& belief, const SewerMap& map);

// Reads the JSON format (versions 1 to 3); every problem is a diagnostic at "file:$.path" naming
// the object (an unknown pipe or manhole, an offset outside the pipe, a slot the manhole does not
// have, a probability outside 0..1, a remembered junction outside its pipe).
Result<Learnt> read_learnt_json(std::string_view text, const std::string& file_name,
                                const SewerMap& map, Diagnostics& diagnostics);
Result<Learnt> read_learnt(const std::filesystem::path& path, const SewerMap& map,
                           Diagnostics& diagnostics);
// The JSON text; read_learnt_json reads it back to an equal Learnt.
std::string learnt_json(const Learnt& learnt, const SewerMap& map);

}  // namespace sewerplan::executor
