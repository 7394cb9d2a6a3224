// SPDX-License-Identifier: MIT
// run_campaign: many seeded runs (run.h) in parallel, each guarded in a child process.
//
// Worker threads take runs in index order; each run is computed in a forked child that writes its
// record as one JSON line to a pipe. A child killed by a signal is a crash, one still running at
// the time limit is killed (SIGKILL) and is a hang; either is recorded with its seed and the
// campaign goes on. A progress callback sees every finished run. The records come back in index
// order, so the output does not depend on the number of threads. A stop condition (a cancel flag
// set from another thread, a time limit) ends the campaign early: no run starts after it fires,
// and the guarded children still running are killed at once (within the guard's 20 ms poll); the
// records returned are then those of the runs that finished.
//
//   CampaignOptions options{.jobs = 2, .timeout_s = 60};
//   std::vector<RunRecord> records = run_campaign(map, mission, spec, options);
//   Summary s = summarize(spec, records);  // summary.h
//
// Thread safety: run_campaign may be called from any thread; it only reads the map and
// mission. Guarded, it starts its own worker threads and forks a child per run from them, so the
// caller's other threads should hold no lock a run needs. `progress` runs on the thread that
// called run_campaign, one call at a time, with no lock of the campaign's held: a slow callback
// holds up no worker and no running child, and a stop is honoured meanwhile. Guarded, no child is
// forked while it runs (its allocations stay out of a fork: an allocator that is not safe to fork
// under, such as ASan's before LLVM 17, would leave the child waiting on its lock), so it should
// return promptly: record, and write elsewhere. Unguarded, the runs run on that thread too, and
// the callback between them. parse_injections shares nothing.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <vector>

#include "sewerplan/campaign/record.h"
#include "sewerplan/campaign/run.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/core/stop_condition.h"

namespace sewerplan::campaign {

struct Progress {
  std::size_t done = 0;
  std::size_t total = 0;
  std::size_t failed = 0;  // crashes and hangs so far
  double elapsed_s = 0;
  const RunRecord* last = nullptr;  // the run just finished; valid during the call only
};

// For tests of the guard only: make a run's child crash (SIGSEGV) or hang.
enum class InjectedFault { kCrash, kHang };

struct CampaignOptions {
  std::size_t jobs = 1;
  double timeout_s = 60;  // per run; a child still running then is a hang
  bool guard = true;      // false: in this process, one run at a time (a crash takes it down)
  std::optional<std::size_t> only;  // run just this index (it need not be in the shard)
  // Each finished run (after a stop too), on the caller's thread (see above).
  std::function<void(const Progress&)> progress;
  std::map<std::size_t, InjectedFault> inject;
  // When to give up (StopCondition::with_cancel, after_seconds): checked before each run and,
  // guarded, while a child runs (it is killed). Unguarded, a run in progress finishes first.
  StopCondition stop;
};

// What each run of `spec` is set to: its rates, seed, limits, and the risk settings (a `risk` of
// "expected" adds the risk-aware execution with domain::kDefaultRiskCosts).
RunSettings run_settings(const CampaignSpec& spec);

// The worker threads run_campaign runs `spec` with: options.jobs, at most one a run (of the
// shard, or options.only), at least one; unguarded, one.
std::size_t campaign_jobs(const CampaignSpec& spec, const CampaignOptions& options);

// The runs of `spec`'s shard (or options.only), in index order; after options.stop fired, only
// those that finished (fewer than the shard holds).
std::vector<RunRecord> run_campaign(const SewerMap& map, const Mission& mission,
                                    const CampaignSpec& spec, const CampaignOptions& options);

// Parses SEWERPLAN_CAMPAIGN_INJECT ("crash:3,hang:5"), the test hook behind
// CampaignOptions::inject; empty or unset: none.
Result<std::map<std::size_t, InjectedFault>> parse_injections(std::string_view text);

}  // namespace sewerplan::campaign
