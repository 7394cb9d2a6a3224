// SPDX-License-Identifier: MIT
// RunRecord and CampaignSpec: what a campaign writes to disk, and reads back to merge shards.
//
// A campaign directory holds campaign.json (the CampaignSpec: which map and mission, by name and
// fingerprint, the seed, the number of runs, the fault rates and the shard) and runs.jsonl, one
// RunRecord per line in run order. A record is a run's result, or how its guarded child failed:
// a crash (a signal, or an exit without a result) or a hang (killed at the time limit), with the
// seed that reproduces it. Everything in a line except its "measured" object is deterministic.
//
//   std::ofstream out(dir / "runs.jsonl");
//   for (const RunRecord& r : records) out << run_json_line(r) << '\n';
//   Result<RunRecord> back = parse_run_line(line, "runs.jsonl", 1);
//
// Thread safety: Plain values and pure functions: const access from several threads is safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "sewerplan/campaign/run.h"
#include "sewerplan/core/result.h"

namespace sewerplan {
class JsonLineParser;  // sewerplan/core/json_fields.h
}  // namespace sewerplan

namespace sewerplan::campaign {

struct RunRecord {
  enum class Status { kOk, kCrash, kHang };
  std::size_t index = 0;
  std::uint64_t seed = 0;
  Status status = Status::kOk;
  std::string detail;               // kCrash: "signal 11 (Segmentation fault)"; kHang: the limit
  std::optional<RunResult> result;  // kOk only
  double wall_s = 0;                // measured
  friend bool operator==(const RunRecord&, const RunRecord&) = default;
};

std::string_view to_string(RunRecord::Status status);

// One line of JSON (no line break): {"run":..,"seed":"..","status":"ok",...,"measured":{...}}.
std::string run_json_line(const RunRecord& record);
// Reads a line written by run_json_line; an error names file:line and the field. A reader of many
// lines passes one `parser` for all of them (it keeps its buffers between lines).
Result<RunRecord> parse_run_line(std::string_view line, const std::string& file_name,
                                 std::size_t line_number);
Result<RunRecord> parse_run_line(std::string_view line, const std::string& file_name,
                                 std::size_t line_number, JsonLineParser& parser);

inline constexpr std::string_view kCampaignJsonFormat = "sewerplan-campaign";
inline constexpr int kCampaignJsonVersion = 1;

struct CampaignSpec {
  std::string map_name;  // the files as given, for the commands printed to reproduce a run
  std::string mission_name;
  std::string map_fingerprint;  // FNV-1a 64 of the map as read, in native JSON, 16 hex digits
  std::string mission_fingerprint;
  std::uint64_t seed = 0;
  std::size_t runs = 0;
  FaultRates rates;
  bool push_allowed = false;
  double planner_time_limit_s = 0;  // RunSettings::planner_time_limit_s
  double max_strand_risk = 0;       // RunSettings::max_strand_risk
  // Condition data (--condition), as given and by fingerprint; what the findings mean (--risk:
  // "impassable", "avoid", "expected", "ignore"); RunSettings::faults_from_condition. Written
  // only when not the defaults, so campaigns without condition data read as before.
  std::string condition_name;
  std::string condition_fingerprint;
  std::string risk = "impassable";
  bool faults_from_condition = false;
  // --world-errors as given ("none", "realistic", "realistic,drift=0.05", ...); written only when
  // not "none", so campaigns without world errors read as before.
  std::string world_errors = "none";
  std::size_t shard_index = 0;  // this directory holds the runs with index % shard_count == index
  std::size_t shard_count = 1;
  friend bool operator==(const CampaignSpec&, const CampaignSpec&) = default;

  // Same campaign (all but the shard and the file names as given).
  bool same_campaign(const CampaignSpec& other) const;
  bool in_shard(std::size_t run) const { return run % shard_count == shard_index; }
};

std::string fingerprint(std::string_view bytes);

std::string campaign_json(const CampaignSpec& spec);
Result<CampaignSpec> parse_campaign_json(std::string_view text, const std::string& file_name);

// "--shard i/n" -> (i, n); an error unless 0 <= i < n.
Result<std::pair<std::size_t, std::size_t>> parse_shard(std::string_view text);

// The command that reruns one run alone: "sewerplan campaign --map .. --only K".
std::string reproduce_command(const CampaignSpec& spec, std::size_t run);

}  // namespace sewerplan::campaign
