// SPDX-License-Identifier: MIT
// What every command prints with --json, and the one shape of a failure (docs/cli.md, "JSON"):
//
//   {"error": {"code": "invalid-map", "exit_code": 1, "message": "...", "file": "map.json",
//              "path": "$.pipes[1].to", "diagnostics": [{"severity", "where", "message"}]}}
//
// "code" is the library's ErrorCode name (core/result.h: "io", "parse", "no-plan", ...) or "usage"
// for a command-line error; "file" and "line" (line-based formats) or "path" (JSON path, XML
// element) are there when the first error names them. Numbers keep their full precision in JSON;
// only the text output rounds them (text_format.h).
//
//   if (!map.has_value()) return fail(c, o.json, map.error(), diagnostics);
#pragma once

#include <optional>
#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/domain/validator.h"

#include "command.h"

namespace sewerplan::cli {

// The documents shared with the operator station's server (server/documents.h).
using server::diagnostics_json;
using server::dropped_json;
using server::error_object;
using server::Json;
using server::plan_failure_json;
using server::plan_json;
using server::plan_verdict_json;
using server::report_json;

// Indented, invalid UTF-8 replaced (a name in a Latin-1 file never aborts the output), newline.
void print_json(std::ostream& out, const Json& j);

// Reports a failure: the diagnostics and the message on standard error, and with `json` the error
// object ({"error": {...}} merged into `extra`) on standard output. Returns the exit code.
int fail(Context& c, bool json, const Error& error, const Diagnostics& diagnostics = {},
         Json extra = Json::object());
// A usage error (exit code 2) with this message.
int usage_error(Context& c, bool json, const std::string& message);

// The map's path from --map or, deprecated, the positional MAP (which prints a note saying so on
// standard error). Empty after a usage error (both given, or neither), with `exit_code` set.
std::optional<std::string> map_path(const std::string& option, const std::string& positional,
                                    const std::string& command, Context& c, bool json,
                                    int& exit_code);

}  // namespace sewerplan::cli
