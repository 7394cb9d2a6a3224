// SPDX-License-Identifier: MIT
// The writer of the ASCII sewer database; the reader is in map_ascii.cc.
#include <string>
#include <string_view>

#include "sewerplan/core/map_ascii.h"

#include "ascii_syntax.h"

namespace sewerplan {
namespace {

using ascii_syntax::append_number;

constexpr std::string_view kFirstLine =
    "# sewerplan ASCII sewer database; format: docs/formats/ascii-database.md\n";

// Appends one line per object whose name cannot be written, naming it and saying why.
void check_name(std::string_view kind, std::string_view name, std::string& problems) {
  std::string_view problem = ascii_syntax::name_problem(name);
  if (problem.empty() && kind == "manhole" && name == ascii_syntax::kBlindEnd) {
    problem = "'-' stands for a blind pipe end";
  }
  if (problem.empty()) return;
  if (!problems.empty()) problems += '\n';
  problems += std::string(kind) + " " + ascii_syntax::quoted(name) +
              " cannot be written: " + std::string(problem);
}

std::string name_problems(const SewerMap& map) {
  std::string problems;
  check_name("map name", map.name(), problems);
  for (const Manhole& m : map.manholes()) check_name("manhole", m.name, problems);
  for (const Pipe& p : map.pipes()) check_name("pipe", p.name, problems);
  for (const InspectionPoint& p : map.points()) check_name("inspection point", p.name, problems);
  return problems;
}

template <class T>
void append_key(std::string& out, std::string_view key, T value) {
  out += ' ';
  out += key;
  out += '=';
  append_number(out, value);
}

void append_manhole(std::string& out, const SewerMap& map, ManholeId id) {
  const Manhole& m = map.manhole(id);
  out += "manhole ";
  out += m.name;
  append_key(out, "x", m.position.x_m);
  append_key(out, "y", m.position.y_m);
  append_key(out, "z", m.position.z_m);
  append_key(out, "diameter", m.diameter_m);
  if (m.exit) out += " exit";
  if (m.variant) {
    out += " variant=";
    out += *m.variant;
  }
  if (m.shaft_length_m) append_key(out, "shaft_length", *m.shaft_length_m);
  if (m.shaft_width_m) append_key(out, "shaft_width", *m.shaft_width_m);
  if (m.depth_m) append_key(out, "depth", *m.depth_m);
  out += '\n';
  for (const Slot& slot : map.slots(id)) {
    out += "  slot ";
    out += map.pipe(slot.pipe).name;
    append_key(out, "azimuth", slot.azimuth_deg);
    append_key(out, "invert", slot.invert_z_m);
    out += '\n';
  }
}

void append_end(std::string& out, std::string_view key, const SewerMap& map, const PipeEnd& end) {
  out += ' ';
  out += key;
  out += '=';
  out += end.manhole ? std::string_view(map.manhole(*end.manhole).name) : ascii_syntax::kBlindEnd;
}

void append_pipe(std::string& out, const SewerMap& map, const Pipe& p) {
  out += "pipe ";
  out += p.name;
  append_end(out, "from", map, p.ends[0]);
  append_end(out, "to", map, p.ends[1]);
  append_key(out, "length", p.length_m);
  append_key(out, "diameter", p.diameter_m);
  if (p.shape != PipeShape::kCircular) {
    out += " shape=";
    out += to_string(p.shape);
  }
  // The reader's default height is the diameter; a non-circular profile always states it.
  if (p.shape != PipeShape::kCircular || p.height_m != p.diameter_m) {
    append_key(out, "height", p.height_m);
  }
  if (p.blockage_risk) append_key(out, "risk", *p.blockage_risk);
  out += '\n';
}

std::string canonical_text(const SewerMap& map) {
  std::string out(kFirstLine);
  out += ascii_syntax::kHeaderKeyword;
  out += ' ';
  out += ascii_syntax::kFormatVersion;
  out += "\nmap ";
  out += map.name();
  out += '\n';
  for (ManholeId id : map.manhole_ids()) append_manhole(out, map, id);
  if (map.pipe_count() > 0) out += '\n';
  for (const Pipe& p : map.pipes()) append_pipe(out, map, p);
  if (map.point_count() > 0) out += '\n';
  for (const InspectionPoint& point : map.points()) {
    out += "point ";
    out += point.name;
    out += " pipe=";
    out += map.pipe(point.pipe).name;
    append_key(out, "offset", point.offset_m);
    out += '\n';
  }
  return out;
}

}  // namespace

Result<void> write_map_ascii(const SewerMap& map, std::ostream& out) {
  if (std::string problems = name_problems(map); !problems.empty()) {
    return Error{ErrorCode::kInvalidArgument, std::move(problems)};
  }
  if (map.finding_count() > 0) {
    return Error{ErrorCode::kUnsupportedFormat,
                 "the ASCII sewer database holds no inspection findings, and this map has " +
                     std::to_string(map.finding_count()) + ": write .json to keep them"};
  }
  const std::string text = canonical_text(map);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) return Error{ErrorCode::kIo, "writing the ASCII sewer database failed"};
  return {};
}

}  // namespace sewerplan
