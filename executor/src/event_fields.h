// SPDX-License-Identifier: MIT
// An event's fields as the logs write them: names, plain values, in the log's order.
//
// Private to executor: the one place that says which field of which event is written how, so that
// the JSON lines (event_json.cc) and the readable log (event_text.cc) cannot drift apart.
//
//   write("type", detail::to_string(detail::type_of(event)));
//   for (const auto& [name, value] : detail::fields_of(event)) write(name, value);
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "sewerplan/executor/events.h"

namespace sewerplan::executor::detail {

using FieldValue = std::variant<std::string, double, std::int64_t, bool, std::vector<std::string>>;
using Fields = std::vector<std::pair<std::string_view, FieldValue>>;

// Every field but `t_s` and `type`, in the order the log writes them.
Fields fields_of(const Event& event);

// An event's `type`, one name per type (type_name): an alternative of Event::what, PlanEvent two
// ("plan", "replan"). The writer names an event by type_of; the reader switches on the type it
// parses, so a type is named once, in events.cc.
enum class EventType {
  kPlan,
  kReplan,
  kAction,
  kJob,
  kError,
  kRecovery,
  kFailure,
  kTaskDone,
  kTaskDropped,
  kReserve,
  kArrival,
  kHazard,
  kBeacon,
  kMissionEnd,
};

EventType type_of(const Event& event);
// "plan", "replan", "action", ..., "mission_end" (events.h, type_name); and back (empty for any
// other text).
std::string_view to_string(EventType type);
std::optional<EventType> parse_event_type(std::string_view name);

}  // namespace sewerplan::executor::detail
