// SPDX-License-Identifier: MIT
// libFuzzer target: the readers `sewerplan campaign merge` uses (campaign/record.h): a runs.jsonl
// line and campaign.json. What a line reads as must write back to the same line.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "sewerplan/campaign/record.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = sewerplan::fuzz::as_text(data, size);
  auto record = sewerplan::campaign::parse_run_line(text, "runs.jsonl", 1);
  if (record.has_value()) {
    const std::string line = sewerplan::campaign::run_json_line(*record);
    auto back = sewerplan::campaign::parse_run_line(line, "back.jsonl", 1);
    if (!back.has_value() || sewerplan::campaign::run_json_line(*back) != line) std::abort();
  }
  (void)sewerplan::campaign::parse_campaign_json(text, "campaign.json");
  return 0;
}
