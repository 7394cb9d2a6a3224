// SPDX-License-Identifier: MIT
// Summary: the figures of a fault campaign, and how they are written (JSON, Markdown, SVG chart).
//
// Tasks are compared per run as a share of the oracle's (run.h; a run whose oracle does no task
// counts as 1), then averaged over the runs in which the oracle can end the mission (elsewhere no
// policy can, and the oracle does nothing); the worst run is named. Ours is compared with the
// baseline run by run (better, equal, worse). Outcomes are counted as the robot's true pose shows
// them; a run that could reach an exit but did not is a "missed exit". Planning times are measured,
// so only they (and wall times) differ between two machines.
//
//   Summary s = summarize(spec, records);
//   write_summary_markdown(s, std::cout);
//   std::ofstream svg("summary.svg"); write_summary_svg(s, svg);
//
// Thread safety: Pure functions: call them from any number of threads, each writer with its
// own stream.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "sewerplan/campaign/record.h"

namespace sewerplan::campaign {

struct PolicyFigures {
  double tasks_mean = 0;      // tasks done per run
  double vs_oracle_mean = 0;  // share of the oracle's tasks, mean over runs
  double vs_oracle_worst = 1;
  std::size_t worst_run = 0;
  std::array<std::size_t, 4> outcomes{};  // by Outcome
  std::size_t missed_exits = 0;           // could reach an exit, did not
  // By executor::MissionReport::BeaconCause, over the runs that end with the beacon (outcome
  // beacon: they sum to it), and over the runs that called for recovery yet ended otherwise,
  // whatever their outcome (most often a breakdown at an exit manhole: outcome exit, where the
  // robot can be recovered; issue 14).
  std::array<std::size_t, 6> beacon_causes{};
  std::array<std::size_t, 6> ended_otherwise_beacon_causes{};
  // Runs that ended below the reserve without the Replanner's exit-on-reserve.
  std::size_t reserve_violations = 0;
  std::size_t exits_on_reserve = 0;  // runs the Replanner sent out on the reserve
  double replans_mean = 0;
  std::size_t replans_max = 0;
  double planning_p50_ms = 0;  // measured
  double planning_p99_ms = 0;
  std::array<std::size_t, 11> vs_oracle_histogram{};  // [0,10%), ..., [90%,100%), 100% and more
};

struct FailedRun {
  std::size_t run = 0;
  std::uint64_t seed = 0;
  std::string status;  // "crash", "hang"
  std::string detail;
  std::string command;  // reproduces it
};

struct Summary {
  CampaignSpec spec;
  std::size_t runs = 0;       // records summarized
  std::size_t completed = 0;  // with a result
  std::size_t could_reach_exit = 0;
  double oracle_tasks_mean = 0;
  std::size_t oracle_below_ours = 0;  // runs the oracle can end where ours did more than it
  PolicyFigures ours;
  PolicyFigures baseline;
  std::size_t better_than_baseline = 0;  // runs, by tasks done
  std::size_t equal_to_baseline = 0;
  std::size_t worse_than_baseline = 0;
  // With risk-aware planning (RunResult::risk_aware): its figures, and it against ours (which is
  // risk-blind) run by run: by tasks done, and the runs where only one of them ended at an exit
  // or the end point.
  std::optional<PolicyFigures> risk_aware;
  std::size_t risk_aware_better = 0;
  std::size_t risk_aware_equal = 0;
  std::size_t risk_aware_worse = 0;
  std::size_t risk_aware_only_ended = 0;
  std::size_t risk_blind_only_ended = 0;
  std::vector<FailedRun> failed;  // crashes and hangs
  double wall_s = 0;              // measured: sum over runs

  // No crash, hang, missed exit, stranded run, reserve violation or beacon caused by a limit
  // (ours).
  bool clean() const;
};

Summary summarize(const CampaignSpec& spec, const std::vector<RunRecord>& records);

void write_summary_json(const Summary& summary, std::ostream& out);
void write_summary_markdown(const Summary& summary, std::ostream& out);
// A chart: tasks against the oracle (histogram, ours and baseline) and the outcomes.
void write_summary_svg(const Summary& summary, std::ostream& out);

}  // namespace sewerplan::campaign
