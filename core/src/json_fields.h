// SPDX-License-Identifier: MIT
// JsonFields: reads the fields of one JSON object, reporting problems by JSON path.
//
// Private to core. Every sewerplan JSON reader (map, mission, profile) reads objects through it so
// that a wrong type, a missing required field or an unknown (misspelt) field is reported as
// "file:$.pipes[3].length_m: ..." and reading goes on with the next field.
//
//   JsonFields f(json, "$.pipes[3]", "map.json", diagnostics);
//   double length = f.number("length_m").value_or(0);
//   f.reject_unknown({"name", "length_m"});
#pragma once

#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"

namespace sewerplan::detail {

class JsonFields {
 public:
  enum class Need { kRequired, kOptional };

  // `json` must outlive this object. If it is not an object, that is reported once and every
  // field reads as missing.
  JsonFields(const nlohmann::json& json, std::string path, std::string_view file,
             Diagnostics& diagnostics);

  std::optional<double> number(std::string_view key, Need need = Need::kRequired);
  std::optional<std::string> string(std::string_view key, Need need = Need::kRequired);
  std::optional<bool> boolean(std::string_view key, Need need = Need::kRequired);
  // The member, which must be an array (or an object with want_object); nullptr if absent or wrong.
  const nlohmann::json* array(std::string_view key, Need need = Need::kRequired);
  const nlohmann::json* member(std::string_view key, Need need = Need::kRequired);
  bool has(std::string_view key) const;

  // Warns about members not in `known` (likely misspelt), naming each.
  void warn_unknown(std::initializer_list<std::string_view> known);

  // "file:$.path.key"
  std::string where(std::string_view key = {}) const;
  const std::string& path() const { return path_; }
  Diagnostics& diagnostics() { return diagnostics_; }

 private:
  const nlohmann::json* find(std::string_view key, Need need);
  void wrong_type(std::string_view key, std::string_view expected, const nlohmann::json& got);

  const nlohmann::json& json_;
  std::string path_;
  std::string_view file_;
  Diagnostics& diagnostics_;
  bool is_object_;
};

// Parses `text` as JSON. A syntax error is reported as "file:line:column: ..." and gives nullopt.
std::optional<nlohmann::json> parse_json(std::string_view text, std::string_view file,
                                         Diagnostics& diagnostics);

// Shortest text that reads back as exactly `v` (std::to_chars).
std::string format_double(double v);

}  // namespace sewerplan::detail
