// SPDX-License-Identifier: MIT
#include "json_output.h"

#include <algorithm>
#include <cctype>
#include <sstream>

#include "sewerplan/domain/plan_json.h"

namespace sewerplan::cli {
namespace {

// "FILE:LINE", "FILE:$.json.path" or "FILE:/xml/path" into file and line or path.
void add_where(Json& j, const std::string& where) {
  const auto colon = where.rfind(':');
  if (colon == std::string::npos || colon == 0) return;
  const std::string file = where.substr(0, colon);
  const std::string rest = where.substr(colon + 1);
  if (rest.empty()) return;
  j["file"] = file;
  const bool digits =
      std::all_of(rest.begin(), rest.end(), [](unsigned char ch) { return std::isdigit(ch); });
  if (digits && rest.size() < 10) {
    j["line"] = std::stoi(rest);
  } else {
    j["path"] = rest;
  }
}

std::string_view severity_name(Severity s) {
  switch (s) {
    case Severity::kError:
      return "error";
    case Severity::kWarning:
      return "warning";
  }
  return "error";
}

}  // namespace

Json error_object(const Error& error, const Diagnostics& diagnostics, int exit_code) {
  Json j = {{"code", exit_code == kExitUsage && error.code == ErrorCode::kInvalidArgument
                         ? std::string("usage")
                         : std::string(to_string(error.code))},
            {"exit_code", exit_code},
            {"message", error.message}};
  Json list = Json::array();
  bool located = false;
  for (const Diagnostic& d : diagnostics.all()) {
    if (!located && d.severity == Severity::kError) {
      add_where(j, d.where);
      located = true;
    }
    list.push_back(
        {{"severity", severity_name(d.severity)}, {"where", d.where}, {"message", d.message}});
  }
  j["diagnostics"] = std::move(list);
  return j;
}

void print_json(std::ostream& out, const Json& j) {
  out << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
}

int fail(Context& c, bool json, const Error& error, const Diagnostics& diagnostics, Json extra) {
  print_diagnostics(diagnostics, c.err);
  if (diagnostics.error_count() == 0) c.err << error.message << '\n';
  const int code = exit_code_for(error);
  if (json) {
    Json j = {{"error", error_object(error, diagnostics, code)}};
    for (auto& [key, value] : extra.items()) j[key] = value;
    print_json(c.out, j);
  }
  return code;
}

Json plan_verdict_json(const domain::Plan& plan, const domain::ValidationReport& report,
                       const SewerMap& map, const Mission& mission) {
  std::ostringstream text;
  domain::write_plan_json(plan, report, map, mission, text);
  Json j = Json::parse(text.str());
  if (!report.valid) {
    j["error"] = {{"code", "invalid-plan"},
                  {"exit_code", kExitInvalidInput},
                  {"message", report.error},
                  {"diagnostics", Json::array()}};
  }
  return j;
}

int usage_error(Context& c, bool json, const std::string& message) {
  return fail(c, json, Error{ErrorCode::kInvalidArgument, message});
}

std::optional<std::string> map_path(const std::string& option, const std::string& positional,
                                    const std::string& command, Context& c, bool json,
                                    int& exit_code) {
  if (!option.empty() && !positional.empty()) {
    exit_code = usage_error(c, json, command + ": give the map once, with --map");
    return std::nullopt;
  }
  if (option.empty() && positional.empty()) {
    exit_code = usage_error(c, json, command + ": --map is required");
    return std::nullopt;
  }
  if (!positional.empty()) {
    c.err << "sewerplan " << command
          << ": the map as a positional argument is deprecated; use --map " << positional << '\n';
    return positional;
  }
  return option;
}

}  // namespace sewerplan::cli
