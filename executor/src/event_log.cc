// SPDX-License-Identifier: MIT
#include "sewerplan/executor/event_log.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string_view>

#include <nlohmann/json.hpp>

#include "sewerplan/core/overloaded.h"

namespace sewerplan::executor {
namespace {

// A number with the precision of its unit, which the key's suffix names (issue 18): metres 2
// decimals, seconds, milliseconds and watt-hours 1, anything else 2.
int decimals_for(std::string_view key) {
  const auto ends = [&](std::string_view suffix) {
    return key.size() >= suffix.size() && key.substr(key.size() - suffix.size()) == suffix;
  };
  if (ends("_s") || ends("_ms") || ends("_wh")) return 1;
  return 2;
}

std::string readable_value(std::string_view key, const EventValue& value) {
  return std::visit(Overloaded{[](const std::string& s) { return s; },
                               [&](double d) {
                                 std::ostringstream out;
                                 out << std::fixed << std::setprecision(decimals_for(key)) << d;
                                 return out.str();
                               },
                               [](std::int64_t i) { return std::to_string(i); },
                               [](bool b) { return std::string(b ? "yes" : "no"); },
                               [](const std::vector<std::string>& list) {
                                 std::string out;
                                 for (const auto& s : list) out += (out.empty() ? "" : ", ") + s;
                                 return "[" + out + "]";
                               }},
                    value);
}

}  // namespace

EventLog::EventLog(std::ostream* json_lines, std::ostream* readable)
    : json_lines_(json_lines), readable_(readable) {}

std::string EventLog::to_json(const Event& event) {
  nlohmann::ordered_json j;
  j["t_s"] = std::round(event.t_s * 1000) / 1000;
  j["type"] = event.type;
  for (const auto& [key, value] : event.fields) {
    std::visit([&, &k = key](const auto& v) { j[k] = v; }, value);
  }
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

void EventLog::add(double t_s, std::string type,
                   std::vector<std::pair<std::string, EventValue>> fields) {
  events_.push_back({t_s, std::move(type), std::move(fields)});
  const Event& e = events_.back();
  if (json_lines_ != nullptr) *json_lines_ << to_json(e) << '\n';
  if (readable_ != nullptr) {
    std::ostringstream line;
    line << '[' << std::fixed << std::setprecision(1) << std::setw(8) << e.t_s << " s] "
         << std::left << std::setw(12) << e.type << std::right;
    for (const auto& [key, value] : e.fields) {
      line << ' ' << key << '=' << readable_value(key, value);
    }
    *readable_ << line.str() << '\n';
  }
}

std::size_t EventLog::count(std::string_view type) const {
  return static_cast<std::size_t>(std::count_if(events_.begin(), events_.end(),
                                                [&](const Event& e) { return e.type == type; }));
}

}  // namespace sewerplan::executor
