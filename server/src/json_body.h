// SPDX-License-Identifier: MIT
// A request's JSON body, read as the handlers use it (nlohmann's Json, documents.h), refusing what
// nlohmann would silently drop: a key given twice in one object, of which it keeps the last. Every
// reader of sewerplan's files refuses that (core's JsonFields, docs/formats/); a body sent to the
// station is the same document, so /simulate and /campaign, which take the mission inside a larger
// object, refuse it as /plan, which reads the mission itself, does. Private to server/src.
//
//   Result<Json> body = parse_json_body(req.body);
//   if (!body.has_value()) return bad_request(res, body.error().message);
#pragma once

#include <string_view>

#include "sewerplan/core/result.h"
#include "sewerplan/server/documents.h"

namespace sewerplan::server {

// The value, or kParse: the syntax error's position and nlohmann's words ("the body is not JSON:
// parse error at line 1, column 9: ..."), a body nested deeper than 256 levels, or each repeated
// key by its JSON path ("$.mission.tasks[2].id: error: field 'id' given twice in one object: which
// value is meant is unclear"), one a line, the first 20 named and the rest counted. A key that
// holds '.' or '[' is written as it is, as the file readers do.
Result<Json> parse_json_body(std::string_view text);

}  // namespace sewerplan::server
