// SPDX-License-Identifier: MIT
#include "request_guard.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <regex>
#include <string_view>

#include "http_reply.h"
#include <arpa/inet.h>

namespace sewerplan::server {
namespace {

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

bool is_ip_address(const std::string& name) {
  unsigned char address[16];
  return inet_pton(AF_INET, name.c_str(), address) == 1 ||
         inet_pton(AF_INET6, name.c_str(), address) == 1;
}

// The POST endpoints whose body is a file sent as it is (a map, condition data, an event log).
bool takes_a_file(const std::string& path) {
  static const std::regex files(R"(/api/maps(/[^/]+/(condition|replay))?)");
  return std::regex_match(path, files);
}

// "text/plain; charset=UTF-8" -> "text/plain".
std::string media_type(const std::string& content_type) {
  std::string type = lower(content_type.substr(0, content_type.find(';')));
  const auto blank = [](unsigned char c) { return std::isspace(c) != 0; };
  type.erase(type.begin(), std::find_if_not(type.begin(), type.end(), blank));
  type.erase(std::find_if_not(type.rbegin(), type.rend(), blank).base(), type.end());
  return type;
}

// The types a page may send to another origin without a preflight (the Fetch standard's
// CORS-safelisted request types).
bool safelisted(const std::string& type) {
  return type == "text/plain" || type == "application/x-www-form-urlencoded" ||
         type == "multipart/form-data";
}

std::optional<Refusal> check_host(const httplib::Request& req, const GuardOptions& guard) {
  if (!req.has_header("Host")) {
    return Refusal{kForbidden, "forbidden-host",
                   "the request has no Host header: send the station's address as Host"};
  }
  const std::string value = req.get_header_value("Host");
  const std::string name = host_name(value);
  const bool allowed =
      !name.empty() &&
      (is_ip_address(name) || name == "localhost" || name == lower(guard.bound_host) ||
       std::any_of(guard.allowed_hosts.begin(), guard.allowed_hosts.end(),
                   [&](const std::string& h) { return lower(h) == name; }));
  if (allowed) return std::nullopt;
  return Refusal{kForbidden, "forbidden-host",
                 "Host '" + value +
                     "' is not a name this station is served under (a page of another site may "
                     "have made its name point here): open the station by its address or "
                     "localhost, or start `sewerplan serve` with --allow-host " +
                     (name.empty() ? std::string("NAME") : name) + " to allow that name"};
}

std::optional<Refusal> check_origin(const httplib::Request& req) {
  if (!req.has_header("Origin")) return std::nullopt;
  const std::string origin = lower(req.get_header_value("Origin"));
  const std::string host = lower(req.get_header_value("Host"));
  if (origin == "http://" + host || origin == "https://" + host) return std::nullopt;
  return Refusal{kForbidden, "forbidden-origin",
                 "Origin '" + req.get_header_value("Origin") + "' is not this station's (http://" +
                     req.get_header_value("Host") +
                     "): the station answers its own page only, and no request from another "
                     "site; open the station's page at its own address"};
}

std::optional<Refusal> check_method(const httplib::Request& req) {
  if (req.method == "GET" || req.method == "HEAD" || req.method == "POST") return std::nullopt;
  return Refusal{kMethodNotAllowed, "method-not-allowed",
                 req.method + " " + req.path +
                     ": the station answers GET, HEAD and POST only, and no cross-origin "
                     "request (no CORS preflight is granted)"};
}

std::optional<Refusal> check_content_type(const httplib::Request& req) {
  if (req.method != "POST") return std::nullopt;
  const std::string given = req.get_header_value("Content-Type");
  const std::string type = media_type(given);
  const std::string what = given.empty() ? "none" : "'" + given + "'";
  if (takes_a_file(req.path)) {
    if (!type.empty() && !safelisted(type)) return std::nullopt;
    return Refusal{kUnsupportedMediaType, "unsupported-media-type",
                   "POST " + req.path +
                       " needs the file's own Content-Type (application/json, application/xml, "
                       "application/octet-stream, ...), not " +
                       what +
                       ": text/plain, form types and none are what any web page may send here "
                       "unasked (curl: --data-binary @FILE -H 'Content-Type: "
                       "application/octet-stream')"};
  }
  if (type == "application/json") return std::nullopt;
  return Refusal{kUnsupportedMediaType, "unsupported-media-type",
                 "POST " + req.path + " needs \"Content-Type: application/json\", not " + what +
                     ": the body is JSON, and other types are what any web page may send here "
                     "unasked (curl: -H 'Content-Type: application/json')"};
}

std::optional<Refusal> check_length(const httplib::Request& req, std::size_t limit) {
  if (!req.has_header("Content-Length")) return std::nullopt;
  const std::string text = req.get_header_value("Content-Length");
  std::uint64_t length = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), length);
  if (ec == std::errc::result_out_of_range)
    length = UINT64_MAX;
  else if (ec != std::errc() || end != text.data() + text.size()) {
    return Refusal{kBadRequest, "http-400", "Content-Length '" + text + "': not a byte count"};
  }
  if (length <= limit) return std::nullopt;
  return Refusal{kPayloadTooLarge, "http-413", body_over_limit(limit)};
}

}  // namespace

std::string body_over_limit(std::size_t limit) {
  return "the request body is over the size limit of " + std::to_string(limit) + " bytes";
}

std::string host_name(const std::string& host_header) {
  std::string_view name = host_header;
  std::string_view port;
  if (name.starts_with('[')) {
    const std::size_t close = name.find(']');
    if (close == std::string_view::npos) return {};
    port = name.substr(close + 1);
    name = name.substr(1, close - 1);
    if (!port.empty() && !port.starts_with(':')) return {};
  } else if (const std::size_t colon = name.rfind(':'); colon != std::string_view::npos) {
    port = name.substr(colon);
    name = name.substr(0, colon);
  }
  if (name.empty() || (!host_header.starts_with('[') && name.find(':') != std::string_view::npos)) {
    return {};  // a colon outside brackets: only an IPv6 address has them, and in brackets
  }
  if (!port.empty()) {
    port.remove_prefix(1);
    if (port.empty() || !std::all_of(port.begin(), port.end(),
                                     [](unsigned char c) { return std::isdigit(c) != 0; })) {
      return {};
    }
  }
  return lower(name);
}

std::optional<Refusal> check_request(const httplib::Request& req, const GuardOptions& guard) {
  if (auto r = check_host(req, guard)) return r;
  if (auto r = check_origin(req)) return r;
  if (auto r = check_method(req)) return r;
  if (auto r = check_content_type(req)) return r;
  return check_length(req, guard.max_body_bytes);
}

}  // namespace sewerplan::server
