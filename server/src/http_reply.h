// SPDX-License-Identifier: MIT
// How the station's handlers answer: JSON with the CLI's error shape ({"error": {...}},
// documents.h) and the statuses the API uses (docs/operator-station.md). Private to server/src,
// the only place that includes httplib.h.
//
//   if (!m) return send_error(res, kNotFound, Error{ErrorCode::kInvalidArgument, "no map 'x'"});
//   send_json(res, {{"state", "running"}});
#pragma once

#include <string>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/server/documents.h"

#include <httplib.h>

namespace sewerplan::server {

inline constexpr int kBadRequest = 400;
inline constexpr int kUnauthorized = 401;
inline constexpr int kForbidden = 403;  // a Host or Origin not the station's (request_guard.h)
inline constexpr int kNotFound = 404;
inline constexpr int kMethodNotAllowed = 405;
inline constexpr int kConflict = 409;  // a limit of the station: maps, campaigns at once
inline constexpr int kPayloadTooLarge = 413;
inline constexpr int kUnsupportedMediaType = 415;
inline constexpr int kUnprocessable = 422;  // well-formed, but not a valid mission, log or plan

// Debian's httplib compresses every "application/json", "application/javascript" and "text/..."
// answer with brotli at its slowest quality (11) when the client accepts "br", as every browser
// does: the page's 840 kB bundle took 3 s to compress on an idle machine and 14 to 20 s on a
// loaded one, and a 100,000-manhole map's geometry far longer. The station serves its own
// machine or a LAN: it sends uncompressed, and these types (with a charset, so that httplib's
// exact match does not see them) are how (docs/operator-station.md, "Figures").
inline constexpr const char* kJsonType = "application/json; charset=utf-8";
inline constexpr const char* kJavaScriptType = "application/javascript; charset=utf-8";

// One line of JSON; bad UTF-8 in a name is replaced, never thrown on.
std::string dump(const Json& j);

void send_json(httplib::Response& res, const Json& j, int status = 200);
// {"error": error_object(...)} plus the members of `extra`.
void send_error(httplib::Response& res, int status, const Error& error,
                const Diagnostics& diagnostics = {}, Json extra = Json::object());
// 400 with `message` (it names the parameter or field that is wrong).
void bad_request(httplib::Response& res, const std::string& message);

}  // namespace sewerplan::server
