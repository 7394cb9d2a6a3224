// SPDX-License-Identifier: MIT
// Merging the directories that shards of one campaign wrote (`campaign --shard i/n --out DIR`).
//
// Each directory holds campaign.json and runs.jsonl (record.h). The merge checks that they belong
// to one campaign (same map and mission fingerprints, seed, runs, fault rates, push setting, shard
// count), that no shard comes twice and none is missing, that every line is in its shard, and that
// every run appears exactly once; then it returns the whole campaign's records in run order.
//
//   Result<MergedCampaign> all = merge_shards({"out/shard-0", "out/shard-1"});
//   Summary s = summarize(all->spec, all->records);
//
// Thread safety: The functions share nothing but the file system: call them from any number
// of threads, but not on the same directory while one of them writes it.
#pragma once

#include <filesystem>
#include <vector>

#include "sewerplan/campaign/record.h"
#include "sewerplan/core/result.h"

namespace sewerplan::campaign {

struct MergedCampaign {
  CampaignSpec spec;  // shard 0/1
  std::vector<RunRecord> records;
};

// Reads one directory: its spec and its records (in file order). Errors name file and line.
Result<MergedCampaign> read_campaign_dir(const std::filesystem::path& dir);

Result<MergedCampaign> merge_shards(const std::vector<std::filesystem::path>& dirs);

// Writes campaign.json, runs.jsonl, summary.json, summary.md and summary.svg into `dir` (created if
// needed).
Result<void> write_campaign_dir(const std::filesystem::path& dir, const CampaignSpec& spec,
                                const std::vector<RunRecord>& records);

}  // namespace sewerplan::campaign
