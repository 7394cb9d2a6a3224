// SPDX-License-Identifier: MIT
#include "sewerplan/core/map_json.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <nlohmann/json.hpp>

#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/map_builder.h"
#include "sewerplan/core/message_text.h"

#include "json_scan.h"
#include "map_json_fast.h"

namespace sewerplan {
namespace {

using Need = JsonFields::Need;
using nlohmann::json;

std::string element_path(std::string_view array, std::size_t i) {
  return "$." + std::string(array) + "[" + std::to_string(i) + "]";
}

Locator json_locator(std::string file) {
  return [file = std::move(file)](const RecordRef& ref, std::string_view field) {
    std::string w = file + ":";
    switch (ref.kind) {
      case RecordRef::Kind::kMap:
        w += "$";
        break;
      case RecordRef::Kind::kManhole:
        w += element_path("manholes", ref.index);
        break;
      case RecordRef::Kind::kSlot:
        w += element_path("manholes", ref.index) + ".slots[" + std::to_string(ref.slot_index) + "]";
        break;
      case RecordRef::Kind::kPipe:
        w += element_path("pipes", ref.index);
        break;
      case RecordRef::Kind::kPoint:
        w += element_path("inspection_points", ref.index);
        break;
      case RecordRef::Kind::kFinding:
        w += element_path("findings", ref.index);
        break;
    }
    if (!field.empty()) w += "." + std::string(field);
    return w;
  };
}

std::optional<char> read_variant(JsonFields& f) {
  auto v = f.string("variant", Need::kOptional);
  if (!v) return std::nullopt;
  if (v->size() != 1) {
    f.diagnostics().error(f.where("variant"),
                          "variant must be one capital letter, got " + input_quoted(*v));
    return std::nullopt;
  }
  return (*v)[0];
}

SlotRecord read_slot(JsonElement j, std::string path, std::string_view file, double floor_z,
                     Diagnostics& d) {
  JsonFields f(j, std::move(path), file, d);
  SlotRecord slot;
  slot.pipe = f.string("pipe").value_or("");
  slot.azimuth_deg = f.number("azimuth_deg").value_or(0);
  slot.invert_z_m = f.number("invert_m", Need::kOptional).value_or(floor_z);
  f.warn_unknown({"pipe", "azimuth_deg", "invert_m"});
  return slot;
}

ManholeRecord read_manhole(JsonElement j, std::size_t index, std::string_view file,
                           Diagnostics& d) {
  JsonFields f(j, element_path("manholes", index), file, d);
  ManholeRecord m;
  m.name = f.string("name").value_or("");
  m.position.x_m = f.number("x_m", Need::kOptional).value_or(0);
  m.position.y_m = f.number("y_m", Need::kOptional).value_or(0);
  m.position.z_m = f.number("z_m", Need::kOptional).value_or(0);
  m.diameter_m = f.number("diameter_m").value_or(0);
  m.exit = f.boolean("exit", Need::kOptional).value_or(false);
  m.variant = read_variant(f);
  m.shaft_length_m = f.number("shaft_length_m", Need::kOptional);
  m.shaft_width_m = f.number("shaft_width_m", Need::kOptional);
  m.depth_m = f.number("depth_m", Need::kOptional);
  if (m.shaft_length_m.has_value() != m.shaft_width_m.has_value()) {
    d.error(f.where(m.shaft_length_m ? "shaft_width_m" : "shaft_length_m"),
            "manhole " + m.name + ": shaft_length_m and shaft_width_m come together");
  }
  if (auto slots = f.array("slots", Need::kOptional)) {
    m.slots.reserve(slots->size());
    std::size_t s = 0;
    for (JsonElement slot : *slots) {
      m.slots.push_back(read_slot(slot, f.path() + ".slots[" + std::to_string(s++) + "]", file,
                                  m.position.z_m, d));
    }
  }
  f.warn_unknown({"name", "x_m", "y_m", "z_m", "diameter_m", "exit", "variant", "shaft_length_m",
                  "shaft_width_m", "depth_m", "slots"});
  return m;
}

std::optional<std::string> read_end(JsonFields& f, std::string_view key) {
  auto v = f.member(key);
  if (!v || v->is_null()) return std::nullopt;  // null: a blind end
  std::string_view name;
  if (v->get_string().get(name) != simdjson::SUCCESS) {
    f.diagnostics().error(f.where(key),
                          "expected a manhole name or null, got " + describe_json(*v));
    return std::nullopt;
  }
  return std::string(name);
}

PipeRecord read_pipe(JsonElement j, std::size_t index, std::string_view file, Diagnostics& d) {
  JsonFields f(j, element_path("pipes", index), file, d);
  PipeRecord p;
  p.name = f.string("name").value_or("");
  p.from = read_end(f, "from");
  p.to = read_end(f, "to");
  p.length_m = f.number("length_m").value_or(0);
  p.diameter_m = f.number("diameter_m").value_or(0);
  if (auto shape = f.string("shape", Need::kOptional)) {
    if (auto s = pipe_shape_from_string(*shape)) {
      p.shape = *s;
    } else {
      d.error(f.where("shape"), "pipe " + input_text(p.name) + ": unknown shape " +
                                    input_quoted(*shape) + " (" + pipe_shape_names() + ")");
    }
  }
  p.height_m = f.number("height_m", Need::kOptional);
  if (auto risk = f.number("blockage_risk", Need::kOptional)) {
    p.blockage_risk = static_cast<float>(*risk);
  }
  f.warn_unknown(
      {"name", "from", "to", "length_m", "diameter_m", "shape", "height_m", "blockage_risk"});
  return p;
}

PointRecord read_point(JsonElement j, std::size_t index, std::string_view file, Diagnostics& d) {
  JsonFields f(j, element_path("inspection_points", index), file, d);
  PointRecord p;
  p.name = f.string("name").value_or("");
  p.pipe = f.string("pipe").value_or("");
  p.offset_m = f.number("offset_m").value_or(0);
  f.warn_unknown({"name", "pipe", "offset_m"});
  return p;
}

FindingRecord read_finding(JsonElement j, std::size_t index, std::string_view file,
                           Diagnostics& d) {
  JsonFields f(j, element_path("findings", index), file, d);
  FindingRecord r;
  r.pipe = f.string("pipe").value_or("");
  r.code = f.string("code").value_or("");
  r.characterisation = f.string("characterisation", Need::kOptional).value_or("");
  r.station_m = f.number("offset_m").value_or(0);
  r.quantity1 = f.number("quantity1", Need::kOptional);
  r.quantity2 = f.number("quantity2", Need::kOptional);
  r.line = static_cast<std::uint32_t>(index + 1);
  f.warn_unknown({"pipe", "code", "characterisation", "offset_m", "quantity1", "quantity2"});
  return r;
}

void check_header(JsonFields& f) {
  auto format = f.string("format");
  if (format && *format != kMapJsonFormat) {
    f.diagnostics().error(f.where("format"), "expected \"" + std::string(kMapJsonFormat) +
                                                 "\", got " + input_quoted(*format));
  }
  auto version = f.number("version");
  if (version && *version != kMapJsonVersion) {
    f.diagnostics().error(f.where("version"), "unsupported version " + format_double(*version) +
                                                  ", this reader knows version " +
                                                  std::to_string(kMapJsonVersion));
  }
}

// Names are valid UTF-8 (MapBuilder checks); replace keeps a bad one from throwing all the same.
void write_string(std::ostream& out, const std::string& s) {
  out << json(s).dump(-1, ' ', false, json::error_handler_t::replace);
}

void write_optional(std::ostream& out, std::string_view key, const std::optional<double>& v) {
  if (v) out << ", \"" << key << "\": " << format_double(*v);
}

void write_manhole(std::ostream& out, const SewerMap& map, ManholeId id) {
  const Manhole& m = map.manhole(id);
  out << "    {\"name\": ";
  write_string(out, m.name);
  out << ", \"x_m\": " << format_double(m.position.x_m)
      << ", \"y_m\": " << format_double(m.position.y_m)
      << ", \"z_m\": " << format_double(m.position.z_m)
      << ", \"diameter_m\": " << format_double(m.diameter_m);
  if (m.exit) out << ", \"exit\": true";
  if (m.variant) out << ", \"variant\": \"" << *m.variant << '"';
  write_optional(out, "shaft_length_m", m.shaft_length_m);
  write_optional(out, "shaft_width_m", m.shaft_width_m);
  write_optional(out, "depth_m", m.depth_m);
  out << ",\n     \"slots\": [";
  bool first = true;
  for (const Slot& s : map.slots(id)) {
    out << (first ? "" : ", ") << "{\"pipe\": ";
    write_string(out, map.pipe(s.pipe).name);
    out << ", \"azimuth_deg\": " << format_double(s.azimuth_deg)
        << ", \"invert_m\": " << format_double(s.invert_z_m) << '}';
    first = false;
  }
  out << "]}";
}

void write_pipe(std::ostream& out, const SewerMap& map, const Pipe& p) {
  out << "    {\"name\": ";
  write_string(out, p.name);
  for (std::size_t e = 0; e < 2; ++e) {
    out << (e == 0 ? ", \"from\": " : ", \"to\": ");
    if (p.ends[e].manhole) {
      write_string(out, map.manhole(*p.ends[e].manhole).name);
    } else {
      out << "null";
    }
  }
  out << ", \"length_m\": " << format_double(p.length_m)
      << ", \"diameter_m\": " << format_double(p.diameter_m);
  if (p.shape != PipeShape::kCircular) {
    out << ", \"shape\": \"" << to_string(p.shape)
        << "\", \"height_m\": " << format_double(p.height_m);
  }
  if (p.blockage_risk) out << ", \"blockage_risk\": " << format_double(*p.blockage_risk);
  out << '}';
}

// The fast path: a well-formed map, every field known, of the right type and valid as the
// document reader would find it, read in one pass with JsonScan (json_scan.h) and no document
// tree. Anything else (nullopt) goes to the document reader, which reports it.
class FastReader {
 public:
  FastReader(std::string_view text, const std::string& file_name)
      : scan_(text), file_name_(file_name), builder_("", json_locator(file_name)) {
    // The names are the text's strings, unescaped: they take at most its size.
    builder_.reserve_names(text.size());
  }

  std::optional<MapBuilder> read() && {
    if (!root() || !scan_.at_end() || !format_ || !version_ || !manholes_ || !pipes_) {
      return std::nullopt;
    }
    builder_.set_name(std::string(name_));
    builder_.set_crs(std::move(crs_));
    return std::move(builder_);
  }

 private:
  // Each known field once: a repeated one goes to the document reader (which takes the first).
  bool once(unsigned& seen, unsigned bit) {
    if ((seen & bit) != 0) return false;
    seen |= bit;
    return true;
  }

  // The records go straight into the builder's vectors, which are reserved once kSample records of
  // an array are read: for as many more as the rest of the text holds at the bytes those took (an
  // overestimate, as the rest holds the other arrays too, but memory reserved and never written is
  // never given: issue 16). Before, the records were read into chunks and moved into vectors of
  // their size: every record written to fresh memory twice, and fresh memory was the largest cost
  // of reading a 1,000,000-manhole map (the kernel zeroing it). An estimate too small only means a
  // vector grows as usual.
  static constexpr std::size_t kSample = 1024;
  std::size_t rest_at_rate(std::size_t count, std::size_t begin) const {
    const std::size_t used = scan_.position() - begin;
    return count + (scan_.size() - scan_.position()) / std::max<std::size_t>(1, used / count);
  }

  bool root() {
    unsigned seen = 0;
    return scan_.object([&](std::string_view key) {
      if (key == "format") {
        std::string_view f;
        format_ = once(seen, 1) && scan_.string(f) && f == kMapJsonFormat;
        return format_;
      }
      if (key == "version") {
        double v = 0;
        version_ = once(seen, 2) && scan_.number(v) && v == kMapJsonVersion;
        return version_;
      }
      if (key == "name") return once(seen, 4) && scan_.string(name_);
      if (key == "crs") {
        std::string_view text;
        if (!once(seen, 128) || !scan_.string(text)) return false;
        Result<Crs> crs = parse_crs(text);
        if (!crs.has_value()) return false;
        crs_ = std::move(*crs);
        return true;
      }
      if (key == "manholes") {
        if (!once(seen, 8)) return false;
        const std::size_t begin = scan_.position();
        std::size_t count = 0;
        manholes_ = scan_.array([&] {
          if (++count == kSample) {
            const std::size_t manholes = rest_at_rate(count, begin);
            builder_.reserve(manholes, 0, manholes * slot_count_ / count + kSample);
          }
          return manhole();
        });
        return manholes_;
      }
      if (key == "pipes") {
        if (!once(seen, 16)) return false;
        const std::size_t begin = scan_.position();
        std::size_t count = 0;
        pipes_ = scan_.array([&] {
          if (++count == kSample) builder_.reserve(0, rest_at_rate(count, begin), 0);
          return pipe();
        });
        return pipes_;
      }
      if (key == "inspection_points") {
        return once(seen, 32) && scan_.array([&] { return point(); });
      }
      if (key == "findings") {
        std::uint32_t index = 0;
        return once(seen, 64) && scan_.array([&] { return finding(++index); });
      }
      return false;
    });
  }

  bool number(unsigned& seen, unsigned bit, double& out) {
    return once(seen, bit) && scan_.number(out);
  }

  bool number(unsigned& seen, unsigned bit, std::optional<double>& out) {
    double v = 0;
    if (!number(seen, bit, v)) return false;
    out = v;
    return true;
  }

  bool string(unsigned& seen, unsigned bit, std::string& out) {
    std::string_view v;
    if (!once(seen, bit) || !scan_.string(v)) return false;
    out = v;
    return true;
  }

  bool manhole() {
    ManholeRecord m;
    slots_.clear();
    unsigned seen = 0;
    const bool ok = scan_.object([&](std::string_view key) {
      if (key == "name") return string(seen, 1, m.name);
      if (key == "x_m") return number(seen, 2, m.position.x_m);
      if (key == "y_m") return number(seen, 4, m.position.y_m);
      if (key == "z_m") return number(seen, 8, m.position.z_m);
      if (key == "diameter_m") return number(seen, 16, m.diameter_m);
      if (key == "exit") return once(seen, 32) && scan_.boolean(m.exit);
      if (key == "variant") {
        std::string_view v;
        if (!once(seen, 64) || !scan_.string(v) || v.size() != 1) return false;
        m.variant = v[0];
        return true;
      }
      if (key == "shaft_length_m") return number(seen, 128, m.shaft_length_m);
      if (key == "shaft_width_m") return number(seen, 256, m.shaft_width_m);
      if (key == "depth_m") return number(seen, 512, m.depth_m);
      if (key == "slots") {
        return once(seen, 1024) && scan_.array([&] { return slot(slots_.emplace_back()); });
      }
      return false;
    });
    if (!ok || (seen & (1U | 16U)) != (1U | 16U)) return false;
    if (m.shaft_length_m.has_value() != m.shaft_width_m.has_value()) return false;
    // The invert defaults to the manhole's floor, which may come after the slots. JSON has no
    // NaN, so NaN marks an invert not given.
    for (SlotRecord& s : slots_) {
      if (std::isnan(s.invert_z_m)) s.invert_z_m = m.position.z_m;
    }
    builder_.add_manhole(std::move(m));
    for (SlotRecord& s : slots_) builder_.add_slot(std::move(s));
    slot_count_ += slots_.size();
    return true;
  }

  bool slot(SlotRecord& s) {
    s.invert_z_m = std::numeric_limits<double>::quiet_NaN();
    unsigned seen = 0;
    return scan_.object([&](std::string_view key) {
      if (key == "pipe") return string(seen, 1, s.pipe);
      if (key == "azimuth_deg") return number(seen, 2, s.azimuth_deg);
      if (key == "invert_m") return number(seen, 4, s.invert_z_m);
      return false;
    }) && (seen & 3U) == 3U;
  }

  bool end(unsigned& seen, unsigned bit, std::optional<std::string>& out) {
    if (!once(seen, bit)) return false;
    if (scan_.peek('n')) return scan_.null();
    std::string_view v;
    if (!scan_.string(v)) return false;
    out = std::string(v);
    return true;
  }

  bool pipe() {
    PipeRecord p;
    unsigned seen = 0;
    const bool ok = scan_.object([&](std::string_view key) {
      if (key == "name") return string(seen, 1, p.name);
      if (key == "from") return end(seen, 2, p.from);
      if (key == "to") return end(seen, 4, p.to);
      if (key == "length_m") return number(seen, 8, p.length_m);
      if (key == "diameter_m") return number(seen, 16, p.diameter_m);
      if (key == "shape") {
        std::string_view v;
        if (!once(seen, 32) || !scan_.string(v)) return false;
        const auto shape = pipe_shape_from_string(v);
        if (shape) p.shape = *shape;
        return shape.has_value();
      }
      if (key == "height_m") return number(seen, 64, p.height_m);
      if (key == "blockage_risk") {
        double v = 0;
        if (!number(seen, 128, v)) return false;
        p.blockage_risk = static_cast<float>(v);
        return true;
      }
      return false;
    });
    if (!ok || (seen & 31U) != 31U) return false;
    builder_.add_pipe(std::move(p));
    return true;
  }

  bool point() {
    PointRecord p;
    unsigned seen = 0;
    const bool ok = scan_.object([&](std::string_view key) {
      if (key == "name") return string(seen, 1, p.name);
      if (key == "pipe") return string(seen, 2, p.pipe);
      if (key == "offset_m") return number(seen, 4, p.offset_m);
      return false;
    });
    if (!ok || seen != 7U) return false;
    builder_.add_point(std::move(p));
    return true;
  }

  bool finding(std::uint32_t index) {
    FindingRecord r;
    r.line = index;
    unsigned seen = 0;
    const bool ok = scan_.object([&](std::string_view key) {
      if (key == "pipe") return string(seen, 1, r.pipe);
      if (key == "code") return string(seen, 2, r.code);
      if (key == "characterisation") return string(seen, 4, r.characterisation);
      if (key == "offset_m") return number(seen, 8, r.station_m);
      if (key == "quantity1") return number(seen, 16, r.quantity1);
      if (key == "quantity2") return number(seen, 32, r.quantity2);
      return false;
    });
    if (!ok || (seen & 11U) != 11U) return false;
    builder_.add_finding(std::move(r));
    return true;
  }

  detail::JsonScan scan_;
  const std::string& file_name_;
  std::string_view name_;
  std::optional<Crs> crs_;
  bool format_ = false;
  bool version_ = false;
  bool manholes_ = false;
  bool pipes_ = false;
  MapBuilder builder_;
  std::size_t slot_count_ = 0;
  std::vector<SlotRecord> slots_;  // the current manhole's, while it is read
};

}  // namespace

namespace detail {

std::optional<MapBuilder> read_map_json_fast(std::string_view text, const std::string& file_name) {
  return FastReader(text, file_name).read();
}

}  // namespace detail

Result<SewerMap> read_map_json(std::string_view text, const std::string& file_name,
                               Diagnostics& diagnostics) {
  if (std::optional<MapBuilder> builder = detail::read_map_json_fast(text, file_name)) {
    return std::move(*builder).build(diagnostics);
  }
  return detail::read_map_json_document(text, file_name, diagnostics);
}

namespace detail {

Result<SewerMap> read_map_json_document(std::string_view text, const std::string& file_name,
                                        Diagnostics& diagnostics) {
  const Diagnostics::Mark before = diagnostics.mark();
  std::optional<JsonDocument> doc = JsonDocument::parse(text, file_name, diagnostics);
  if (!doc) return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  JsonFields root(doc->root(), "$", file_name, diagnostics);
  check_header(root);
  MapBuilder builder(root.string("name", Need::kOptional).value_or(""), json_locator(file_name));
  if (std::optional<std::string> crs_text = root.string("crs", Need::kOptional)) {
    Result<Crs> crs = parse_crs(*crs_text);
    if (crs.has_value()) {
      builder.set_crs(std::move(*crs));
    } else {
      diagnostics.error(root.where("crs"), crs.error().message);
    }
  }
  const auto manholes = root.array("manholes");
  const auto pipes = root.array("pipes");
  const auto points = root.array("inspection_points", Need::kOptional);
  const auto findings = root.array("findings", Need::kOptional);
  root.warn_unknown(
      {"format", "version", "name", "crs", "manholes", "pipes", "inspection_points", "findings"});
  builder.reserve(manholes ? manholes->size() : 0, pipes ? pipes->size() : 0);
  std::size_t i = 0;
  if (manholes) {
    for (JsonElement m : *manholes)
      builder.add_manhole(read_manhole(m, i++, file_name, diagnostics));
  }
  i = 0;
  if (pipes) {
    for (JsonElement p : *pipes) builder.add_pipe(read_pipe(p, i++, file_name, diagnostics));
  }
  i = 0;
  if (points) {
    for (JsonElement p : *points) builder.add_point(read_point(p, i++, file_name, diagnostics));
  }
  i = 0;
  if (findings) {
    for (JsonElement f : *findings) {
      builder.add_finding(read_finding(f, i++, file_name, diagnostics));
    }
  }
  doc.reset();  // free the parsed document before building
  if (diagnostics.has_errors_since(before))
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  return std::move(builder).build(diagnostics);
}

}  // namespace detail

void write_map_json(const SewerMap& map, std::ostream& out) {
  out << "{\n  \"format\": \"" << kMapJsonFormat << "\",\n  \"version\": " << kMapJsonVersion
      << ",\n  \"name\": ";
  write_string(out, map.name());
  if (map.crs()) out << ",\n  \"crs\": \"" << map.crs()->to_string() << '"';
  out << ",\n  \"manholes\": [\n";
  for (ManholeId m : map.manhole_ids()) {
    if (m.value() > 0) out << ",\n";
    write_manhole(out, map, m);
  }
  out << "\n  ],\n  \"pipes\": [\n";
  for (PipeId p : map.pipe_ids()) {
    if (p.value() > 0) out << ",\n";
    write_pipe(out, map, map.pipe(p));
  }
  out << "\n  ],\n  \"inspection_points\": [";
  for (PointId p : map.point_ids()) {
    const InspectionPoint& point = map.point(p);
    out << (p.value() > 0 ? ",\n" : "\n") << "    {\"name\": ";
    write_string(out, point.name);
    out << ", \"pipe\": ";
    write_string(out, map.pipe(point.pipe).name);
    out << ", \"offset_m\": " << format_double(point.offset_m) << '}';
  }
  out << (map.point_count() > 0 ? "\n  ]" : "]");
  if (map.finding_count() > 0) {
    out << ",\n  \"findings\": [";
    bool first = true;
    for (const Finding& f : map.findings()) {
      out << (first ? "\n" : ",\n") << "    {\"pipe\": ";
      write_string(out, map.pipe(f.pipe).name);
      out << ", \"code\": ";
      write_string(out, f.code);
      if (!f.characterisation.empty()) {
        out << ", \"characterisation\": ";
        write_string(out, f.characterisation);
      }
      out << ", \"offset_m\": " << format_double(f.offset_m);
      write_optional(out, "quantity1", f.quantity1);
      write_optional(out, "quantity2", f.quantity2);
      out << '}';
      first = false;
    }
    out << "\n  ]";
  }
  out << "\n}\n";
}

}  // namespace sewerplan
