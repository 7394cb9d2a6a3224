// SPDX-License-Identifier: MIT
// sewerplan campaign --map MAP --mission MISSION [--runs N] [--seed S] [--fault-rates R]
//                    [--jobs J] [--shard I/N] [--only RUN] [--out DIR] [--timeout S] [-q]
//                    [--condition FILE] [--risk MODE] [--risk-table FILE] [--faults-from-condition]
// sewerplan campaign merge DIR... -o OUT
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <thread>

#include <CLI/CLI.hpp>

#include "sewerplan/campaign/campaign.h"
#include "sewerplan/campaign/merge.h"
#include "sewerplan/campaign/summary.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/map_json.h"
#include "sewerplan/core/output_file.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/executor/event_json.h"

#include "command.h"
#include "condition_options.h"
#include "json_output.h"
#include "map_input.h"
#include "motion_options.h"
#include <unistd.h>

namespace sewerplan::cli {
namespace {

constexpr std::size_t kMaxRuns = 10'000'000;
constexpr std::size_t kMaxJobs = 1024;

struct CampaignCliOptions {
  std::string map;
  std::string gis_fields;  // --gis-fields
  std::string mission;
  std::size_t runs = 100;
  std::uint64_t seed = 1;
  std::string fault_rates;
  std::string world_errors = "none";
  std::size_t jobs = 1;
  std::string shard = "0/1";
  std::optional<std::size_t> only;
  std::string out;
  double timeout_s = 60;
  bool allow_push = false;
  double planner_time_limit_s = 0;
  bool quiet = false;
  bool no_guard = false;
  std::string faults_out;
  std::string log_out;  // --log-out: with --only, ours' event log
  MotionOptions motion;
  std::string condition;
  RiskOptions risk;
  bool faults_from_condition = false;
  bool json = false;
  // merge
  std::vector<std::string> merge_dirs;
  std::string merge_out;
};

std::string clock_text(double seconds) {
  const auto s = static_cast<long long>(std::max(0.0, seconds) + 0.5);
  std::ostringstream out;
  out << s / 60 << ':' << std::setw(2) << std::setfill('0') << s % 60;
  return out.str();
}

// A progress bar on a terminal, a line every 10 % (and at most every 10 s) otherwise.
class ProgressPrinter {
 public:
  explicit ProgressPrinter(std::ostream& err) : err_(err), tty_(::isatty(STDERR_FILENO) != 0) {}

  void operator()(const campaign::Progress& p) {
    const double eta = p.done == 0 ? 0
                                   : p.elapsed_s / static_cast<double>(p.done) *
                                         static_cast<double>(p.total - p.done);
    std::ostringstream line;
    line << p.done << '/' << p.total << " runs, " << p.failed << " crashed or hung, "
         << clock_text(p.elapsed_s) << " elapsed, " << clock_text(eta) << " left";
    if (tty_) {
      // At most ten redraws a second.
      if (p.done != p.total && p.elapsed_s - last_s_ < 0.1) return;
      last_s_ = p.elapsed_s;
      constexpr std::size_t kWidth = 30;
      const std::size_t filled = p.total == 0 ? kWidth : kWidth * p.done / p.total;
      err_ << "\r[" << std::string(filled, '#') << std::string(kWidth - filled, '.') << "] "
           << line.str() << (p.done == p.total ? "\n" : "") << std::flush;
      return;
    }
    const std::size_t decile = p.total == 0 ? 10 : 10 * p.done / p.total;
    if (decile > last_decile_ || p.elapsed_s - last_s_ >= 10 || p.done == p.total) {
      last_decile_ = decile;
      last_s_ = p.elapsed_s;
      err_ << "campaign: " << line.str() << '\n';
    }
  }

 private:
  std::ostream& err_;
  bool tty_;
  std::size_t last_decile_ = 0;
  double last_s_ = 0;
};

int merge(const CampaignCliOptions& o, Context& c) {
  std::vector<std::filesystem::path> dirs(o.merge_dirs.begin(), o.merge_dirs.end());
  Result<campaign::MergedCampaign> merged = campaign::merge_shards(dirs);
  if (!merged.has_value()) {
    Error error = merged.error();
    // Shards that are not one campaign are invalid input (1), not a usage error.
    if (error.code == ErrorCode::kInvalidArgument) error.code = ErrorCode::kInvalidMission;
    return fail(c, o.json, error);
  }
  if (auto w = campaign::write_campaign_dir(o.merge_out, merged->spec, merged->records);
      !w.has_value()) {
    return fail(c, o.json, Error{ErrorCode::kIo, w.error().message});
  }
  const campaign::Summary s = campaign::summarize(merged->spec, merged->records);
  if (o.json) {
    campaign::write_summary_json(s, c.out);
  } else if (!o.quiet) {
    campaign::write_summary_markdown(s, c.out);
    c.out << "\nwrote " << o.merge_out
          << "/{campaign.json,runs.jsonl,summary.json,summary.md,summary.svg}\n";
  }
  return s.clean() ? kExitOk : kExitCampaignNotClean;
}

int run(const CampaignCliOptions& o, Context& c) {
  if (o.map.empty() || o.mission.empty()) {
    return usage_error(c, o.json,
                       "campaign: --map and --mission are required (or: campaign merge DIR... -o "
                       "OUT)");
  }
  Result<campaign::FaultRates> rates = campaign::parse_fault_rates(o.fault_rates);
  if (Result<hal::WorldErrorProfile> world = hal::parse_world_errors(o.world_errors);
      !world.has_value()) {
    return usage_error(c, o.json, world.error().message);
  }
  Result<std::pair<std::size_t, std::size_t>> shard = campaign::parse_shard(o.shard);
  const char* inject_env = std::getenv("SEWERPLAN_CAMPAIGN_INJECT");
  auto inject = campaign::parse_injections(inject_env != nullptr ? inject_env : "");
  for (const Error* e :
       {rates.has_value() ? nullptr : &rates.error(), shard.has_value() ? nullptr : &shard.error(),
        inject.has_value() ? nullptr : &inject.error()}) {
    if (e != nullptr) return usage_error(c, o.json, e->message);
  }
  if (std::string why = o.risk.strand_risk_error(); !why.empty()) {
    return usage_error(c, o.json, "campaign: " + why);
  }
  if (o.runs == 0 || (o.only && *o.only >= o.runs)) {
    return usage_error(c, o.json, "campaign: --runs must be at least 1 and --only below it");
  }
  // Each run keeps a record in memory until the summary: a bound well above any real campaign
  // (35,000 runs were the largest tried) and well below what exhausts a machine.
  if (o.runs > kMaxRuns) {
    return usage_error(c, o.json,
                       "campaign: --runs " + std::to_string(o.runs) + " is more than " +
                           std::to_string(kMaxRuns) + "; run a bigger campaign as shards");
  }
  if (o.jobs > kMaxJobs) {
    return usage_error(c, o.json,
                       "campaign: --jobs " + std::to_string(o.jobs) + " is more than " +
                           std::to_string(kMaxJobs) + " threads");
  }
  Result<std::string> mission_text = read_text_file(o.mission);
  Diagnostics diagnostics;
  Result<std::string> condition_text =
      o.condition.empty() ? Result<std::string>(std::string()) : read_text_file(o.condition);
  Result<SewerMap> map =
      !condition_text.has_value()
          ? Result<SewerMap>(condition_text.error())
          : read_map_with_condition({o.map, o.gis_fields}, o.condition, diagnostics);
  // The map as read, in our JSON: a GIS source has no one file to hash (a Shapefile directory),
  // and its field mapping (--gis-fields or a sidecar file) changes the network, so shards read
  // through different mappings must not merge.
  std::string map_fingerprint;
  if (map.has_value()) {
    std::ostringstream map_json;
    write_map_json(*map, map_json);
    map_fingerprint = campaign::fingerprint(map_json.str());
  }
  Result<Mission> mission = !map.has_value() ? Result<Mission>(map.error())
                            : !mission_text.has_value()
                                ? Result<Mission>(mission_text.error())
                                : read_mission(o.mission, *map, diagnostics);
  if (mission.has_value()) {
    // Every policy plans with what the findings close; the hazards are there for the risk-aware
    // execution and for the obstacles drawn from them (risk-blind planning does not weigh them).
    RiskOptions risk = o.risk;
    if (o.faults_from_condition && risk.risk_mode() != RiskMode::kAvoid) risk.mode = "expected";
    if (Result<void> r = apply_risk(risk, *map, *mission, diagnostics, c.err); !r.has_value()) {
      mission = r.error();
    }
  }
  if (!mission.has_value()) return fail(c, o.json, mission.error(), diagnostics);
  print_diagnostics(diagnostics, c.err);
  if (o.faults_from_condition && mission->hazards.empty()) {
    return usage_error(c, o.json,
                       "campaign: --faults-from-condition: the condition data has no possible "
                       "blockage (give --condition FILE, or a map with findings; --risk avoid "
                       "closes them all)");
  }
  Result<std::string> motion = attach_motion_table(o.motion, o.map, *map, *mission, c.err);
  if (!motion.has_value()) return fail(c, o.json, motion.error());
  const std::string motion_path = *motion;
  campaign::CampaignSpec spec;
  spec.map_name = o.map;
  spec.mission_name = o.mission;
  spec.map_fingerprint = map_fingerprint;
  // A planned-motion table changes every plan, so it belongs to the mission's identity: shards
  // made with and without it (or with different tables) must not merge.
  Result<std::string> motion_text =
      motion_path.empty() ? Result<std::string>(std::string()) : read_text_file(motion_path);
  spec.mission_fingerprint = campaign::fingerprint(
      motion_path.empty()
          ? *mission_text
          : *mission_text + "\nmotion:" + (motion_text.has_value() ? *motion_text : std::string()));
  spec.seed = o.seed;
  spec.runs = o.runs;
  spec.rates = *rates;
  spec.push_allowed = o.allow_push;
  spec.planner_time_limit_s = o.planner_time_limit_s;
  spec.max_strand_risk = o.risk.max_strand_risk;
  spec.shard_index = shard->first;
  spec.shard_count = shard->second;
  if (!o.condition.empty()) {
    spec.condition_name = o.condition;
    spec.condition_fingerprint = campaign::fingerprint(*condition_text);
  }
  spec.risk = o.risk.mode;
  spec.faults_from_condition = o.faults_from_condition;
  spec.world_errors = o.world_errors;
  if (!o.risk.table.empty()) {
    // A risk table changes what the findings mean: part of the mission's identity.
    Result<std::string> table = read_text_file(o.risk.table);
    spec.mission_fingerprint = campaign::fingerprint(
        spec.mission_fingerprint + "\nrisk-table:" + (table.has_value() ? *table : ""));
  }

  campaign::CampaignOptions options;
  options.jobs = std::max<std::size_t>(1, o.jobs);
  options.timeout_s = o.timeout_s;
  options.guard = !o.no_guard;
  options.only = o.only;
  options.inject = *inject;
  ProgressPrinter printer(c.err);
  const bool print_progress = !o.quiet && !o.only;
  // Issue 30: the runs are written as they finish (appended and flushed per run), beside the
  // campaign's spec, so that a crash or a halt mid-campaign keeps the runs so far (merge names the
  // missing ones). The first write that fails stops the campaign: exit 3, naming the file.
  std::optional<LogFile> runs_log;
  std::atomic<bool> write_failed{false};
  if (!o.out.empty() && !o.only) {
    const std::filesystem::path dir = o.out;
    Result<void> made = create_output_directory(dir);
    if (made.has_value())
      made = write_text_file(dir / "campaign.json", campaign::campaign_json(spec));
    if (!made.has_value()) return fail(c, o.json, made.error());
    Result<LogFile> log = LogFile::open(dir / "runs.jsonl");
    if (!log.has_value()) return fail(c, o.json, log.error());
    runs_log = std::move(*log);
    options.stop.with_cancel(write_failed);
  }
  if (print_progress || runs_log) {
    options.progress = [&](const campaign::Progress& p) {
      if (runs_log && p.last != nullptr && !write_failed.load() &&
          !runs_log->append(campaign::run_json_line(*p.last) + "\n")) {
        write_failed.store(true);
      }
      if (print_progress) printer(p);
    };
  }
  const std::vector<campaign::RunRecord> records =
      campaign::run_campaign(*map, *mission, spec, options);
  if (runs_log) {
    if (Result<void> closed = runs_log->close(); !closed.has_value()) {
      return fail(c, o.json,
                  Error{ErrorCode::kIo, closed.error().message + "; the campaign stopped after " +
                                            std::to_string(records.size()) + " runs"});
    }
  }

  if (o.only && !o.faults_out.empty()) {
    const campaign::RunSettings settings = campaign::run_settings(spec);
    Result<hal::FaultScenario> faults = campaign::run_faults(*map, *mission, settings, *o.only);
    if (!faults.has_value()) return fail(c, o.json, faults.error());
    std::ostringstream text;
    hal::write_faults_json(*faults, *map, text);
    if (Result<void> w = write_text_file(o.faults_out, text.str()); !w.has_value()) {
      return fail(c, o.json, w.error());
    }
  }
  if (o.only && !o.log_out.empty()) {
    // The run again, as run_one carried it out, with every event written as simulate --log
    // writes it: what a missed exit or a beacon was, event by event.
    std::ostringstream text;
    campaign::ExecutionObservers observers;
    observers.on_event = [&](const executor::Event& e) {
      text << executor::to_json_line(e) << '\n';
    };
    const Result<campaign::Execution> replayed = campaign::replay_execution(
        *map, *mission, campaign::run_settings(spec), *o.only, campaign::Policy::kOurs, observers);
    if (!replayed.has_value()) return fail(c, o.json, replayed.error());
    if (Result<void> w = write_text_file(o.log_out, text.str()); !w.has_value()) {
      return fail(c, o.json, w.error());
    }
  }
  if (o.only) {
    const campaign::RunRecord& r = records.front();
    c.out << campaign::run_json_line(r) << '\n';
    if (r.status != campaign::RunRecord::Status::kOk) {
      c.err << "run " << r.index << " (seed " << r.seed << "): " << campaign::to_string(r.status)
            << ", " << r.detail << '\n';
      return kExitCampaignNotClean;
    }
    return kExitOk;
  }
  if (!o.out.empty()) {
    if (auto w = campaign::write_campaign_dir(o.out, spec, records); !w.has_value()) {
      return fail(c, o.json, Error{ErrorCode::kIo, w.error().message});
    }
  }
  const campaign::Summary s = campaign::summarize(spec, records);
  if (o.json) {
    campaign::write_summary_json(s, c.out);
  } else if (!o.quiet) {
    campaign::write_summary_markdown(s, c.out);
    if (!o.out.empty()) {
      c.out << "\nwrote " << o.out
            << "/{campaign.json,runs.jsonl,summary.json,summary.md,summary.svg}\n";
    }
  }
  return s.clean() ? kExitOk : kExitCampaignNotClean;
}

}  // namespace

void add_campaign_command(CLI::App& app, Context& context) {
  auto options = std::make_shared<CampaignCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "campaign",
      "Run many seeded simulated missions with random faults, against an oracle and the "
      "paper-era baseline (docs/campaign.md)");
  cmd->add_option("--map", options->map, "Map file");
  add_gis_fields_option(*cmd, options->gis_fields);
  cmd->add_option("--mission", options->mission, "Mission file (.json)");
  cmd->add_option("--runs", options->runs, "Number of runs")->capture_default_str();
  cmd->add_option("--seed", options->seed, "Campaign seed")->capture_default_str();
  cmd->add_option("--fault-rates", options->fault_rates,
                  "[PROFILE,]NAME=VALUE,...: a profile (default, realistic, moderate, harsh), "
                  "then obstacles=20 (per km of pipe), danger=5 (per km), passages=0.01 "
                  "(share), malfunctions=0.5 (per hour), permanent=0.1, transient=0.5 (shares)");
  cmd->add_option("--world-errors", options->world_errors,
                  "NAME|SPEC: the true world each robot drives (none, realistic; or "
                  "[NAME,]key=value,...: docs/simulation.md)")
      ->capture_default_str();
  cmd->add_option("-j,--jobs", options->jobs, "Runs in parallel")->capture_default_str();
  cmd->add_option("--shard", options->shard, "I/N: only the runs with index % N == I")
      ->capture_default_str();
  cmd->add_option("--only", options->only, "Run just this run (from 0) and print its JSON line");
  cmd->add_option("-o,--out", options->out,
                  "Directory for campaign.json, runs.jsonl and summary.{json,md,svg}");
  cmd->add_option("--timeout", options->timeout_s, "Seconds before a run counts as hung")
      ->capture_default_str();
  cmd->add_flag("--allow-push", options->allow_push, "Allow recovery phase 3, pushing");
  cmd->add_option("--planner-time-limit", options->planner_time_limit_s,
                  "Seconds: the deadline of each replan of ours and the baseline (0: none)")
      ->check(CLI::Range(0.0, 86400.0))
      ->capture_default_str();
  cmd->add_flag("--no-guard", options->no_guard,
                "Run in this process, not in guarded children (for a debugger)");
  cmd->add_option("--faults-out", options->faults_out,
                  "With --only: write the run's hidden faults (for simulate --faults, render)");
  cmd->add_option("--log-out", options->log_out,
                  "With --only: write ours' event log of the run (JSON lines, as simulate --log)");
  cmd->add_flag("-q,--quiet", options->quiet, "No progress and no summary on the terminal");
  cmd->add_flag("--json", options->json,
                "Print the summary as JSON (summary.json; with --only, the run's JSON line)");
  add_motion_options(*cmd, options->motion);
  add_condition_option(*cmd, options->condition);
  add_risk_options(*cmd, options->risk);
  cmd->add_flag("--faults-from-condition", options->faults_from_condition,
                "Draw hidden obstacles from the condition data too: each possible blockage, with "
                "its probability, at its offset (docs/campaign.md)");
  CLI::App* merge_cmd =
      cmd->add_subcommand("merge", "Merge the output directories of a sharded campaign");
  merge_cmd->add_option("dirs", options->merge_dirs, "Shard directories")->required();
  merge_cmd->add_option("-o,--out", options->merge_out, "Output directory")->required();
  merge_cmd->add_flag("-q,--quiet", options->quiet, "No summary on the terminal");
  merge_cmd->add_flag("--json", options->json, "Print the summary as JSON (summary.json)");
  cmd->require_subcommand(0, 1);
  merge_cmd->callback([options, &context] { context.exit_code = merge(*options, context); });
  cmd->callback([options, merge_cmd, &context] {
    if (merge_cmd->parsed()) return;
    context.exit_code = run(*options, context);
  });
}

}  // namespace sewerplan::cli
