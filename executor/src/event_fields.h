// SPDX-License-Identifier: MIT
// An event's fields as the logs write them: names, plain values, in the log's order.
//
// Private to executor: the one place that says which field of which event is written how, so that
// the JSON lines (event_json.cc) and the readable log (event_text.cc) cannot drift apart.
//
//   for (const auto& [name, value] : detail::fields_of(event)) write(name, value);
#pragma once

#include <cstdint>
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

}  // namespace sewerplan::executor::detail
