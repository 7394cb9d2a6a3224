// SPDX-License-Identifier: MIT
// The readable live log (event_text.h).
#include "sewerplan/executor/event_text.h"

#include <iomanip>
#include <sstream>

#include "sewerplan/core/overloaded.h"

#include "event_fields.h"

namespace sewerplan::executor {
namespace {

std::string readable_value(const detail::FieldValue& value) {
  return std::visit(Overloaded{[](const std::string& s) { return s; },
                               [](double d) {
                                 std::ostringstream out;
                                 out << std::setprecision(4) << d;
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
    line << ' ' << key << '=' << readable_value(value);
  }
  return line.str();
}

EventObserver readable_writer(std::ostream& out) {
  return [&out](const Event& event) { out << readable_line(event) << '\n'; };
}

}  // namespace sewerplan::executor
