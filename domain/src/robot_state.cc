// SPDX-License-Identifier: MIT
#include "sewerplan/domain/robot_state.h"

#include <sstream>

namespace sewerplan::domain {

std::string describe(const RobotPosition& position, const SewerMap& map) {
  std::ostringstream out;
  if (const auto* m = std::get_if<InManhole>(&position)) {
    out << "in manhole " << map.manhole(m->manhole).name;
  } else if (const auto* s = std::get_if<AtSlot>(&position)) {
    out << "at " << map.manhole(s->manhole).name << " slot " << to_paper_number(s->slot) << " ("
        << map.pipe(map.slot(s->manhole, s->slot).pipe).name << ")";
  } else {
    const auto& p = std::get<InPipe>(position);
    out << "in pipe " << map.pipe(p.pipe).name << " at " << p.offset_m << " m";
  }
  return out.str();
}

std::optional<ManholeId> manhole_of(const RobotPosition& position) {
  if (const auto* m = std::get_if<InManhole>(&position)) return m->manhole;
  if (const auto* s = std::get_if<AtSlot>(&position)) return s->manhole;
  return std::nullopt;
}

double end_offset_m(const Pipe& pipe, std::size_t end) { return end == 0 ? 0.0 : pipe.length_m; }

MissionProgress initial_progress(const Mission& mission, const SewerMap& map) {
  MissionProgress progress;
  progress.done.assign(mission.tasks.size(), false);
  if (const auto* m = std::get_if<ManholeId>(&mission.start)) {
    progress.position = InManhole{*m};
  } else {
    const auto& spot = std::get<PipeSpot>(mission.start);
    progress.position = InPipe{spot.pipe, spot.offset_m.value_or(map.pipe(spot.pipe).length_m / 2)};
  }
  return progress;
}

}  // namespace sewerplan::domain
