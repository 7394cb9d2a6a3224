// SPDX-License-Identifier: MIT
#include "json_output.h"

#include <algorithm>
#include <cctype>
#include <sstream>

#include "sewerplan/domain/plan_json.h"

namespace sewerplan::cli {
namespace {}  // namespace

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
