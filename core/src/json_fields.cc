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

// simdjson's errors for a document nlohmann reads, in our words. None of them names a place.
std::string describe_simdjson_error(simdjson::error_code error) {
  switch (error) {
    case simdjson::DEPTH_ERROR:
      return "the JSON nests arrays and objects more than " +
             std::to_string(simdjson::DEFAULT_MAX_DEPTH) + " levels deep";
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
                         Diagnostics& diagnostics) {
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
  diagnostics.error(std::string(file), describe_simdjson_error(error));
}

// A UTF-8 byte order mark (Windows editors write one) starts no JSON value; simdjson would call it
// a syntax error where nlohmann, which locates errors, skips it and finds none.
std::string_view without_bom(std::string_view text) {
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  return text;
}

}  // namespace

std::optional<JsonDocument> JsonDocument::parse(std::string_view text, std::string_view file,
                                                Diagnostics& diagnostics) {
  const std::string_view full = text;
  text = without_bom(text);
  JsonDocument doc;
  doc.parser_ = std::make_unique<simdjson::dom::parser>();
  const simdjson::error_code error = doc.parser_->parse(text.data(), text.size()).get(doc.root_);
  if (error != simdjson::SUCCESS) {
    report_syntax_error(full, file, error, diagnostics);
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

// simdjson finds a key's first occurrence, so a second one would be silently ignored; which of the
// two the writer meant cannot be known, so it is an error. Most objects have a handful of members,
// compared pairwise; a large one (a dictionary) is sorted instead.
void JsonFields::report_duplicate_keys() {
  constexpr std::size_t kPairwise = 16;
  std::vector<std::pair<std::size_t, std::string_view>> repeated;  // position, key: the 2nd, 3rd..
  std::array<std::string_view, kPairwise> small;
  std::vector<std::pair<std::string_view, std::size_t>> large;  // key, position
  std::size_t n = 0;
  for (simdjson::dom::key_value_pair field : object_) {
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
    std::sort(repeated.begin(), repeated.end());  // reported in the object's order
  }
  for (const auto& [position, key_view] : repeated) {
    const std::string key(key_view);
    diagnostics_.error(where(key), "field " + input_quoted(key) +
                                       " given twice in one object: which value is meant is "
                                       "unclear");
  }
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

void JsonFields::reject_unknown(std::initializer_list<std::string_view> known) {
  if (!is_object_) return;
  for (simdjson::dom::key_value_pair field : object_) {
    if (std::find(known.begin(), known.end(), field.key) == known.end()) {
      diagnostics_.error(where(field.key), "unknown field " + input_quoted(field.key));
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
