// SPDX-License-Identifier: MIT
// Small hand-made maps and missions for domain tests, drawn by manhole positions.
//
// Each pipe is straight between its manholes: its length is their distance unless given, and each
// slot's azimuth points at the pipe's other end, so turns follow from the drawing. A manhole's
// slots are in the order its pipes were added. All inverts are at 0 unless set.
//
//   SewerMap map = SmallMap()
//                      .manhole("M1", 0, 0, /*exit=*/true)
//                      .manhole("M2", 10, 0)
//                      .pipe("P1", "M1", "M2")
//                      .build();
//   Mission mission = small_mission(map, "M1");
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sewerplan/core/map_builder.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::testing {

class SmallMap {
 public:
  SmallMap& manhole(std::string name, double x_m, double y_m, bool exit = false);
  // `from` or `to` empty: a blind end.
  SmallMap& pipe(std::string name, std::string from, std::string to, double diameter_m = 0.5,
                 std::optional<double> length_m = std::nullopt);
  // The invert height of `pipe`'s end in `manhole`.
  SmallMap& invert(const std::string& manhole, const std::string& pipe, double z_m);
  SmallMap& point(std::string name, std::string pipe, double offset_m);
  // The map; a test failure (and an empty map) if it does not validate.
  SewerMap build() const;

 private:
  std::vector<ManholeRecord> manholes_;
  std::vector<PipeRecord> pipes_;
  std::vector<PointRecord> points_;
};

// A mission with the makro-1.1 profile starting at `start` (a manhole's or a pipe's name, a pipe
// meaning its middle), no tasks, the map's exits, no battery reserve.
Mission small_mission(const SewerMap& map, const std::string& start);

// Adds a task at a manhole, a whole pipe, or a pipe at an offset; returns its ID.
TaskId add_task(Mission& mission, const SewerMap& map, std::string name, TaskKind kind,
                const std::string& where, std::optional<double> offset_m = std::nullopt,
                bool final = false);

}  // namespace sewerplan::testing
