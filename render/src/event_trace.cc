// SPDX-License-Identifier: MIT
// Reading an event log for pictures (event_trace.h).
#include "sewerplan/render/event_trace.h"

#include "sewerplan/core/overloaded.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/executor/event_json.h"

namespace sewerplan::render {

Result<EventTrace> read_event_trace(std::string_view text, const std::string& file_name,
                                    const SewerMap& map, const Mission& mission,
                                    Diagnostics& diagnostics) {
  const std::size_t errors_before = diagnostics.error_count();
  const std::vector<executor::LoggedEvent> events =
      executor::read_event_log_lines(text, file_name, diagnostics);
  EventTrace trace;
  for (const executor::LoggedEvent& logged : events) {
    const std::string where = file_name + ":" + std::to_string(logged.line);
    auto bad = [&](const std::string& what) { diagnostics.error(where, what); };
    std::visit(
        Overloaded{
            [&](const executor::ActionEvent& e) {
              Diagnostics step_diagnostics;
              Result<domain::Plan> plan =
                  domain::parse_plan(e.step, where + " step", map, mission, step_diagnostics);
              if (!plan.has_value() || plan->steps.size() != 1) {
                bad("action step '" + e.step + "' is not one action of this map and mission");
                return;
              }
              trace.driven.push_back(plan->steps.front());
            },
            [&](const executor::FailureEvent& e) {
              if (const auto* in = std::get_if<executor::FailureEvent::InPipe>(&e.where)) {
                const auto id = map.find_pipe(in->pipe);
                if (!id || !(in->offset_m >= 0) || in->offset_m > map.pipe(*id).length_m) {
                  bad("failure: pipe '" + in->pipe + "' or its offset_m is not on the map");
                  return;
                }
                trace.blocked.push_back({*id, in->offset_m});
              } else if (const auto* p = std::get_if<executor::FailureEvent::Passage>(&e.where)) {
                const auto id = map.find_manhole(p->manhole);
                const int slots = id ? static_cast<int>(map.manhole(*id).slot_count) : 0;
                if (!id || p->from_slot < 1 || p->to_slot < 1 || p->from_slot > slots ||
                    p->to_slot > slots) {
                  bad("failure: manhole '" + p->manhole + "' or its slots are not on the map");
                  return;
                }
                trace.closed.push_back({*id,
                                        SlotIndex{static_cast<std::uint16_t>(p->from_slot - 1)},
                                        SlotIndex{static_cast<std::uint16_t>(p->to_slot - 1)}});
              }
            },
            [&](const executor::TaskDoneEvent& e) { trace.tasks_done.push_back(e.task); },
            [&](const executor::PlanEvent& e) { trace.replans += e.replan ? 1 : 0; },
            [&](const executor::BeaconEvent& e) { trace.outcome = "beacon: " + e.reason; },
            [&](const executor::MissionEndEvent& e) {
              if (e.outcome == executor::MissionOutcome::kEnded)
                trace.outcome = "ended at " + e.end;
              if (e.outcome == executor::MissionOutcome::kHalted) trace.outcome = "halted " + e.end;
            },
            [](const auto&) {}},
        logged.event.what);
  }
  if (diagnostics.error_count() > errors_before) {
    return Error{ErrorCode::kParse, file_name + ": not an event log of this map and mission"};
  }
  return trace;
}

Result<EventTrace> read_event_trace_file(const std::filesystem::path& path, const SewerMap& map,
                                         const Mission& mission, Diagnostics& diagnostics) {
  Result<std::string> text = read_text_file(path);
  if (!text.has_value()) return text.error();
  return read_event_trace(*text, path.string(), map, mission, diagnostics);
}

}  // namespace sewerplan::render
