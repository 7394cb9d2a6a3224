// SPDX-License-Identifier: MIT
// SewerMap: the sewer world model, an immutable network of manholes joined by pipes.
//
// MAKRO's world (Adria, Streich and Hertzberg 2004, sections 2.1 and 4.2) is topological: manholes,
// the pipes between them, and places in pipes where tasks are done. A manhole has a diameter and an
// ordered list of slots; each slot is one pipe mouth, with the azimuth at which that pipe leaves
// the manhole and the height of that pipe end's invert (the floor of the pipe). From two slots
// follow the turn and the step the robot makes passing from one pipe to the other. A manhole's type
// is its number of slots (the paper's TYPE_2, TYPE_3, TYPE_4); three-way manholes come in geometric
// variants, recorded as a letter (the paper's TYPE_B).
//
// Layout: manholes, pipes, slots and inspection points are flat vectors indexed by strong IDs;
// each manhole's slots are one contiguous run of the slot vector (compressed sparse row), so the
// slots are also the adjacency of the network. A map is built and validated by MapBuilder
// (map_builder.h) and read from files by read_map (map_io.h); once built it never changes, so it is
// shared by const reference. Queries live in map_queries.h.
//
//   const SewerMap& map = ...;
//   ManholeId m = *map.find_manhole("M6");
//   for (const Slot& slot : map.slots(m)) {
//     const Pipe& pipe = map.pipe(slot.pipe);
//     std::cout << pipe.name << " leaves at " << slot.azimuth_deg << " deg\n";
//   }
//
// Conventions: lengths in metres; angles in degrees counter-clockwise from +x (east), as in the
// files, so that reading and writing a map loses nothing; z up.
//
// Thread safety: A SewerMap is immutable once built: share it (const) between any number of
// threads.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/crs.h"
#include "sewerplan/core/strong_id.h"

namespace sewerplan {

using ManholeId = StrongId<struct ManholeTag>;
using PipeId = StrongId<struct PipeTag>;
using PointId = StrongId<struct InspectionPointTag>;
// A slot's position in its manhole's slot list, from 0. The paper numbers slots from 1 in action
// names (DRIVE_MANHOLE_TYPE_4_FROM_3_TO_4); to_paper_number() converts.
using SlotIndex = StrongId<struct SlotTag, std::uint16_t>;

constexpr int to_paper_number(SlotIndex slot) { return slot.value() + 1; }

struct Position {
  double x_m = 0;
  double y_m = 0;
  double z_m = 0;  // for a manhole: its floor (invert) height
  friend bool operator==(const Position&, const Position&) = default;
};

// One pipe mouth in a manhole.
struct Slot {
  PipeId pipe{0};
  std::uint8_t pipe_end = 0;  // which end of the pipe is here: 0 = Pipe::ends[0], 1 = ends[1]
  double azimuth_deg = 0;     // direction in which the pipe leaves the manhole
  double invert_z_m = 0;      // absolute height of this pipe end's invert
  friend bool operator==(const Slot&, const Slot&) = default;
};

struct Manhole {
  std::string name;
  Position position;
  double diameter_m = 0;
  std::uint32_t first_slot = 0;  // index of its first slot in the map's slot vector
  std::uint16_t slot_count = 0;  // the manhole's type
  bool exit = false;             // the robot can be lowered in and recovered here
  std::optional<char> variant;   // geometric variant of the type, 'A'..'Z' (the paper's TYPE_B)
  // A rectangular shaft's floor plan (ISYBAU Unterteil length and width), when the file gives
  // one; diameter_m is then its shorter side, the room the robot has to turn. Empty: round.
  std::optional<double> shaft_length_m;
  std::optional<double> shaft_width_m;
  std::optional<double> depth_m;  // cover to floor, when the file gives it
  friend bool operator==(const Manhole&, const Manhole&) = default;
};

enum class PipeShape : std::uint8_t { kCircular, kRectangular, kEgg, kOther };

std::string_view to_string(PipeShape shape);
std::optional<PipeShape> pipe_shape_from_string(std::string_view name);
// The names pipe_shape_from_string reads, "circular, rectangular, egg, other", for messages.
std::string pipe_shape_names();

// One end of a pipe: a slot of a manhole, or nothing (a blind end, such as a stub).
struct PipeEnd {
  std::optional<ManholeId> manhole;
  SlotIndex slot{0};  // meaningful only with a manhole
  friend bool operator==(const PipeEnd&, const PipeEnd&) = default;
};

struct Pipe {
  std::string name;
  std::array<PipeEnd, 2> ends;  // ends[0] is the upstream end ("from"), ends[1] downstream ("to")
  double length_m = 0;
  // The clear size the robot must fit: a circular pipe's diameter; for other shapes the smaller of
  // width and height.
  double diameter_m = 0;
  PipeShape shape = PipeShape::kCircular;
  double height_m = 0;  // the profile's height; equals diameter_m for a circular pipe
  // Likelihood, from the last inspection, that the pipe is blocked (0..1); unknown if empty.
  std::optional<float> blockage_risk;
  friend bool operator==(const Pipe&, const Pipe&) = default;
};

// One finding of a pipe's last inspection, in the codes of DIN EN 13508-2 (ISYBAU Zustandsdaten):
// the main code ("BAC" collapse, "BBA" roots, ...), its characterisations, its quantifications
// (their meaning depends on the code: a share of the cross-section lost in percent, a
// displacement in millimetres, ...) and where it is. What a finding means for a robot is not
// decided here: condition_risk.h does that, with a table.
struct Finding {
  PipeId pipe{0};
  std::string code;              // three letters, e.g. "BAC"
  std::string characterisation;  // Charakterisierung 1 and 2, e.g. "AB"; may be empty
  double offset_m = 0;           // from the pipe's ends[0], whichever way it was inspected
  std::optional<double> quantity1;
  std::optional<double> quantity2;
  friend bool operator==(const Finding&, const Finding&) = default;
};

// A named place in a pipe, offset_m from the pipe's ends[0] towards ends[1].
struct InspectionPoint {
  std::string name;
  PipeId pipe{0};
  double offset_m = 0;
  friend bool operator==(const InspectionPoint&, const InspectionPoint&) = default;
};

class SewerMap {
 public:
  SewerMap() = default;

  const std::string& name() const { return name_; }
  // The coordinate reference system of the manholes' x and y (crs.h); empty: local coordinates,
  // or a source that did not say.
  const std::optional<Crs>& crs() const { return crs_; }

  std::size_t manhole_count() const { return manholes_.size(); }
  std::size_t pipe_count() const { return pipes_.size(); }
  std::size_t point_count() const { return points_.size(); }
  std::size_t slot_count() const { return slots_.size(); }
  std::size_t finding_count() const { return findings_.size(); }

  IdRange<ManholeId> manhole_ids() const { return id_range<ManholeId>(manholes_.size()); }
  IdRange<PipeId> pipe_ids() const { return id_range<PipeId>(pipes_.size()); }
  IdRange<PointId> point_ids() const { return id_range<PointId>(points_.size()); }

  // Precondition for all accessors: the ID belongs to this map (checked).
  const Manhole& manhole(ManholeId id) const;
  const Pipe& pipe(PipeId id) const;
  const InspectionPoint& point(PointId id) const;
  std::span<const Slot> slots(ManholeId id) const;
  const Slot& slot(ManholeId id, SlotIndex slot) const;

  std::span<const Manhole> manholes() const { return manholes_; }
  std::span<const Pipe> pipes() const { return pipes_; }
  std::span<const InspectionPoint> points() const { return points_; }
  // Inspection findings, sorted by pipe, then offset. findings(pipe): those of one pipe.
  // Runtime: O(log findings).
  std::span<const Finding> findings() const { return findings_; }
  std::span<const Finding> findings(PipeId pipe) const;

  // Look-up by name. Runtime: O(log n).
  std::optional<ManholeId> find_manhole(std::string_view name) const;
  std::optional<PipeId> find_pipe(std::string_view name) const;
  std::optional<PointId> find_point(std::string_view name) const;

  // Bytes held by this map, its vectors and its names' heap buffers.
  std::size_t memory_bytes() const;

  friend bool operator==(const SewerMap& a, const SewerMap& b);

 private:
  friend class MapBuilder;

  std::string name_;
  std::optional<Crs> crs_;
  std::vector<Manhole> manholes_;
  std::vector<Slot> slots_;
  std::vector<Pipe> pipes_;
  std::vector<InspectionPoint> points_;
  std::vector<Finding> findings_;
  // Indices sorted by name, for find_*.
  std::vector<std::uint32_t> manholes_by_name_;
  std::vector<std::uint32_t> pipes_by_name_;
  std::vector<std::uint32_t> points_by_name_;
};

}  // namespace sewerplan
