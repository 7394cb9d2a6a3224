// SPDX-License-Identifier: MIT
// Who may drive the station: the checks every request passes before it is routed and before its
// body is read (docs/operator-station.md, "Who may drive the station"). A web page open in the
// operator's browser can send requests to the station whatever its own origin: a "simple" POST
// (text/plain, a form) without asking first, and, through DNS rebinding (a name of the page's
// that is made to resolve to 127.0.0.1), even as if it were the station's own page. So:
//   - Host must name the station: an IP address (a page reached by an address is that address's
//     page, which rebinding cannot fake), "localhost", the bound host, or a name the operator
//     allowed (`serve --allow-host NAME`); else 403.
//   - Origin, when the browser sends one, must be the station's own: http(s):// + the Host; else
//     403. A preflight (OPTIONS) is refused with it: no cross-origin request is ever allowed.
//   - Only GET, HEAD and POST; a POST carries a Content-Type that no page can send to another
//     origin without a preflight: application/json to the JSON endpoints, any type but
//     text/plain, application/x-www-form-urlencoded, multipart/form-data or none to the uploads
//     (a map, condition data, an event log, sent as they are); else 415.
//   - A Content-Length over the limit is refused (413) before the body is read; bodies of any
//     transfer encoding are read by the station with the limit (station_server.cc).
// Private to server/src.
//
//   if (const std::optional<Refusal> r = check_request(req, guard)) send the refusal
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <httplib.h>

namespace sewerplan::server {

struct GuardOptions {
  std::string bound_host;                  // ServerOptions::host
  std::vector<std::string> allowed_hosts;  // ServerOptions::allowed_hosts
  std::size_t max_body_bytes = 0;
};

// Why a request is refused: its HTTP status, the error's code and a message that says what is
// wrong and what to do.
struct Refusal {
  int status = 0;
  std::string code;
  std::string message;
};

// The refusal of `req` by the rules above, or nullopt. Reads only the request line and headers.
std::optional<Refusal> check_request(const httplib::Request& req, const GuardOptions& guard);

// The message of a body refused for its size (413), whether by its Content-Length or as it is read.
std::string body_over_limit(std::size_t limit);

// The host name of a Host header's value ("[::1]:8080" -> "::1", "Example:80" -> "example"),
// lower-cased; empty if it is not one.
std::string host_name(const std::string& host_header);

}  // namespace sewerplan::server
