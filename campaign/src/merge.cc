// SPDX-License-Identifier: MIT
// Campaign directories: writing them and merging shards (merge.h).
#include "sewerplan/campaign/merge.h"

#include <algorithm>
#include <sstream>

#include "sewerplan/campaign/summary.h"
#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/text_file.h"

namespace sewerplan::campaign {
namespace {}  // namespace

Result<MergedCampaign> read_campaign_dir(const std::filesystem::path& dir) {
  const std::filesystem::path spec_path = dir / "campaign.json";
  Result<std::string> spec_text = read_text_file(spec_path);
  if (!spec_text.has_value()) return spec_text.error();
  Result<CampaignSpec> spec = parse_campaign_json(*spec_text, spec_path.string());
  if (!spec.has_value()) return spec.error();
  const std::filesystem::path runs_path = dir / "runs.jsonl";
  Result<std::string> runs_text = read_text_file(runs_path);
  if (!runs_text.has_value()) return runs_text.error();
  MergedCampaign out{*spec, {}};
  std::istringstream lines(*runs_text);
  std::string line;
  JsonLineParser parser;  // one for every line: it keeps its buffers
  for (std::size_t n = 1; std::getline(lines, line); ++n) {
    if (line.empty()) continue;
    Result<RunRecord> r = parse_run_line(line, runs_path.string(), n, parser);
    if (!r.has_value()) return r.error();
    if (r->index >= spec->runs || !spec->in_shard(r->index)) {
      return Error{ErrorCode::kInvalidArgument,
                   runs_path.string() + ":" + std::to_string(n) + ": run " +
                       std::to_string(r->index) + " does not belong to shard " +
                       std::to_string(spec->shard_index) + "/" + std::to_string(spec->shard_count) +
                       " of " + std::to_string(spec->runs) + " runs"};
    }
    out.records.push_back(std::move(*r));
  }
  return out;
}

Result<MergedCampaign> merge_shards(const std::vector<std::filesystem::path>& dirs) {
  if (dirs.empty()) return Error{ErrorCode::kInvalidArgument, "merge: no directories"};
  std::vector<MergedCampaign> parts;
  for (const auto& dir : dirs) {
    Result<MergedCampaign> part = read_campaign_dir(dir);
    if (!part.has_value()) return part.error();
    parts.push_back(std::move(*part));
  }
  const CampaignSpec& first = parts.front().spec;
  std::vector<std::string> seen(first.shard_count);
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const CampaignSpec& s = parts[k].spec;
    const std::string name = dirs[k].string();
    if (!s.same_campaign(first)) {
      std::string what;
      if (s.map_fingerprint != first.map_fingerprint)
        what = "the map differs";
      else if (s.mission_fingerprint != first.mission_fingerprint)
        what = "the mission differs (or its motion table)";
      else if (s.seed != first.seed)
        what = "the seed differs";
      else if (s.runs != first.runs)
        what = "the number of runs differs";
      else if (s.shard_count != first.shard_count)
        what = "the number of shards differs";
      else
        what = "the fault rates or the push setting differ";
      return Error{ErrorCode::kInvalidArgument, "merge: " + name + " is not from the campaign of " +
                                                    dirs.front().string() + ": " + what};
    }
    if (!seen[s.shard_index].empty()) {
      return Error{ErrorCode::kInvalidArgument, "merge: shard " + std::to_string(s.shard_index) +
                                                    "/" + std::to_string(s.shard_count) +
                                                    " given twice: " + seen[s.shard_index] +
                                                    " and " + name};
    }
    seen[s.shard_index] = name;
  }
  std::string missing;
  for (std::size_t i = 0; i < seen.size(); ++i) {
    if (seen[i].empty()) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
  }
  if (!missing.empty()) {
    return Error{ErrorCode::kInvalidArgument, "merge: shard(s) " + missing + " of " +
                                                  std::to_string(first.shard_count) + " missing"};
  }
  MergedCampaign merged{first, {}};
  merged.spec.shard_index = 0;
  merged.spec.shard_count = 1;
  std::vector<bool> have(first.runs, false);
  for (auto& part : parts) {
    for (auto& r : part.records) {
      if (have[r.index]) {
        return Error{ErrorCode::kInvalidArgument,
                     "merge: run " + std::to_string(r.index) + " appears twice"};
      }
      have[r.index] = true;
      merged.records.push_back(std::move(r));
    }
  }
  std::string absent;
  std::size_t absent_count = 0;
  for (std::size_t i = 0; i < have.size(); ++i) {
    if (have[i]) continue;
    if (++absent_count <= 10) absent += (absent.empty() ? "" : ", ") + std::to_string(i);
  }
  if (absent_count > 0) {
    return Error{ErrorCode::kInvalidArgument,
                 "merge: " + std::to_string(absent_count) + " run(s) missing: " + absent +
                     (absent_count > 10 ? ", ..." : "") + " (an interrupted shard?)"};
  }
  std::sort(merged.records.begin(), merged.records.end(),
            [](const RunRecord& a, const RunRecord& b) { return a.index < b.index; });
  return merged;
}

Result<void> write_campaign_dir(const std::filesystem::path& dir, const CampaignSpec& spec,
                                const std::vector<RunRecord>& records) {
  if (Result<void> made = create_output_directory(dir); !made.has_value()) return made;
  if (auto r = write_text_file(dir / "campaign.json", campaign_json(spec)); !r.has_value())
    return r;
  std::string lines;
  for (const RunRecord& r : records) lines += run_json_line(r) + "\n";
  if (auto r = write_text_file(dir / "runs.jsonl", lines); !r.has_value()) return r;
  const Summary summary = summarize(spec, records);
  std::ostringstream json;
  std::ostringstream md;
  std::ostringstream svg;
  write_summary_json(summary, json);
  write_summary_markdown(summary, md);
  write_summary_svg(summary, svg);
  if (auto r = write_text_file(dir / "summary.json", json.str()); !r.has_value()) return r;
  if (auto r = write_text_file(dir / "summary.md", md.str()); !r.has_value()) return r;
  return write_text_file(dir / "summary.svg", svg.str());
}

}  // namespace sewerplan::campaign
