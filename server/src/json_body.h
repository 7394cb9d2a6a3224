// SPDX-License-Identifier: MIT
// A request's JSON body, parsed by the reader of sewerplan's files (core's JsonDocument) and read
// by its JsonFields and file readers (read_mission_value, hal::read_faults_value), each problem
// named at its JSON path of the "body": "body:$.mission.tasks[2].at: error: ...". The station's
// limits come first: a body nested too deep, or with a key given twice in any of its objects, is
// refused whole before any part of it is read, so that no repeat is silently resolved in a part
// nobody reads (nlohmann, simdjson and browsers each keep a different one of the two). Private to
// server/src.
//
//   Result<JsonDocument> body = parse_json_body(req.body);
//   if (!body.has_value()) return bad_request(res, body.error().message);
//   JsonFields fields(body->root(), "$", kBodyFile, diagnostics);
#pragma once

#include <cstddef>
#include <string_view>

#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/result.h"

namespace sewerplan::server {

// The name of the body in messages, where a file reader names its file.
inline constexpr std::string_view kBodyFile = "body";
// Arrays and objects nested deeper are refused: no request of the API nests more than a few levels.
inline constexpr std::size_t kMaxBodyDepth = 256;
// Keys given twice that are named; the rest are counted. A body of repeated keys could otherwise be
// answered with many times its size.
inline constexpr std::size_t kMaxRepeatsNamed = 20;

// The parsed body, or kParse with one "where: error: message" a line: the syntax error's place
// ("body:1:13: error: syntax error while parsing value - unexpected end of input; ..."), the first
// array or object nested deeper than kMaxBodyDepth ("body:1:257: error: the JSON nests arrays and
// objects more than 256 levels deep"), or each repeated key by its JSON path ("body:$.runs: error:
// field 'runs' given twice in one object: which value is meant is unclear"), the first
// kMaxRepeatsNamed named and the rest counted. Not UTF-8, a number beyond a double and the like
// are refused as the file readers refuse them.
Result<JsonDocument> parse_json_body(std::string_view text);

}  // namespace sewerplan::server
