// SPDX-License-Identifier: MIT
#include "sewerplan/core/json_fields.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "sewerplan/core/message_text.h"

namespace sewerplan {
namespace {

// A number of the text that no double holds (1e999: beyond 1.8e308), as `token` at byte `offset`.
struct OutOfRangeNumber {
  std::size_t offset = 0;
  std::string_view token;
};

// The first number outside a string that is too large for a double. A well-formed document with one
// is refused by both parsers in their own words and without a place (nlohmann: "number overflow
// parsing '1e999'"; simdjson: "Problem while parsing a number"); this finds it to say where.
std::optional<OutOfRangeNumber> find_out_of_range_number(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '"') {  // skip the string, escapes included
      for (++i; i < text.size() && text[i] != '"'; ++i) {
        if (text[i] == '\\') ++i;
      }
      ++i;
      continue;
    }
    if (c != '-' && (c < '0' || c > '9')) {
      ++i;
      continue;
    }
    const std::size_t start = i;
    while (i < text.size() &&
           (std::string_view("0123456789+-.eE").find(text[i]) != std::string_view::npos)) {
      ++i;
    }
    const std::string token(text.substr(start, i - start));
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    if (end == token.c_str() + token.size() && std::isinf(v)) {
      return OutOfRangeNumber{start, text.substr(start, i - start)};
    }
  }
  return std::nullopt;
}

// "file:line:column" of byte `offset` (0-based) of `text`.
std::string place_of(std::string_view text, std::string_view file, std::size_t offset) {
  const std::string_view before = text.substr(0, std::min(offset, text.size()));
  const auto line = 1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
  const std::size_t line_start = before.rfind('\n');
  const std::size_t column =
      line_start == std::string_view::npos ? offset + 1 : offset - line_start;
  return std::string(file) + ":" + std::to_string(line) + ":" + std::to_string(column);
}

// The offset of the first '[' or '{' outside a string that opens a level beyond `max_depth`.
std::optional<std::size_t> find_too_deep(std::string_view text, std::size_t max_depth) {
  std::size_t depth = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"') {  // skip the string, escapes included
      for (++i; i < text.size() && text[i] != '"'; ++i) {
        if (text[i] == '\\') ++i;
      }
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) return i;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return std::nullopt;
}

std::string too_deep(std::size_t max_depth) {
  return "the JSON nests arrays and objects more than " + std::to_string(max_depth) +
         " levels deep";
}

// simdjson's errors for a document nlohmann reads, in our words. None of them names a place.
std::string describe_simdjson_error(simdjson::error_code error, std::size_t max_depth) {
  switch (error) {
    case simdjson::DEPTH_ERROR:
      return too_deep(max_depth);
    case simdjson::NUMBER_ERROR:
      return "a number sewerplan cannot read (beyond the range of a double)";
    case simdjson::CAPACITY:
      return "the JSON file is larger than the 4 GiB sewerplan reads";
    case simdjson::UTF8_ERROR:
      return "the JSON text is not valid UTF-8";
    case simdjson::UNESCAPED_CHARS:
      return "a string holds a control character (such as a line break or a NUL) that JSON "
             "allows only escaped";
    default:
      return "not valid JSON (" + std::string(simdjson::error_message(error)) + ")";
  }
}

// A number token short enough to read in a message: its first and last digits around the count
// of those left out ("1444444444...4444 (400 characters)").
std::string abbreviated_number(std::string_view token) {
  constexpr std::size_t kShown = 24;
  if (token.size() <= kShown) return input_text(token);
  return input_text(token.substr(0, 12)) + "..." + input_text(token.substr(token.size() - 8)) +
         " (" + std::to_string(token.size()) + " characters)";
}

// simdjson does not say where a syntax error is; nlohmann does. Used only on the error path.
void report_syntax_error(std::string_view text, std::string_view file, simdjson::error_code error,
                         std::size_t max_depth, Diagnostics& diagnostics) {
  // Before nlohmann is asked: a text of a million '[', closed or not, is refused for its depth
  // here, without building anything.
  if (const std::optional<std::size_t> offset = find_too_deep(text, max_depth)) {
    diagnostics.error(place_of(text, file, *offset), too_deep(max_depth));
    return;
  }
  if (const std::optional<OutOfRangeNumber> n = find_out_of_range_number(text)) {
    diagnostics.error(place_of(text, file, n->offset),
                      "number " + abbreviated_number(n->token) +
                          " is out of range: no number beyond about 1.8e308 can be read");
    return;
  }
  try {
    [[maybe_unused]] const nlohmann::json parsed = nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    report_json_syntax_error(text, file, e.byte, e.what(), diagnostics);
    return;
  } catch (const std::exception&) {
    // Refused for a reason other than syntax: simdjson's reason, in our words, below.
  }
  diagnostics.error(std::string(file), describe_simdjson_error(error, max_depth));
}

// A UTF-8 byte order mark (Windows editors write one) starts no JSON value; simdjson would call it
// a syntax error where nlohmann, which locates errors, skips it and finds none.
std::string_view without_bom(std::string_view text) {
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  return text;
}

}  // namespace

std::optional<JsonDocument> JsonDocument::parse(std::string_view text, std::string_view file,
                                                Diagnostics& diagnostics, std::size_t max_depth) {
  const std::string_view full = text;
  text = without_bom(text);
  JsonDocument doc;
  doc.parser_ = std::make_unique<simdjson::dom::parser>();
  // simdjson counts the document as a level of its own: max_depth + 1 lets max_depth levels of
  // arrays and objects through. Capacity grows as parse() needs it, keeping the depth set here.
  simdjson::error_code error =
      doc.parser_->allocate(std::max<std::size_t>(text.size(), 1), max_depth + 1);
  if (error == simdjson::SUCCESS) {
    error = doc.parser_->parse(text.data(), text.size()).get(doc.root_);
  }
  if (error != simdjson::SUCCESS) {
    report_syntax_error(full, file, error, max_depth, diagnostics);
    return std::nullopt;
  }
  return doc;
}

JsonLineParser::JsonLineParser() : parser_(std::make_unique<simdjson::dom::parser>()) {}

std::optional<JsonElement> JsonLineParser::parse(std::string_view text) {
  text = without_bom(text);
  JsonElement root;
  if (parser_->parse(text.data(), text.size()).get(root) != simdjson::SUCCESS) return std::nullopt;
  return root;
}

JsonFields::JsonFields(JsonElement json, std::string path, std::string_view file,
                       Diagnostics& diagnostics)
    : path_(std::move(path)), file_(file), diagnostics_(diagnostics) {
  is_object_ = json.get_object().get(object_) == simdjson::SUCCESS;
  if (!is_object_) {
    diagnostics_.error(where(), "expected an object, got " + describe_json(json));
    return;
  }
  report_duplicate_keys();
}

namespace {

// The members of `object` whose key an earlier member has: position and key, in the object's
// order. Most objects have a handful of members, compared pairwise; a large one (a dictionary) is
// sorted instead.
std::vector<std::pair<std::size_t, std::string_view>> repeated_keys(simdjson::dom::object object) {
  constexpr std::size_t kPairwise = 16;
  std::vector<std::pair<std::size_t, std::string_view>> repeated;  // position, key: the 2nd, 3rd..
  std::array<std::string_view, kPairwise> small;
  std::vector<std::pair<std::string_view, std::size_t>> large;  // key, position
  std::size_t n = 0;
  for (simdjson::dom::key_value_pair field : object) {
    if (n < kPairwise) small[n] = field.key;
    if (n == kPairwise) {
      for (std::size_t i = 0; i < kPairwise; ++i) large.emplace_back(small[i], i);
    }
    if (n >= kPairwise) large.emplace_back(field.key, n);
    ++n;
  }
  if (n <= kPairwise) {
    for (std::size_t i = 1; i < n; ++i) {
      if (std::find(small.begin(), small.begin() + i, small[i]) != small.begin() + i) {
        repeated.emplace_back(i, small[i]);
      }
    }
  } else {
    std::sort(large.begin(), large.end());  // equal keys together, each run in the object's order
    for (std::size_t i = 1; i < large.size(); ++i) {
      if (large[i].first == large[i - 1].first)
        repeated.emplace_back(large[i].second, large[i].first);
    }
    std::sort(repeated.begin(), repeated.end());  // in the object's order
  }
  return repeated;
}

std::string repeated_key_message(std::string_view key) {
  return "field " + input_quoted(key) +
         " given twice in one object: which value is meant is unclear";
}

// report_repeated_keys' walk; `path` is extended and restored in place.
struct RepeatedKeyWalk {
  std::string_view file;
  Diagnostics& diagnostics;
  std::size_t max_named = 0;
  std::size_t found = 0;

  void walk(JsonElement json, std::string& path) {
    const std::size_t length = path.size();
    simdjson::dom::object object;
    simdjson::dom::array array;
    if (json.get_object().get(object) == simdjson::SUCCESS) {
      const auto repeated = repeated_keys(object);
      std::size_t position = 0;
      auto next = repeated.begin();
      for (simdjson::dom::key_value_pair field : object) {
        path += '.';
        path += input_text(field.key);
        if (next != repeated.end() && next->first == position) {
          ++next;
          if (++found <= max_named) {
            diagnostics.error(std::string(file) + ":" + path, repeated_key_message(field.key));
          }
        }
        walk(field.value, path);
        path.resize(length);
        ++position;
      }
    } else if (json.get_array().get(array) == simdjson::SUCCESS) {
      std::size_t i = 0;
      for (JsonElement element : array) {
        path += '[' + std::to_string(i++) + ']';
        walk(element, path);
        path.resize(length);
      }
    }
  }
};

}  // namespace

// simdjson finds a key's first occurrence, so a second one would be silently ignored; which of the
// two the writer meant cannot be known, so it is an error.
void JsonFields::report_duplicate_keys() {
  for (const auto& [position, key] : repeated_keys(object_)) {
    diagnostics_.error(where(key), repeated_key_message(key));
  }
}

std::size_t report_repeated_keys(JsonElement json, const std::string& path, std::string_view file,
                                 Diagnostics& diagnostics, std::size_t max_named) {
  RepeatedKeyWalk walk{file, diagnostics, max_named};
  std::string where = path;
  walk.walk(json, where);
  if (walk.found > max_named) {
    diagnostics.error(std::string(file),
                      "(" + std::to_string(walk.found - max_named) + " more fields given twice)");
  }
  return walk.found;
}

std::string JsonFields::where(std::string_view key) const {
  std::string w(file_);
  w += ':';
  w += path_;
  if (!key.empty()) {
    w += '.';
    w += input_text(key);  // a key of the file's may hold anything
  }
  return w;
}

void JsonFields::error(std::string_view key, const std::string& message) {
  diagnostics_.error(where(key), message);
}

bool JsonFields::has(std::string_view key) const {
  JsonElement unused;
  return is_object_ && object_.at_key(key).get(unused) == simdjson::SUCCESS;
}

std::optional<JsonElement> JsonFields::find(std::string_view key, Need need) {
  if (!is_object_) return std::nullopt;
  JsonElement value;
  if (object_.at_key(key).get(value) != simdjson::SUCCESS) {
    if (need == Need::kRequired) {
      diagnostics_.error(where(), "missing required field '" + std::string(key) + "'");
    }
    return std::nullopt;
  }
  return value;
}

void JsonFields::wrong_type(std::string_view key, std::string_view expected, JsonElement got) {
  diagnostics_.error(where(key),
                     "expected " + std::string(expected) + ", got " + describe_json(got));
}

std::optional<double> JsonFields::number(std::string_view key, Need need) {
  auto v = find(key, need);
  if (!v) return std::nullopt;
  double d = 0;
  if (!v->is_number() || v->get_double().get(d) != simdjson::SUCCESS) {
    wrong_type(key, "a number", *v);
    return std::nullopt;
  }
  return d;
}

std::optional<std::uint64_t> JsonFields::count(std::string_view key, std::uint64_t max, Need need) {
  const std::optional<JsonElement> v = find(key, need);
  if (!v) return std::nullopt;
  std::uint64_t whole = 0;
  double d = 0;
  if (v->get_uint64().get(whole) == simdjson::SUCCESS) {  // exact, also beyond 2^53
    if (whole <= max) return whole;
  } else if (v->is_number() && v->get_double().get(d) == simdjson::SUCCESS && d >= 0 &&
             d <= static_cast<double>(max) && std::floor(d) == d) {
    return static_cast<std::uint64_t>(d);  // 3.0 or 1e2
  }
  if (!v->is_number()) {
    wrong_type(key, "a whole number", *v);
  } else {
    error(key, "expected a whole number from 0 to " + std::to_string(max) + ", got " +
                   describe_json(*v));
  }
  return std::nullopt;
}

std::optional<std::string> JsonFields::string(std::string_view key, Need need) {
  auto v = find(key, need);
  if (!v) return std::nullopt;
  std::string_view s;
  if (v->get_string().get(s) != simdjson::SUCCESS) {
    wrong_type(key, "a string", *v);
    return std::nullopt;
  }
  return std::string(s);
}

std::optional<bool> JsonFields::boolean(std::string_view key, Need need) {
  auto v = find(key, need);
  if (!v) return std::nullopt;
  bool b = false;
  if (v->get_bool().get(b) != simdjson::SUCCESS) {
    wrong_type(key, "true or false", *v);
    return std::nullopt;
  }
  return b;
}

std::optional<JsonArray> JsonFields::array(std::string_view key, Need need) {
  auto v = find(key, need);
  if (!v) return std::nullopt;
  JsonArray a;
  if (v->get_array().get(a) != simdjson::SUCCESS) {
    wrong_type(key, "an array", *v);
    return std::nullopt;
  }
  return a;
}

std::optional<JsonElement> JsonFields::member(std::string_view key, Need need) {
  return find(key, need);
}

void JsonFields::warn_unknown(std::initializer_list<std::string_view> known) {
  warn_unknown([known](std::string_view key) {
    return std::find(known.begin(), known.end(), key) != known.end();
  });
}

void JsonFields::warn_unknown(const std::function<bool(std::string_view)>& is_known) {
  if (!is_object_) return;
  for (simdjson::dom::key_value_pair field : object_) {
    if (!is_known(field.key)) {
      diagnostics_.warning(where(field.key),
                           "unknown field " + input_quoted(field.key) + " ignored");
    }
  }
}

// Names the unknown member and the fields known: "unknown field 'seeed' (expected mission, faults,
// random_faults)". For files sewerplan writes itself and for input where a misspelt field must not
// leave its default without a word: a mission, a request's body (the station's).
void JsonFields::reject_unknown(std::initializer_list<std::string_view> known) {
  if (!is_object_) return;
  std::string expected;
  for (const std::string_view key : known) {
    expected += (expected.empty() ? " (expected " : ", ") + std::string(key);
  }
  if (!expected.empty()) expected += ")";
  for (simdjson::dom::key_value_pair field : object_) {
    if (std::find(known.begin(), known.end(), field.key) == known.end()) {
      diagnostics_.error(where(field.key), "unknown field " + input_quoted(field.key) + expected);
    }
  }
}

std::optional<std::string> string_element(JsonElement element, const std::string& where,
                                          Diagnostics& diagnostics) {
  std::string_view s;
  if (element.get_string().get(s) != simdjson::SUCCESS) {
    diagnostics.error(where, "expected a name (a string), got " + describe_json(element));
    return std::nullopt;
  }
  return std::string(s);
}

std::string describe_json(JsonElement element) {
  switch (element.type()) {
    case simdjson::dom::element_type::ARRAY:
      return "an array";
    case simdjson::dom::element_type::OBJECT:
      return "an object";
    case simdjson::dom::element_type::NULL_VALUE:
      return "null";
    case simdjson::dom::element_type::BOOL:
    case simdjson::dom::element_type::INT64:
    case simdjson::dom::element_type::UINT64:
    case simdjson::dom::element_type::DOUBLE:
    case simdjson::dom::element_type::STRING:
      return simdjson::minify(element);
  }
  return "a value";
}

std::string format_double(double v) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, end);
}

}  // namespace sewerplan
