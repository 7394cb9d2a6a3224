// SPDX-License-Identifier: MIT
#include "http_reply.h"

namespace sewerplan::server {

std::string dump(const Json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

void send_json(httplib::Response& res, const Json& j, int status) {
  res.status = status;
  res.set_content(dump(j), kJsonType);
}

void send_error(httplib::Response& res, int status, const Error& error,
                const Diagnostics& diagnostics, Json extra) {
  Json j = {{"error", error_object(error, diagnostics, exit_code_for(error))}};
  for (auto& [key, value] : extra.items()) j[key] = value;
  send_json(res, j, status);
}

void bad_request(httplib::Response& res, const std::string& message) {
  send_error(res, kBadRequest, Error{ErrorCode::kInvalidArgument, message});
}

}  // namespace sewerplan::server
