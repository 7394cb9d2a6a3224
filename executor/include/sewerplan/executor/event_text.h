// SPDX-License-Identifier: MIT
// The readable live log: one line per event (events.h) for people watching a mission.
//
// "[    39.3 s] error        kind=blockage reason=obstacle in P1 at 3.00 m where=in pipe P1 ...":
// the mission time, the type, and the fields of the JSON-lines log (event_json.h) in its order;
// numbers to 4 significant digits, flags as yes and no, lists in brackets. For people, not for
// programs: read the JSON lines back instead.
//
//   executor.subscribe(readable_writer(std::cout));
//
// Thread safety: readable_line shares nothing; a writer writes to its stream on the thread that
// calls it (run()'s thread, as an observer).
#pragma once

#include <ostream>
#include <string>

#include "sewerplan/executor/events.h"

namespace sewerplan::executor {

// One event as a readable line, without the newline.
std::string readable_line(const Event& event);

// An observer that writes each event's readable line to `out`, which must outlive it.
EventObserver readable_writer(std::ostream& out);

}  // namespace sewerplan::executor
