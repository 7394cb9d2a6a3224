// SPDX-License-Identifier: MIT
// Internal helpers shared by the plan text, the validator and the plan JSON: names of objects that
// tolerate IDs outside the map or the mission, the tasks an action may do, number formatting.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::domain::detail {

bool in_map(const SewerMap& map, ManholeId id);
bool in_map(const SewerMap& map, PipeId id);
bool in_mission(const Mission& mission, TaskId id);

// The object's name, or "#N" for an ID the map or mission does not have.
std::string name_of(const SewerMap& map, ManholeId id);
std::string name_of(const SewerMap& map, PipeId id);
std::string name_of(const Mission& mission, TaskId id);

// "task 'sample' (take_water_sample)"
std::string describe_task(const Mission& mission, TaskId id);

// The pipe a task is in (samples, inspections, go-to a pipe spot), or the manhole (go-to a
// manhole).
std::optional<PipeId> task_pipe(const Task& task);
std::optional<ManholeId> task_manhole(const Task& task);

// The offset a task is done at: its spot's offset (or point's); empty for a whole pipe.
std::optional<double> task_offset_m(const Task& task, const SewerMap& map);

// The tasks of `kind` in `pipe`, or the go-to tasks at manhole `m`, in mission order.
std::vector<TaskId> tasks_in_pipe(const Mission& mission, TaskKind kind, PipeId pipe);
std::vector<TaskId> go_to_tasks_at(const Mission& mission, ManholeId m);

// `v` with `decimals` digits after the point: fixed(0.8, 2) == "0.80".
std::string fixed(double v, int decimals);
// The shortest text that reads back as `v`: 2.5 -> "2.5".
std::string shortest(double v);

// A manhole's type as the paper's action names write it: "TYPE_4", "TYPE_3_TYPE_B".
std::string paper_type(const Manhole& m);

char ascii_upper(char c);
std::string ascii_upper(std::string_view s);
bool equals_ignoring_case(std::string_view a, std::string_view b);

}  // namespace sewerplan::domain::detail
