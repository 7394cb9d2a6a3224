// SPDX-License-Identifier: MIT
#include "json_fields.h"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace sewerplan::detail {

JsonFields::JsonFields(const nlohmann::json& json, std::string path, std::string_view file,
                       Diagnostics& diagnostics)
    : json_(json),
      path_(std::move(path)),
      file_(file),
      diagnostics_(diagnostics),
      is_object_(json.is_object()) {
  if (!is_object_) {
    diagnostics_.error(where(), std::string("expected an object, got ") + json.type_name());
  }
}

std::string JsonFields::where(std::string_view key) const {
  std::string w(file_);
  w += ':';
  w += path_;
  if (!key.empty()) {
    w += '.';
    w += key;
  }
  return w;
}

bool JsonFields::has(std::string_view key) const {
  return is_object_ && json_.find(key) != json_.end();
}

const nlohmann::json* JsonFields::find(std::string_view key, Need need) {
  if (!is_object_) return nullptr;
  auto it = json_.find(key);
  if (it == json_.end()) {
    if (need == Need::kRequired) {
      diagnostics_.error(where(), "missing required field '" + std::string(key) + "'");
    }
    return nullptr;
  }
  return &*it;
}

void JsonFields::wrong_type(std::string_view key, std::string_view expected,
                            const nlohmann::json& got) {
  diagnostics_.error(where(key), "expected " + std::string(expected) + ", got " +
                                     (got.is_primitive() ? got.dump() : got.type_name()));
}

std::optional<double> JsonFields::number(std::string_view key, Need need) {
  const nlohmann::json* v = find(key, need);
  if (v == nullptr) return std::nullopt;
  if (!v->is_number()) {
    wrong_type(key, "a number", *v);
    return std::nullopt;
  }
  return v->get<double>();
}

std::optional<std::string> JsonFields::string(std::string_view key, Need need) {
  const nlohmann::json* v = find(key, need);
  if (v == nullptr) return std::nullopt;
  if (!v->is_string()) {
    wrong_type(key, "a string", *v);
    return std::nullopt;
  }
  return v->get<std::string>();
}

std::optional<bool> JsonFields::boolean(std::string_view key, Need need) {
  const nlohmann::json* v = find(key, need);
  if (v == nullptr) return std::nullopt;
  if (!v->is_boolean()) {
    wrong_type(key, "true or false", *v);
    return std::nullopt;
  }
  return v->get<bool>();
}

const nlohmann::json* JsonFields::array(std::string_view key, Need need) {
  const nlohmann::json* v = find(key, need);
  if (v == nullptr) return nullptr;
  if (!v->is_array()) {
    wrong_type(key, "an array", *v);
    return nullptr;
  }
  return v;
}

const nlohmann::json* JsonFields::member(std::string_view key, Need need) {
  return find(key, need);
}

void JsonFields::warn_unknown(std::initializer_list<std::string_view> known) {
  if (!is_object_) return;
  for (const auto& [key, value] : json_.items()) {
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      diagnostics_.warning(where(key), "unknown field '" + key + "' ignored");
    }
  }
}

std::optional<nlohmann::json> parse_json(std::string_view text, std::string_view file,
                                         Diagnostics& diagnostics) {
  try {
    return nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is 1-based: the position of the offending character.
    const std::size_t byte = std::min<std::size_t>(e.byte == 0 ? 0 : e.byte - 1, text.size());
    const auto before = text.substr(0, byte);
    const std::size_t line =
        1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
    const std::size_t line_start = before.rfind('\n');
    const std::size_t column = line_start == std::string_view::npos ? byte + 1 : byte - line_start;
    std::string message = e.what();
    // nlohmann's message starts with "[json.exception.parse_error.101] parse error at line ...: ".
    if (auto colon = message.find(": ", message.find("parse error")); colon != std::string::npos) {
      message = message.substr(colon + 2);
    }
    diagnostics.error(std::string(file) + ":" + std::to_string(line) + ":" + std::to_string(column),
                      "JSON syntax error: " + message);
    return std::nullopt;
  }
}

std::string format_double(double v) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, end);
}

}  // namespace sewerplan::detail
