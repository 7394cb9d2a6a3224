// SPDX-License-Identifier: MIT
// Reading an event log for pictures (event_trace.h).
#include "sewerplan/render/event_trace.h"

#include <nlohmann/json.hpp>

#include "sewerplan/domain/plan_text.h"

namespace sewerplan::render {
namespace {

using Json = nlohmann::json;

std::string string_field(const Json& j, const char* key) {
  if (!j.contains(key) || !j.at(key).is_string()) return {};
  return j.at(key).get<std::string>();
}

}  // namespace

Result<EventTrace> read_event_trace(std::string_view text, const std::string& file_name,
                                    const SewerMap& map, const Mission& mission,
                                    Diagnostics& diagnostics) {
  EventTrace trace;
  std::size_t line_number = 0;
  const std::size_t errors_before = diagnostics.error_count();
  auto bad = [&](const std::string& what) {
    diagnostics.error(file_name + ":" + std::to_string(line_number), what);
  };
  while (!text.empty()) {
    ++line_number;
    const std::size_t newline = text.find('\n');
    const std::string_view line = text.substr(0, newline);
    text = newline == std::string_view::npos ? std::string_view{} : text.substr(newline + 1);
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    const Json j = Json::parse(line, nullptr, false);
    if (j.is_discarded() || !j.is_object()) {
      bad("not a JSON object");
      continue;
    }
    const std::string type = string_field(j, "type");
    if (type == "action") {
      const std::string step = string_field(j, "step");
      Diagnostics step_diagnostics;
      Result<domain::Plan> plan =
          domain::parse_plan(step, file_name + ":" + std::to_string(line_number) + " step", map,
                             mission, step_diagnostics);
      if (!plan.has_value() || plan->steps.size() != 1) {
        bad("action step '" + step + "' is not one action of this map and mission");
        continue;
      }
      trace.driven.push_back(plan->steps.front());
    } else if (type == "failure") {
      const std::string pipe = string_field(j, "pipe");
      const std::string manhole = string_field(j, "manhole");
      if (!pipe.empty()) {
        const auto id = map.find_pipe(pipe);
        const auto offset = j.contains("offset_m") && j.at("offset_m").is_number()
                                ? j.at("offset_m").get<double>()
                                : -1.0;
        if (!id || !(offset >= 0) || offset > map.pipe(*id).length_m) {
          bad("failure: pipe '" + pipe + "' or its offset_m is not on the map");
          continue;
        }
        trace.blocked.push_back({*id, offset});
      } else if (!manhole.empty()) {
        const auto id = map.find_manhole(manhole);
        const auto slot = [&](const char* key) -> std::int64_t {
          return j.contains(key) && j.at(key).is_number_integer() ? j.at(key).get<std::int64_t>()
                                                                  : 0;
        };
        const std::int64_t from = slot("from_slot");
        const std::int64_t to = slot("to_slot");
        const auto slots = id ? static_cast<std::int64_t>(map.manhole(*id).slot_count) : 0;
        if (!id || from < 1 || to < 1 || from > slots || to > slots) {
          bad("failure: manhole '" + manhole + "' or its slots are not on the map");
          continue;
        }
        trace.closed.push_back({*id, SlotIndex{static_cast<std::uint16_t>(from - 1)},
                                SlotIndex{static_cast<std::uint16_t>(to - 1)}});
      }
    } else if (type == "task_done") {
      trace.tasks_done.push_back(string_field(j, "task"));
    } else if (type == "replan") {
      ++trace.replans;
    } else if (type == "beacon") {
      trace.outcome = "beacon: " + string_field(j, "reason");
    } else if (type == "mission_end") {
      if (string_field(j, "outcome") == "ended")
        trace.outcome = "ended at " + string_field(j, "end");
    }
  }
  if (diagnostics.error_count() > errors_before) {
    return Error{ErrorCode::kParse, file_name + ": not an event log of this map and mission"};
  }
  return trace;
}

}  // namespace sewerplan::render
