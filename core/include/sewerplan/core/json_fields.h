// SPDX-License-Identifier: MIT
// Reading sewerplan's JSON files: a parsed document, and the fields of its objects by JSON path.
//
// The one JSON reader of sewerplan's files: every reader (map, mission, profile, fault file,
// learnt knowledge, ...) parses with JsonDocument and reads objects through JsonFields, so that a
// wrong type, a missing required field, an unknown (misspelt) field or a field given twice in one
// object is reported alike, as "file:$.pipes[3].length_m: ...", and reading goes on. Writers may
// build their text otherwise.
//
// Parsing uses simdjson, which reads a 100,000-manhole map (42 MB) in about 0.14 s where
// nlohmann::json's document tree took 0.76 s (bench/core/map_load_bench.cc); nlohmann is still
// used on the error path, for the line and column of a syntax error (and for what a number too
// large for a double is), and for writing. simdjson is part of this interface: a library that
// reads through it links simdjson too (sewerplan::core does so publicly).
//
//   Diagnostics d;
//   auto doc = JsonDocument::parse(text, "map.json", d);
//   JsonFields f(doc->root(), "$", "map.json", d);
//   double length = f.number("length_m").value_or(0);
//   f.warn_unknown({"name", "length_m"});
#pragma once

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "sewerplan/core/diagnostics.h"

#include <simdjson.h>

namespace sewerplan {

using JsonElement = simdjson::dom::element;
using JsonArray = simdjson::dom::array;

// A parsed JSON text. Elements refer into it: keep it alive while reading them.
class JsonDocument {
 public:
  // A syntax error is reported as "file:line:column: JSON syntax error: ..." and gives nullopt. A
  // leading UTF-8 byte order mark (Windows editors write one) is skipped. Arrays and objects nested
  // more than `max_depth` levels are refused at the first one too deep ("file:1:257: the JSON
  // nests arrays and objects more than 256 levels deep"): files are read with simdjson's 1024, a
  // request's body with less (the station).
  static std::optional<JsonDocument> parse(std::string_view text, std::string_view file,
                                           Diagnostics& diagnostics,
                                           std::size_t max_depth = simdjson::DEFAULT_MAX_DEPTH);
  JsonElement root() const { return root_; }

 private:
  std::unique_ptr<simdjson::dom::parser> parser_;
  JsonElement root_;
};

// One small JSON text after another (the lines of a JSON-lines log) with one parser, which keeps
// its buffers between texts. The element of a text is valid until the next parse; a text that is
// not JSON gives nullopt, and the caller says where it was.
class JsonLineParser {
 public:
  JsonLineParser();
  std::optional<JsonElement> parse(std::string_view text);

 private:
  std::unique_ptr<simdjson::dom::parser> parser_;
};

class JsonFields {
 public:
  enum class Need { kRequired, kOptional };

  // If `json` is not an object, that is reported once and every field reads as missing.
  JsonFields(JsonElement json, std::string path, std::string_view file, Diagnostics& diagnostics);

  std::optional<double> number(std::string_view key, Need need = Need::kRequired);
  // A whole number from 0 to `max` (a count, an index); `max` at most 2^53, which a double holds
  // exactly.
  std::optional<std::uint64_t> count(std::string_view key, std::uint64_t max,
                                     Need need = Need::kRequired);
  std::optional<std::string> string(std::string_view key, Need need = Need::kRequired);
  std::optional<bool> boolean(std::string_view key, Need need = Need::kRequired);
  std::optional<JsonArray> array(std::string_view key, Need need = Need::kRequired);
  std::optional<JsonElement> member(std::string_view key, Need need = Need::kRequired);
  bool has(std::string_view key) const;
  // False if the value was not an object (reported when constructed).
  bool is_object() const { return is_object_; }

  // Warns about members not in `known` (likely misspelt), naming each.
  void warn_unknown(std::initializer_list<std::string_view> known);
  void warn_unknown(const std::function<bool(std::string_view)>& is_known);
  // An error for each member not in `known`: for files sewerplan writes and reads back itself
  // (learnt knowledge), where an unknown member means the file is not what it claims.
  void reject_unknown(std::initializer_list<std::string_view> known);

  // A problem the caller found with the field `key` (empty: with the object), at where(key).
  void error(std::string_view key, const std::string& message);

  // "file:$.path.key"
  std::string where(std::string_view key = {}) const;
  const std::string& path() const { return path_; }
  Diagnostics& diagnostics() { return diagnostics_; }

 private:
  std::optional<JsonElement> find(std::string_view key, Need need);
  void report_duplicate_keys();
  void wrong_type(std::string_view key, std::string_view expected, JsonElement got);

  simdjson::dom::object object_;
  bool is_object_ = false;
  std::string path_;
  std::string_view file_;
  Diagnostics& diagnostics_;
};

// Every key given twice in one object anywhere in `json` (at JSON path `path` of `file`), reported
// as JsonFields reports one ("file:$.a[2].b: field 'b' given twice in one object: ..."), in the
// text's order: the first `max_named` by name, the rest counted in one more error. For a text
// refused whole if any key is repeated, before its parts are read (a request's body: a repeat
// inside a part no reader looks at is still found). The number of repeats.
std::size_t report_repeated_keys(JsonElement json, const std::string& path, std::string_view file,
                                 Diagnostics& diagnostics, std::size_t max_named);

// An array element that must be a string (a name), else an error at `where`.
std::optional<std::string> string_element(JsonElement element, const std::string& where,
                                          Diagnostics& diagnostics);

// A JSON value as it would be written, for messages: "7.5", "\"7.5\"", "an object".
std::string describe_json(JsonElement element);

// Shortest text that reads back as exactly `v` (std::to_chars).
std::string format_double(double v);

// "path[i]": the JSON path of an array's element, for diagnostics.
inline std::string indexed(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

}  // namespace sewerplan
