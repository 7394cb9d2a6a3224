// SPDX-License-Identifier: MIT
// EventTrace: what a picture needs from an executed mission's event log (JSON lines, as
// `sewerplan simulate --log` writes them, read into typed events by executor/event_json.h).
//
// The route driven is the plan steps of the ActionEvents, in order (the last one may have been
// cut short by a failure); blocked pipes and closed passages come from the FailureEvents; done
// tasks from TaskDoneEvents; the outcome from the MissionEndEvent or a BeaconEvent. Lines of
// types the reader does not know are skipped, so logs from newer versions still read. A line the
// reader rejects, a step that does not parse, or a name not in the map is an error naming the
// file and line.
//
//   Diagnostics diagnostics;
//   Result<EventTrace> trace = read_event_trace(text, "events.jsonl", map, mission, diagnostics);
//   Result<EventTrace> from_file = read_event_trace_file("events.jsonl", map, mission,
//   diagnostics);
//
// Thread safety: read_event_trace shares nothing: call it from any number of threads, each
// with its own Diagnostics.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/plan.h"

namespace sewerplan::render {

struct EventTrace {
  std::vector<domain::PlanStep> driven;
  std::vector<Blockage> blocked;  // pipes found blocked or dangerous
  std::vector<ClosedPassage> closed;
  std::vector<std::string> tasks_done;
  std::string outcome;  // "ended at exit M4", "beacon: ...", or empty when the log stops early
  std::size_t replans = 0;
};

Result<EventTrace> read_event_trace(std::string_view text, const std::string& file_name,
                                    const SewerMap& map, const Mission& mission,
                                    Diagnostics& diagnostics);
// The same, read from the file at `path` (an I/O error names the file).
Result<EventTrace> read_event_trace_file(const std::filesystem::path& path, const SewerMap& map,
                                         const Mission& mission, Diagnostics& diagnostics);

}  // namespace sewerplan::render
