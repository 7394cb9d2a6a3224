// SPDX-License-Identifier: MIT
// Summary: the figures of a fault campaign, and how they are written (JSON, Markdown, SVG chart).
//
// Tasks are compared per run as a share of the oracle's (run.h; a run whose oracle does no task
// counts as 1), then averaged over the runs in which the oracle can end the mission (elsewhere no
// policy can, and the oracle does nothing); the worst run is named. When the oracle can end no
// run there is nothing to compare: `compared` is 0 and the writers say so (no mean, no worst run).
// A run where a policy did more than the oracle's plan is counted (`above_oracle`, its own bin of
// the histogram), never folded into 100 %. Ours is compared with the baseline run by run (better,
// equal, worse). Outcomes are counted as the robot's true pose shows them; a run in which the
// oracle can end the mission and no permanent malfunction stopped that policy's robot, which did
// not end at an exit or the end point, is that policy's "missed exit". Planning times are
// measured, so only they (and wall times) differ between two machines.
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
  std::size_t compared = 0;   // runs compared with the oracle: those it can end
  double vs_oracle_mean = 0;  // share of the oracle's tasks, mean over those runs (0 if none)
  double vs_oracle_worst = 1;
  std::size_t worst_run = 0;
  std::size_t above_oracle = 0;  // compared runs where it did more tasks than the oracle's plan
  std::array<std::size_t, 4> outcomes{};  // by Outcome
  std::size_t could_reach_exit = 0;       // the oracle can end it, and this robot could move
  std::size_t missed_exits = 0;           // of those, not ended at an exit or the end point
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
  // The plans (first plans and replans) each rung of the anytime ladder answered, summed over the
  // runs, indexed by executor::PlanResponse::Rung.
  std::array<std::size_t, executor::PlanResponse::kRungCount> rungs{};
  // The first plans' computed stranding risk (Execution::strand_risk), mean over the runs; beside
  // it the share of missed exits (of could_reach_exit) with its 95 % Wilson interval.
  double strand_risk_mean = 0;
  double planning_p50_ms = 0;  // measured
  double planning_p99_ms = 0;
  // [0,10%), ..., [90%,100%), 100 %, more than the oracle (over the compared runs).
  std::array<std::size_t, 12> vs_oracle_histogram{};
};

// Ours' localisation and measured map against the true world, pooled over the runs scored
// (world_score.h; only with world errors): counts summed, the length RMS over every measured pipe
// of every run (each run's RMS weighted by its pipes).
struct WorldFigures {
  std::size_t runs = 0;  // runs scored
  WorldScore total;
  std::optional<double> correct_arrivals_pct() const;     // none: no arrival
  std::optional<double> length_rms_pct() const;           // none: no pipe measured
  std::optional<double> discrepancies_found_pct() const;  // none: none seeded within reach
  std::optional<double> false_reports_pct() const;        // none: none reported
};

// Pools the scores of `runs` (those without one are left out); none when no run has one.
std::optional<WorldFigures> pool_world_scores(const std::vector<const RunResult*>& runs);

struct FailedRun {
  std::size_t run = 0;
  std::uint64_t seed = 0;
  RunRecord::Status status = RunRecord::Status::kCrash;  // kCrash or kHang
  std::string detail;
  std::string command;  // reproduces it
};

struct Summary {
  CampaignSpec spec;
  std::size_t runs = 0;              // records summarized
  std::size_t completed = 0;         // with a result
  std::size_t could_reach_exit = 0;  // by ours (PolicyFigures::could_reach_exit)
  std::size_t oracle_can_end = 0;    // runs whose oracle can end the mission
  double oracle_tasks_mean = 0;
  // Runs where ours did more than the oracle: more tasks than its plan, or ended (an exit, the
  // end point) a mission the oracle could not end. Each one shows the oracle is no bound there.
  std::size_t oracle_below_ours = 0;
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
  // Ours against the true world (with world errors only): summary.json's "localisation" and
  // "corrected_map", null without.
  std::optional<WorldFigures> world;
  std::vector<FailedRun> failed;  // crashes and hangs
  double wall_s = 0;              // measured: sum over runs

  // No crash, hang, missed exit, stranded run, reserve violation or beacon caused by a limit
  // (ours).
  bool clean() const;
};

Summary summarize(const CampaignSpec& spec, const std::vector<RunRecord>& records);

// What makes the campaign not clean, one item a kind ("3 missed exits", "1 hang"); empty when it
// is clean. The Markdown and the SVG give the verdict with these.
std::vector<std::string> verdict_faults(const Summary& summary);

void write_summary_json(const Summary& summary, std::ostream& out);
void write_summary_markdown(const Summary& summary, std::ostream& out);
// A chart: the verdict, the fault rates and limits, tasks against the oracle over the runs it
// can end (histogram, ours and baseline; runs above the oracle in a bin of their own), the
// outcomes, missed exits, and how many runs the oracle could not end (not drawn).
void write_summary_svg(const Summary& summary, std::ostream& out);

}  // namespace sewerplan::campaign
