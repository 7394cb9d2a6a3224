// SPDX-License-Identifier: MIT
// Mission: what an operator asks of the robot on one map.
//
// The paper's mission (Adria, Streich and Hertzberg 2004, sections 3.2, 4.3 and 6) names where the
// robot is put into the sewer, the tasks to do and where it is recovered. Three kinds of task: go
// to a place, inspect a pipe (an area is a set of pipes, one task each), and take a water sample.
// The end point of the paper's mission is a go-to task marked `final`: done last, and the mission
// ends there; without a final task the mission ends at one of its exits (manholes where the robot
// can be recovered; by default, those marked exit in the map). The robot profile, a battery
// reserve, and pipes or manhole passages known to be closed complete it.
//
// A Mission refers to its map by IDs, so it is read against that map (read_mission_json) and only
// valid with it. The JSON form is documented in docs/formats/mission-json.md.
//
//   Diagnostics diagnostics;
//   Result<Mission> mission = read_mission_json(text, "paper.json", map, diagnostics);
//   for (const Task& task : mission->tasks) std::cout << task.name << '\n';
//
// Thread safety: A Mission is a plain value: const access from several threads is safe (its motion
// table is immutable and shared); a mission being changed must not be read at the same time.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/passage_motion.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/sewer_map.h"

namespace simdjson::dom {
class element;  // JsonElement (json_fields.h), which this header does not pull in
}  // namespace simdjson::dom

namespace sewerplan {

// A place in a pipe: the whole pipe, a point offset_m from its ends[0], or a named point.
struct PipeSpot {
  PipeId pipe{0};
  std::optional<double> offset_m;
  std::optional<PointId> point;  // when given by an inspection point's name
  friend bool operator==(const PipeSpot&, const PipeSpot&) = default;
};

// Where the robot starts or a task is done: in a manhole, or in a pipe.
using Place = std::variant<ManholeId, PipeSpot>;

enum class TaskKind { kGoTo, kInspectPipe, kTakeWaterSample };

// A task's position in Mission::tasks.
using TaskId = StrongId<struct TaskTag>;

std::string_view to_string(TaskKind kind);

struct Task {
  std::string name;
  TaskKind kind = TaskKind::kGoTo;
  Place place = ManholeId{0};  // kInspectPipe: the whole pipe
  bool final = false;          // done last; the mission ends here
  friend bool operator==(const Task&, const Task&) = default;
};

// A passage through a manhole that must not be used, in either direction.
struct ClosedPassage {
  ManholeId manhole{0};
  SlotIndex from{0};
  SlotIndex to{0};
  friend bool operator==(const ClosedPassage&, const ClosedPassage&) = default;
};

// A place in a pipe that the robot cannot pass, such as an obstacle it met there: the robot may
// still enter the pipe from either end and drive up to it, but not across it.
struct Blockage {
  PipeId pipe{0};
  double offset_m = 0;  // from the pipe's ends[0]
  friend bool operator==(const Blockage&, const Blockage&) = default;
};

// A place in a pipe where the robot may be stopped, with a probability: an inspection finding the
// risk table (condition_risk.h) rates as a possible blockage. It closes nothing; risk-aware
// planning (domain/compile.h, RiskCosts) charges the expected cost of meeting it.
struct Hazard {
  PipeId pipe{0};
  double offset_m = 0;     // from the pipe's ends[0]
  double probability = 0;  // of being stopped there, 0..1
  std::string reason;      // "BBA roots", for reports
  friend bool operator==(const Hazard&, const Hazard&) = default;
};

struct Mission {
  std::string name;
  RobotProfile profile;
  Place start = ManholeId{0};
  std::vector<Task> tasks;
  std::vector<ManholeId> exits;
  // Share of the battery that must be left at the end of the mission, 0..1.
  double battery_reserve_fraction = 0.2;
  std::vector<PipeId> closed_pipes;
  std::vector<ClosedPassage> closed_passages;
  std::vector<Blockage> blockages;
  // Places that may stop the robot (not part of the mission's file: the CLI adds them from the
  // map's inspection findings with --risk expected).
  std::vector<Hazard> hazards;
  // Planned manhole passages (passage_motion.h), when the map has a motion table: they decide
  // which passages are allowed and what they cost, instead of the turn and step rules. Not part
  // of the mission's file; the CLI attaches the table kept beside the map. Shared, because it is
  // immutable and every copy of a mission (the executor's, each replan's) uses the same one.
  std::shared_ptr<const PassageMotionTable> passage_motion;
  friend bool operator==(const Mission&, const Mission&) = default;

  // The final task, if the mission has one.
  const Task* final_task() const;
  std::optional<TaskId> final_task_id() const;
  const Task& task(TaskId id) const;
  IdRange<TaskId> task_ids() const { return id_range<TaskId>(tasks.size()); }
};

inline constexpr std::string_view kMissionJsonFormat = "sewerplan-mission";
inline constexpr int kMissionJsonVersion = 1;

// Reads a mission and resolves its names against `map`. Unknown names, duplicate task names, more
// than one final task, a mission without any exit or final task, and an invalid profile are errors
// naming the JSON path.
Result<Mission> read_mission_json(std::string_view text, const std::string& file_name,
                                  const SewerMap& map, Diagnostics& diagnostics);
// The same, of a mission parsed already (json_fields.h) at JSON path `path` of `file_name`: a
// request's body that holds the mission among other members ("body:$.mission.tasks[2].at: ...").
Result<Mission> read_mission_value(const simdjson::dom::element& value, const std::string& path,
                                   const std::string& file_name, const SewerMap& map,
                                   Diagnostics& diagnostics);

void write_mission_json(const Mission& mission, const SewerMap& map, std::ostream& out);

// The first of the mission's blockages strictly between offsets a and b of `pipe` (either order),
// which a robot driving from a to b cannot pass. Runtime: O(blockages).
std::optional<Blockage> blockage_between(const Mission& mission, PipeId pipe, double a, double b);

// A place as people read it: "manhole M3", "pipe P6", "pipe P6 at 2.5 m", "point W1 (pipe P6)".
std::string describe(const Place& place, const SewerMap& map);

}  // namespace sewerplan

namespace sewerplan {

// Reads a mission file against `map`; an unreadable file is a kIo error naming it.
Result<Mission> read_mission(const std::filesystem::path& path, const SewerMap& map,
                             Diagnostics& diagnostics);

}  // namespace sewerplan
