// SPDX-License-Identifier: MIT
// MapBuilder: turns named records, as a file states them, into a validated SewerMap.
//
// Every map format (native JSON, the ASCII database, SWMM, ISYBAU, the generator) reads its input
// into records that refer to each other by name, and hands them to one MapBuilder. build() resolves
// the names and checks the whole network, so every format gets the same validation:
//   errors   - empty or duplicate names (per object kind), names with white space, non-finite
//              numbers, non-positive lengths and diameters, a pipe end naming an unknown manhole,
//              a slot naming an unknown pipe, a slot in a manhole that is not one of its pipe's
//              ends, a pipe end with no slot for it, two slots for one pipe end, a pipe joining a
//              manhole to itself, an inspection point off its pipe;
//   warnings - manholes without pipes, a network in several disconnected parts, findings naming
//              no pipe or lying off their pipe (left out, or clamped onto it).
// Each diagnostic names the object, and the place in the file through the Locator the reader
// supplies (a line, or a JSON path).
//
//   MapBuilder builder("ais-testbed");
//   builder.add_manhole({.name = "M2", .diameter_m = 1.0, .slots = {{.pipe = "P12"}, ...}});
//   builder.add_pipe({.name = "P12", .from = "M1", .to = "M2", .length_m = 5, .diameter_m = 0.6});
//   Diagnostics diagnostics;
//   Result<SewerMap> map = std::move(builder).build(diagnostics);
//
// Thread safety: A MapBuilder is not thread-safe: build on one thread, then share the SewerMap it
// makes.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

struct SlotRecord {
  std::string pipe;
  double azimuth_deg = 0;
  double invert_z_m = 0;
  std::uint32_t line = 0;  // where the record stands in its file (0: not line-based)
};

struct ManholeRecord {
  std::string name;
  Position position;
  double diameter_m = 0;
  bool exit = false;
  std::optional<char> variant;
  std::optional<double> shaft_length_m;  // with shaft_width_m: a rectangular shaft
  std::optional<double> shaft_width_m;
  std::optional<double> depth_m;
  std::vector<SlotRecord> slots;
  std::uint32_t line = 0;
};

struct PipeRecord {
  std::string name;
  std::optional<std::string> from;  // empty: a blind end
  std::optional<std::string> to;
  double length_m = 0;
  double diameter_m = 0;
  PipeShape shape = PipeShape::kCircular;
  std::optional<double> height_m;  // defaults to diameter_m
  std::optional<float> blockage_risk;
  std::uint32_t line = 0;
};

struct PointRecord {
  std::string name;
  std::string pipe;
  double offset_m = 0;
  std::uint32_t line = 0;
};

// An inspection finding as a file states it: the pipe by name, and the position as measured by
// the inspection, `station_m` from the end it started at (ends[1] when `against_flow`, so the
// offset from ends[0] is the pipe's length less the station).
struct FindingRecord {
  std::string pipe;
  std::string code;
  std::string characterisation;
  double station_m = 0;
  bool against_flow = false;
  std::optional<double> quantity1;
  std::optional<double> quantity2;
  std::uint32_t line = 0;
};

// What a diagnostic is about, for the Locator to turn into a place in the file.
struct RecordRef {
  enum class Kind { kMap, kManhole, kSlot, kPipe, kPoint, kFinding };
  Kind kind = Kind::kMap;
  std::uint32_t index = 0;       // record index within its kind, in the order added
  std::uint32_t slot_index = 0;  // with kSlot: the slot within manhole `index`
  std::uint32_t line = 0;        // the record's line, if the reader set one
};

// Turns a record and a field name ("length_m", or empty for the whole record) into the `where` of
// a diagnostic. The default names the file and, if known, the line.
using Locator = std::function<std::string(const RecordRef& record, std::string_view field)>;

// "file:line", or "file" when line is 0.
Locator line_locator(std::string file);

class MapBuilder {
 public:
  explicit MapBuilder(std::string map_name, Locator locator = line_locator("<map>"));

  // Its slots are `record.slots`, then any add_slot() before the next add_manhole().
  void add_manhole(ManholeRecord record);
  // One more slot of the manhole added last (precondition: one was added). A reader streaming a
  // large map hands the slots one by one, with no vector per manhole (issue 16: a million of them
  // were the reader's largest share of small allocations).
  void add_slot(SlotRecord slot);
  void add_pipe(PipeRecord record);
  void add_point(PointRecord record);
  void add_finding(FindingRecord record);
  // The map's name, when the reader learns it after the records (as given to the constructor).
  void set_name(std::string map_name);
  // The coordinate reference system of the records' positions (crs.h), when the source names one.
  void set_crs(std::optional<Crs> crs);
  void reserve(std::size_t manholes, std::size_t pipes, std::size_t slots = 0);
  // Room for this many bytes of names in all (a bound, such as the size of the text they are read
  // from: room reserved and never written is never given).
  void reserve_names(std::size_t bytes);

  // Validates and builds. On error, every problem found is in `diagnostics` and the Error's
  // message lists them. Warnings are added to `diagnostics` either way.
  Result<SewerMap> build(Diagnostics& diagnostics) &&;

  // `map` with its coordinate reference system replaced (a --crs given for a source without one).
  static SewerMap with_crs(SewerMap map, std::optional<Crs> crs);

  // `map` with `findings` added (a condition file joined to a map read before): a finding naming
  // no pipe of the map is left out with a warning, as is one off its pipe (clamped onto it).
  static SewerMap add_findings(SewerMap map, std::vector<FindingRecord> findings,
                               const Locator& locator, Diagnostics& diagnostics);

 private:
  class Validation;
  // The records as stored until build(): their names are offset and length into one buffer,
  // names_, and their optional fields are flags beside plain values. A record kept as added held
  // each name in a std::string of 32 bytes (40 with std::optional) and each optional double in 16:
  // for a 1,000,000-manhole map, 461 MB of records, fresh memory the kernel had to zero, where
  // these take 210 MB and the names 50 MB more (issue 16).
  struct Name {
    static constexpr std::uint32_t kNone = 0xffffffffU;  // size of a name not given (a blind end)
    std::uint32_t offset = 0;
    std::uint32_t size = kNone;
    bool given() const { return size != kNone; }
  };
  struct StoredSlot {
    Name pipe;
    double azimuth_deg;
    double invert_z_m;
    std::uint32_t line;
  };
  struct StoredManhole {
    Name name;
    Position position;
    double diameter_m;
    double shaft_length_m;  // each of these three only if its bit is set in `given`
    double shaft_width_m;
    double depth_m;
    std::uint32_t line;
    bool exit;
    char variant;  // only with kVariant
    std::uint8_t given;
  };
  struct StoredPipe {
    Name name;
    Name from;
    Name to;
    double length_m;
    double diameter_m;
    double height_m;      // only with kHeight
    float blockage_risk;  // only with kBlockageRisk
    std::uint32_t line;
    PipeShape shape;
    std::uint8_t given;
  };
  static constexpr std::uint8_t kVariant = 1, kShaftLength = 2, kShaftWidth = 4, kDepth = 8;
  static constexpr std::uint8_t kHeight = 1, kBlockageRisk = 2;

  Name keep(std::string_view name);
  std::string_view name(Name n) const {
    return n.given() ? std::string_view(names_).substr(n.offset, n.size) : std::string_view();
  }

  std::string name_;
  std::optional<Crs> crs_;
  Locator locator_;
  std::string names_;            // every record's name, one after the other
  bool names_overflow_ = false;  // names_ would pass 4 GiB: build() refuses the map
  // The manholes as added, their slots in one store: manhole i's slots are
  // slots_[slot_end_[i - 1] .. slot_end_[i]) (from 0 for the first).
  std::vector<StoredManhole> manholes_;
  std::vector<StoredSlot> slots_;
  std::vector<std::uint32_t> slot_end_;
  std::span<const StoredSlot> slots_of(std::size_t manhole) const;
  std::vector<StoredPipe> pipes_;
  std::vector<PointRecord> points_;
  std::vector<FindingRecord> findings_;
};

}  // namespace sewerplan
