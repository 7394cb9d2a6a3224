// SPDX-License-Identifier: MIT
// The checks of what the robot reports (replanner.h): check_failure and check_progress, kept apart
// from the Replanner's planning.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "sewerplan/domain/validator.h"
#include "sewerplan/executor/replanner.h"

namespace sewerplan::executor {

Result<void> check_failure(const Failure& failure, const SewerMap& map) {
  const auto invalid = [](std::string what) -> Result<void> {
    return Error{ErrorCode::kInvalidArgument, "invalid failure report: " + std::move(what)};
  };
  switch (failure.kind) {
    case Failure::Kind::kBlockage:
    case Failure::Kind::kDangerInPipe: {
      if (failure.pipe.index() >= map.pipe_count()) {
        return invalid("unknown pipe #" + std::to_string(failure.pipe.index()));
      }
      const Pipe& pipe = map.pipe(failure.pipe);
      if (!std::isfinite(failure.offset_m) || failure.offset_m < 0 ||
          failure.offset_m > pipe.length_m) {
        std::ostringstream out;
        out << "offset " << failure.offset_m << " m is outside pipe " << pipe.name << " (0 to "
            << pipe.length_m << " m)";
        return invalid(out.str());
      }
      return {};
    }
    case Failure::Kind::kDangerousPassage: {
      if (failure.manhole.index() >= map.manhole_count()) {
        return invalid("unknown manhole #" + std::to_string(failure.manhole.index()));
      }
      const std::size_t slots = map.slots(failure.manhole).size();
      const std::string& name = map.manhole(failure.manhole).name;
      if (failure.from.index() >= slots || failure.to.index() >= slots) {
        return invalid("manhole " + name + " has " + std::to_string(slots) + " slots, not slot " +
                       std::to_string(to_paper_number(failure.from.index() >= slots ? failure.from
                                                                                    : failure.to)));
      }
      if (failure.from == failure.to) {
        return invalid("a passage of manhole " + name + " from slot " +
                       std::to_string(to_paper_number(failure.from)) + " to itself");
      }
      return {};
    }
    case Failure::Kind::kStuck:
      return {};
  }
  return invalid("unknown kind");
}

Result<void> check_progress(const domain::MissionProgress& progress, std::uint8_t heading_end,
                            const SewerMap& map, const Mission& mission) {
  const auto invalid = [](std::string what) -> Result<void> {
    return Error{ErrorCode::kInvalidArgument, "invalid progress report: " + std::move(what)};
  };
  if (progress.done.size() != mission.tasks.size()) {
    return invalid(std::to_string(progress.done.size()) + " done flags for " +
                   std::to_string(mission.tasks.size()) + " tasks");
  }
  if (!std::isfinite(progress.energy_used_wh) || progress.energy_used_wh < 0) {
    return invalid("energy used " + std::to_string(progress.energy_used_wh) + " Wh");
  }
  if (heading_end > 1) return invalid("heading end " + std::to_string(heading_end));
  const auto known_manhole = [&](ManholeId m) { return m.index() < map.manhole_count(); };
  if (const auto* in = std::get_if<domain::InManhole>(&progress.position)) {
    if (!known_manhole(in->manhole)) {
      return invalid("unknown manhole #" + std::to_string(in->manhole.index()));
    }
  } else if (const auto* at = std::get_if<domain::AtSlot>(&progress.position)) {
    if (!known_manhole(at->manhole)) {
      return invalid("unknown manhole #" + std::to_string(at->manhole.index()));
    }
    if (at->slot.index() >= map.slots(at->manhole).size()) {
      return invalid("manhole " + map.manhole(at->manhole).name + " has no slot " +
                     std::to_string(to_paper_number(at->slot)));
    }
  } else {
    const auto& p = std::get<domain::InPipe>(progress.position);
    if (p.pipe.index() >= map.pipe_count()) {
      return invalid("unknown pipe #" + std::to_string(p.pipe.index()));
    }
    const Pipe& pipe = map.pipe(p.pipe);
    if (!std::isfinite(p.offset_m) || p.offset_m < 0 || p.offset_m > pipe.length_m) {
      std::ostringstream out;
      out << "offset " << p.offset_m << " m is outside pipe " << pipe.name << " (0 to "
          << pipe.length_m << " m)";
      return invalid(out.str());
    }
  }
  // The final task is done only where it ends the mission: the validator's goal must hold here.
  if (const auto final_task = mission.final_task_id();
      final_task && progress.done[final_task->index()]) {
    domain::MissionProgress all_done = progress;
    std::fill(all_done.done.begin(), all_done.done.end(), true);
    const auto report = domain::validate_plan({}, map, mission, all_done);
    if (!report.valid) {
      return invalid("the final task '" + mission.task(*final_task).name +
                     "' is done, but the robot is " + domain::describe(progress.position, map));
    }
  }
  return {};
}

}  // namespace sewerplan::executor
