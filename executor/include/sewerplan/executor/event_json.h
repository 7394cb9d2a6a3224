// SPDX-License-Identifier: MIT
// The event log as JSON lines: one event (events.h) per line, written and read back.
//
// Each line is an object with `t_s` (rounded to the millisecond), `type` (type_name) and the
// event's fields in a fixed order (docs/executor.md lists them). The format is stable: the same
// run gives the same bytes, and logs of earlier versions read back. Reading is lenient where older
// versions differ and strict where the text is wrong:
// - a line of an unknown `type` is skipped (a newer version's event);
// - a field that is missing keeps its default (older versions had fewer fields), and the decision
//   names of the first logs ("follow", "call for recovery") read as kFollowPlan and
//   kCallForRecovery;
// - a line that is not a JSON object, a field of the wrong type, or a name (decision, error kind,
//   recovery phase, ...) that is not one of ours is an error naming the file and line.
//
//   executor.subscribe(json_lines_writer(file));
//   Result<std::vector<Event>> events = read_event_log(text, "events.jsonl", diagnostics);
//
// Thread safety: the functions share nothing. A writer writes to its stream on the thread that
// calls it (run()'s thread, as an observer).
#pragma once

#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/executor/events.h"

namespace sewerplan::executor {

// One event as a JSON object on one line, without the newline.
std::string to_json_line(const Event& event);

// An observer that writes each event as a line to `out` (which must outlive it) and flushes it,
// so that whoever follows the file sees every event as it happens (a few hundred a mission).
EventObserver json_lines_writer(std::ostream& out);

// Reads a whole log. Every bad line is an error in `diagnostics` at "file:line"; any error makes
// the result an error (kParse) too. Blank lines are skipped.
Result<std::vector<Event>> read_event_log(std::string_view text, const std::string& file_name,
                                          Diagnostics& diagnostics);

// The events of the lines that read, each with its line, for readers that check more and name
// lines in their own errors (render's trace); every bad line is an error in `diagnostics`.
struct LoggedEvent {
  Event event;
  std::size_t line = 0;  // from 1
};
std::vector<LoggedEvent> read_event_log_lines(std::string_view text, const std::string& file_name,
                                              Diagnostics& diagnostics);

}  // namespace sewerplan::executor
