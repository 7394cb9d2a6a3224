// SPDX-License-Identifier: MIT
// The reader of the ASCII sewer database; the writer is in map_ascii_writer.cc.
#include "sewerplan/core/map_ascii.h"

#include <array>
#include <bitset>
#include <filesystem>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "sewerplan/core/map_builder.h"

#include "ascii_syntax.h"

namespace sewerplan {
namespace {

using ascii_syntax::quoted;

// One key a line type accepts. A flag is a bare token ("exit"); every other key is key=value.
struct KeySpec {
  std::string_view key;
  bool required = false;
  bool flag = false;
};

constexpr std::array kManholeKeys{KeySpec{.key = "x"},
                                  KeySpec{.key = "y"},
                                  KeySpec{.key = "z"},
                                  KeySpec{.key = "diameter", .required = true},
                                  KeySpec{.key = "exit", .flag = true},
                                  KeySpec{.key = "variant"},
                                  KeySpec{.key = "shaft_length"},
                                  KeySpec{.key = "shaft_width"},
                                  KeySpec{.key = "depth"}};
constexpr std::array kSlotKeys{KeySpec{.key = "azimuth", .required = true},
                               KeySpec{.key = "invert"}};
constexpr std::array kPipeKeys{KeySpec{.key = "from", .required = true},
                               KeySpec{.key = "to", .required = true},
                               KeySpec{.key = "length", .required = true},
                               KeySpec{.key = "diameter", .required = true},
                               KeySpec{.key = "shape"},
                               KeySpec{.key = "height"},
                               KeySpec{.key = "risk"}};
constexpr std::array kPointKeys{KeySpec{.key = "pipe", .required = true},
                                KeySpec{.key = "offset", .required = true}};

constexpr std::size_t kMaxKeys = 10;
static_assert(kPipeKeys.size() <= kMaxKeys && kManholeKeys.size() <= kMaxKeys);

// The keys given on one line. A key is `seen` once mentioned, even if its value was rejected, so
// that a bad value is not also reported as a missing key.
class Fields {
 public:
  explicit Fields(std::span<const KeySpec> specs) : specs_(specs) {}

  std::span<const KeySpec> specs() const { return specs_; }
  std::optional<std::size_t> find(std::string_view key) const {
    for (std::size_t i = 0; i < specs_.size(); ++i) {
      if (specs_[i].key == key) return i;
    }
    return std::nullopt;
  }
  bool seen(std::size_t i) const { return seen_[i]; }
  void set(std::size_t i, std::optional<std::string_view> value) {
    seen_[i] = true;
    values_[i] = value;
  }
  // The value of `key`, which must be one of the specs; a flag's value is empty.
  std::optional<std::string_view> value(std::string_view key) const {
    const std::optional<std::size_t> i = find(key);
    return i ? values_[*i] : std::nullopt;
  }

 private:
  std::span<const KeySpec> specs_;
  std::array<std::optional<std::string_view>, kMaxKeys> values_{};
  std::bitset<kMaxKeys> seen_;
};

// An object line's name and the tokens after it.
struct Head {
  std::optional<std::string_view> name;
  std::span<const std::string_view> rest;
};

bool is_object_keyword(std::string_view keyword) {
  return keyword == "map" || keyword == "manhole" || keyword == "slot" || keyword == "pipe" ||
         keyword == "point";
}

class AsciiReader {
 public:
  AsciiReader(const std::string& file_name, Diagnostics& diagnostics)
      : file_(file_name), d_(diagnostics) {}

  Result<SewerMap> run(std::string_view text);

 private:
  // False if the rest of the file should not be read.
  bool read_first_line(std::span<const std::string_view> tokens);
  void read_line(std::span<const std::string_view> tokens);
  void read_map_line(std::span<const std::string_view> tokens);
  void read_manhole(std::span<const std::string_view> tokens);
  void read_slot(std::span<const std::string_view> tokens);
  void read_pipe(std::span<const std::string_view> tokens);
  void read_point(std::span<const std::string_view> tokens);
  Result<SewerMap> build();

  Head read_head(std::span<const std::string_view> tokens, const std::string& label);
  Fields read_fields(std::span<const KeySpec> specs, std::span<const std::string_view> tokens);
  void read_field(Fields& fields, std::string_view token);
  template <class T>
  T number_or(const Fields& fields, std::string_view key, T fallback);
  std::optional<std::string> end_or_blind(const Fields& fields, std::string_view key);

  std::string where() const { return file_ + ":" + std::to_string(line_); }
  // Reports a syntax error on the current line, about the current object.
  void error(const std::string& message) {
    ++syntax_errors_;
    d_.error(where(), object_.empty() ? message : object_ + ": " + message);
  }

  const std::string& file_;
  Diagnostics& d_;
  Diagnostics::Mark before_ = d_.mark();  // problems reported before this file are the caller's
  std::uint32_t line_ = 0;
  std::string object_;  // "pipe P5": the object of the current line, for messages
  std::size_t syntax_errors_ = 0;
  std::optional<std::uint32_t> map_line_;
  std::string map_name_;
  bool objects_seen_ = false;
  std::vector<ManholeRecord> manholes_;
  std::vector<PipeRecord> pipes_;
  std::vector<PointRecord> points_;
};

Result<SewerMap> AsciiReader::run(std::string_view text) {
  ascii_syntax::LineReader lines(text);
  std::vector<std::string_view> tokens;
  bool header_seen = false;
  for (std::string_view line; lines.next(line);) {
    line_ = lines.line_number();
    object_.clear();
    ascii_syntax::tokenize(line, tokens);
    if (tokens.empty()) continue;
    if (!header_seen) {
      header_seen = true;
      if (!read_first_line(tokens)) break;
      if (tokens[0] == ascii_syntax::kHeaderKeyword) continue;
    }
    read_line(tokens);
  }
  if (!header_seen) {
    ++syntax_errors_;
    d_.error(file_, "missing header 'sewerdb 1': the file has no content");
  }
  if (syntax_errors_ > 0) return Error{ErrorCode::kParse, d_.error_summary(before_)};
  return build();
}

bool AsciiReader::read_first_line(std::span<const std::string_view> tokens) {
  if (tokens[0] != ascii_syntax::kHeaderKeyword) {
    error("missing header: the first line must be 'sewerdb 1'");
    // A file starting with something else altogether is not a sewerdb file: stop there.
    return is_object_keyword(tokens[0]);
  }
  object_ = "sewerdb";
  if (tokens.size() < 2) {
    error("missing format version (expected 'sewerdb 1')");
    return true;
  }
  if (tokens[1] != ascii_syntax::kFormatVersion) {
    object_.clear();
    error("unsupported sewerdb version " + std::string(tokens[1].substr(0, 40)) +
          ", this reader knows version " + std::string(ascii_syntax::kFormatVersion));
    return false;  // its lines may mean something else in that version
  }
  for (std::string_view extra : tokens.subspan(2)) error("unexpected token " + quoted(extra));
  return true;
}

void AsciiReader::read_line(std::span<const std::string_view> tokens) {
  const std::string_view keyword = tokens[0];
  if (keyword == "map") {
    read_map_line(tokens);
  } else if (keyword == "manhole") {
    read_manhole(tokens);
  } else if (keyword == "slot") {
    read_slot(tokens);
  } else if (keyword == "pipe") {
    read_pipe(tokens);
  } else if (keyword == "point") {
    read_point(tokens);
  } else if (keyword == ascii_syntax::kHeaderKeyword) {
    error("the header 'sewerdb 1' may only be the first line");
  } else {
    error("unknown keyword " + quoted(keyword) + " (expected map, manhole, slot, pipe or point)");
  }
}

Head AsciiReader::read_head(std::span<const std::string_view> tokens, const std::string& label) {
  object_ = label;
  if (tokens.size() < 2 || tokens[1].find('=') != std::string_view::npos) {
    error("missing name (expected '" + std::string(tokens[0]) + " NAME ...')");
    return {std::nullopt, tokens.subspan(1)};
  }
  object_ = label + " " + std::string(tokens[1]);
  return {tokens[1], tokens.subspan(2)};
}

void AsciiReader::read_map_line(std::span<const std::string_view> tokens) {
  const Head head = read_head(tokens, "map");
  if (map_line_) {
    error("the map name is given twice (first at " + file_ + ":" + std::to_string(*map_line_) +
          ")");
  } else if (objects_seen_) {
    error("the map name must come before the first manhole, pipe or point");
  }
  if (!head.name) return;
  for (std::string_view extra : head.rest) error("unexpected token " + quoted(extra));
  if (const std::string_view problem = ascii_syntax::name_problem(*head.name); !problem.empty()) {
    error("the name cannot be read: " + std::string(problem));
  }
  if (!map_line_) {
    map_line_ = line_;
    map_name_ = std::string(*head.name);
  }
}

void AsciiReader::read_manhole(std::span<const std::string_view> tokens) {
  objects_seen_ = true;
  const Head head = read_head(tokens, "manhole");
  const Fields fields = read_fields(kManholeKeys, head.rest);
  ManholeRecord record;
  record.name = std::string(head.name.value_or(""));
  record.line = line_;
  if (head.name == ascii_syntax::kBlindEnd) {
    error("the name '-' is reserved for blind pipe ends");
  }
  record.position = {number_or(fields, "x", 0.0), number_or(fields, "y", 0.0),
                     number_or(fields, "z", 0.0)};
  record.diameter_m = number_or(fields, "diameter", 0.0);
  record.exit = fields.value("exit").has_value();
  if (fields.value("shaft_length")) record.shaft_length_m = number_or(fields, "shaft_length", 0.0);
  if (fields.value("shaft_width")) record.shaft_width_m = number_or(fields, "shaft_width", 0.0);
  if (fields.value("depth")) record.depth_m = number_or(fields, "depth", 0.0);
  if (const std::optional<std::string_view> variant = fields.value("variant")) {
    if (variant->size() == 1 && (*variant)[0] >= 'A' && (*variant)[0] <= 'Z') {
      record.variant = (*variant)[0];
    } else {
      error("variant must be one capital letter A..Z, got " + quoted(*variant));
    }
  }
  manholes_.push_back(std::move(record));
}

void AsciiReader::read_slot(std::span<const std::string_view> tokens) {
  objects_seen_ = true;
  const std::string label =
      manholes_.empty()
          ? std::string("slot")
          : "manhole " +
                (manholes_.back().name.empty() ? std::string("(unnamed)") : manholes_.back().name) +
                " slot";
  const Head head = read_head(tokens, label);
  const Fields fields = read_fields(kSlotKeys, head.rest);
  if (manholes_.empty()) {
    error("comes before any manhole line (a slot belongs to the manhole line above it)");
    return;
  }
  ManholeRecord& manhole = manholes_.back();
  SlotRecord slot;
  slot.pipe = std::string(head.name.value_or(""));
  slot.azimuth_deg = number_or(fields, "azimuth", 0.0);
  slot.invert_z_m = number_or(fields, "invert", manhole.position.z_m);
  slot.line = line_;
  manhole.slots.push_back(std::move(slot));
}

void AsciiReader::read_pipe(std::span<const std::string_view> tokens) {
  objects_seen_ = true;
  const Head head = read_head(tokens, "pipe");
  const Fields fields = read_fields(kPipeKeys, head.rest);
  PipeRecord record;
  record.name = std::string(head.name.value_or(""));
  record.line = line_;
  record.from = end_or_blind(fields, "from");
  record.to = end_or_blind(fields, "to");
  record.length_m = number_or(fields, "length", 0.0);
  record.diameter_m = number_or(fields, "diameter", 0.0);
  if (const std::optional<std::string_view> shape = fields.value("shape")) {
    if (const std::optional<PipeShape> parsed = pipe_shape_from_string(*shape)) {
      record.shape = *parsed;
    } else {
      error("unknown shape " + quoted(*shape) + " (expected " + pipe_shape_names() + ")");
    }
  }
  if (fields.value("height")) record.height_m = number_or(fields, "height", 0.0);
  if (fields.value("risk")) record.blockage_risk = number_or(fields, "risk", 0.0F);
  pipes_.push_back(std::move(record));
}

void AsciiReader::read_point(std::span<const std::string_view> tokens) {
  objects_seen_ = true;
  const Head head = read_head(tokens, "point");
  const Fields fields = read_fields(kPointKeys, head.rest);
  PointRecord record;
  record.name = std::string(head.name.value_or(""));
  record.line = line_;
  record.pipe = std::string(fields.value("pipe").value_or(""));
  record.offset_m = number_or(fields, "offset", 0.0);
  points_.push_back(std::move(record));
}

Fields AsciiReader::read_fields(std::span<const KeySpec> specs,
                                std::span<const std::string_view> tokens) {
  Fields fields(specs);
  for (std::string_view token : tokens) read_field(fields, token);
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (specs[i].required && !fields.seen(i)) {
      error("missing required key '" + std::string(specs[i].key) + "'");
    }
  }
  return fields;
}

void AsciiReader::read_field(Fields& fields, std::string_view token) {
  const std::size_t eq = token.find('=');
  const bool has_value = eq != std::string_view::npos;
  const std::string_view key = token.substr(0, eq);
  const std::optional<std::size_t> index = key.empty() ? std::nullopt : fields.find(key);
  if (!index) {
    error(has_value && !key.empty() ? "unknown key " + quoted(key)
                                    : "unexpected token " + quoted(token));
    return;
  }
  const KeySpec& spec = fields.specs()[*index];
  const std::string name(key);
  if (fields.seen(*index)) {
    error("key '" + name + "' is given twice");
  } else if (spec.flag && has_value) {
    error("'" + name + "' is a flag and takes no value");
    fields.set(*index, std::nullopt);
  } else if (!spec.flag && !has_value) {
    error("key '" + name + "' needs a value (" + name + "=...)");
    fields.set(*index, std::nullopt);
  } else if (has_value && eq + 1 == token.size()) {
    error("empty value for key '" + name + "'");
    fields.set(*index, std::nullopt);
  } else {
    fields.set(*index, has_value ? token.substr(eq + 1) : std::string_view());
  }
}

template <class T>
T AsciiReader::number_or(const Fields& fields, std::string_view key, T fallback) {
  const std::optional<std::string_view> text = fields.value(key);
  if (!text) return fallback;
  T value = fallback;
  std::string_view problem;
  switch (ascii_syntax::parse_number(*text, value)) {
    case ascii_syntax::NumberError::kNone:
      return value;
    case ascii_syntax::NumberError::kNotANumber:
      problem = " is not a number";
      break;
    case ascii_syntax::NumberError::kNotFinite:
      problem = " is not a finite number";
      break;
    case ascii_syntax::NumberError::kOutOfRange:
      problem = " is out of range";
      break;
  }
  error(std::string(key) + " " + quoted(*text) + std::string(problem));
  return fallback;
}

std::optional<std::string> AsciiReader::end_or_blind(const Fields& fields, std::string_view key) {
  const std::optional<std::string_view> end = fields.value(key);
  if (!end || *end == ascii_syntax::kBlindEnd) return std::nullopt;
  return std::string(*end);
}

Result<SewerMap> AsciiReader::build() {
  std::string name =
      map_line_ ? std::move(map_name_) : std::filesystem::path(file_).stem().string();
  MapBuilder builder(std::move(name), line_locator(file_));
  builder.reserve(manholes_.size(), pipes_.size());
  for (ManholeRecord& record : manholes_) builder.add_manhole(std::move(record));
  for (PipeRecord& record : pipes_) builder.add_pipe(std::move(record));
  for (PointRecord& record : points_) builder.add_point(std::move(record));
  return std::move(builder).build(d_);
}

}  // namespace

Result<SewerMap> read_map_ascii(std::string_view text, const std::string& file_name,
                                Diagnostics& diagnostics) {
  return AsciiReader(file_name, diagnostics).run(text);
}

}  // namespace sewerplan
