// SPDX-License-Identifier: MIT
#include "sewerplan/executor/recovery.h"

#include <nlohmann/json.hpp>

namespace sewerplan::executor {

Result<RecoveryConfig> read_recovery_json(std::string_view text, const std::string& file_name) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) {
    return Error{ErrorCode::kParse, file_name + ": not a JSON object"};
  }
  RecoveryConfig c;
  for (const auto& item : j.items()) {
    // Not a structured binding: clang 14 cannot capture one in the lambdas below.
    const std::string& key = item.key();
    const nlohmann::json& value = item.value();
    const std::string where = file_name + ": \"" + key + "\"";
    auto count = [&](int& field) -> std::optional<Error> {
      if (!value.is_number_integer() || value.get<long long>() < 0 ||
          value.get<long long>() > 1000) {
        return Error{ErrorCode::kParse, where + " must be a count from 0 to 1000"};
      }
      field = value.get<int>();
      return std::nullopt;
    };
    auto distance = [&](double& field) -> std::optional<Error> {
      if (!value.is_number() || value.get<double>() < 0 || value.get<double>() > 10) {
        return Error{ErrorCode::kParse, where + " must be metres from 0 to 10"};
      }
      field = value.get<double>();
      return std::nullopt;
    };
    std::optional<Error> error;
    if (key == "backup_retries") {
      error = count(c.backup_retries);
    } else if (key == "backup_m") {
      error = distance(c.backup_m);
    } else if (key == "lift_retries") {
      error = count(c.lift_retries);
    } else if (key == "push_retries") {
      error = count(c.push_retries);
    } else if (key == "danger_backoff_m") {
      error = distance(c.danger_backoff_m);
    } else if (key == "max_reboots") {
      error = count(c.max_reboots);
    } else if (key == "push_allowed") {
      if (!value.is_boolean()) {
        error = Error{ErrorCode::kParse, where + " must be true or false"};
      } else {
        c.push_allowed = value.get<bool>();
      }
    } else {
      error = Error{ErrorCode::kParse, where + " is not a recovery setting"};
    }
    if (error) return *error;
  }
  return c;
}

}  // namespace sewerplan::executor
