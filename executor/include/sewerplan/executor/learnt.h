// SPDX-License-Identifier: MIT
// Learnt: what the robot found out about the sewer on its missions, owned by the Replanner.
//
// The operator's Mission says what to do; what the robot met that its recovery could not clear
// (blockages, danger spots in pipes, dangerous passages through manholes) is knowledge of the
// sewer, kept apart from it in a Learnt, which the Replanner adds to its view of the mission
// when it plans. Saved as JSON, it lets a second mission in the same sewer start from what the
// first learnt (CLI: `simulate --learnt FILE`; the format is in docs/executor.md).
//
//   Diagnostics d;
//   Result<Learnt> learnt = read_learnt("learnt.json", map, d);  // "learnt.json:$.danger[0].pipe:
//   ..." if (learnt.has_value()) (void)replanner.learn(*learnt);
//   ... after the mission:  write_text_file("learnt.json", learnt_json(replanner.learnt(), map));
//
// Thread safety: A Learnt is a plain value: safe to copy and to read from several threads, not
// to change while read. The free functions share nothing.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::executor {

inline constexpr std::string_view kLearntJsonFormat = "sewerplan-learnt";
inline constexpr int kLearntJsonVersion = 1;

struct Learnt {
  std::vector<Blockage> blockages;             // obstacles recovery could not clear
  std::vector<Blockage> danger_spots;          // spots in pipes the robot must not drive onto
  std::vector<ClosedPassage> closed_passages;  // dangerous passages, closed both ways
  bool empty() const {
    return blockages.empty() && danger_spots.empty() && closed_passages.empty();
  }
  friend bool operator==(const Learnt&, const Learnt&) = default;
};

// `mission` as the planner sees it with `learnt`: every blockage and danger spot a blockage,
// every dangerous passage closed.
Mission with_learnt(Mission mission, const Learnt& learnt);

// Reads the JSON format; every problem is a diagnostic at "file:$.path" naming the object
// (an unknown pipe or manhole, an offset outside the pipe, a slot the manhole does not have).
Result<Learnt> read_learnt_json(std::string_view text, const std::string& file_name,
                                const SewerMap& map, Diagnostics& diagnostics);
Result<Learnt> read_learnt(const std::filesystem::path& path, const SewerMap& map,
                           Diagnostics& diagnostics);
// The JSON text; read_learnt_json reads it back to an equal Learnt.
std::string learnt_json(const Learnt& learnt, const SewerMap& map);

}  // namespace sewerplan::executor
