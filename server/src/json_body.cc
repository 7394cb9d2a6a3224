// SPDX-License-Identifier: MIT
#include "json_body.h"

#include <cstddef>
#include <set>
#include <string>
#include <vector>

namespace sewerplan::server {
namespace {

// A body nested deeper is refused before it is read: each level costs a frame here and in the
// document, and no request of the API nests more than a few levels.
constexpr std::size_t kMaxDepth = 256;
// The repeats named; the rest are counted. A body of repeated keys could otherwise be answered
// with many times its size.
constexpr std::size_t kMaxNamed = 20;

// A SAX pass that only follows the JSON path and notes each key seen twice in one object.
class RepeatedKeys : public nlohmann::json_sax<Json> {
 public:
  std::string messages;     // one line each, at most kMaxNamed
  std::size_t repeats = 0;  // all of them
  std::string syntax;       // why the text is not read, if it is not

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(false); }
  bool key(string_t& key) override {
    Frame& f = frames_.back();
    f.key = key;
    if (!f.seen.insert(key).second && ++repeats <= kMaxNamed) {
      messages += path() + ": error: field '" + key +
                  "' given twice in one object: which value is meant is unclear\n";
    }
    return true;
  }
  bool end_object() override { return end(); }
  bool start_array(std::size_t) override { return open(true); }
  bool end_array() override { return end(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    // "[json.exception.parse_error.101] parse error at line 1, column 9: ...": without the tag.
    const std::string what = e.what();
    const std::size_t tag_end = what.find("] ");
    syntax =
        "the body is not JSON: " + (tag_end == std::string::npos ? what : what.substr(tag_end + 2));
    return false;
  }

 private:
  struct Frame {
    bool array = false;
    std::size_t index = 0;       // the element being read, in an array
    std::string key;             // the member being read, in an object
    std::set<std::string> seen;  // the object's keys so far
  };

  bool open(bool array) {
    if (frames_.size() >= kMaxDepth) {
      syntax = "the body is nested deeper than " + std::to_string(kMaxDepth) + " levels";
      return false;
    }
    frames_.push_back({.array = array});
    return true;
  }
  // A whole value was read: the next element of an enclosing array.
  bool value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
    return true;
  }
  bool end() {
    frames_.pop_back();
    return value();
  }
  std::string path() const {
    std::string p = "$";
    for (const Frame& f : frames_) {
      p += f.array ? "[" + std::to_string(f.index) + "]" : "." + f.key;
    }
    return p;
  }

  std::vector<Frame> frames_;
};

}  // namespace

Result<Json> parse_json_body(std::string_view text) {
  RepeatedKeys keys;
  if (!Json::sax_parse(text, &keys)) {
    return Error{ErrorCode::kParse, keys.syntax};
  }
  if (keys.repeats > 0) {
    if (keys.repeats > kMaxNamed) {
      keys.messages += "(" + std::to_string(keys.repeats - kMaxNamed) + " more fields given twice)";
    } else {
      keys.messages.pop_back();  // the last newline
    }
    return Error{ErrorCode::kParse, keys.messages};
  }
  return Json::parse(text);  // the same text, well-formed: it does not throw
}

}  // namespace sewerplan::server
