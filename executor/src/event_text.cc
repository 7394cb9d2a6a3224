// SPDX-License-Identifier: MIT
// The readable live log (event_text.h).
#include "sewerplan/executor/event_text.h"

#include <iomanip>
#include <sstream>
#include <string_view>

#include "sewerplan/core/overloaded.h"

#include "event_fields.h"

namespace sewerplan::executor {
namespace {

// A number with the precision of its unit, which the key's suffix names: metres 2 decimals,
// seconds, milliseconds and watt-hours 1, anything else 2.
int decimals_for(std::string_view key) {
  if (key.ends_with("_s") || key.ends_with("_ms") || key.ends_with("_wh")) return 1;
  return 2;
}

std::string readable_value(std::string_view key, const detail::FieldValue& value) {
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

std::string readable_line(const Event& event) {
  std::ostringstream line;
  line << '[' << std::fixed << std::setprecision(1) << std::setw(8) << event.t_s << " s] "
       << std::left << std::setw(12) << type_name(event) << std::right;
  for (const auto& [key, value] : detail::fields_of(event)) {
    line << ' ' << key << '=' << readable_value(key, value);
  }
  return line.str();
}

EventObserver readable_writer(std::ostream& out) {
  return [&out](const Event& event) { out << readable_line(event) << '\n'; };
}

}  // namespace sewerplan::executor
