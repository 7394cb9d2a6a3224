// SPDX-License-Identifier: MIT
#include "sewerplan/core/sewer_map.h"

#include <algorithm>

#include "sewerplan/core/check.h"
#include "sewerplan/core/enum_names.h"

namespace sewerplan {
namespace {

constexpr detail::EnumNames<PipeShape, 4> kPipeShapes{{
    {PipeShape::kCircular, "circular"},
    {PipeShape::kRectangular, "rectangular"},
    {PipeShape::kEgg, "egg"},
    {PipeShape::kOther, "other"},
}};
static_assert(detail::distinct(kPipeShapes));

template <class T>
std::optional<std::uint32_t> find_by_name(const std::vector<std::uint32_t>& sorted,
                                          const std::vector<T>& objects, std::string_view name) {
  auto it =
      std::lower_bound(sorted.begin(), sorted.end(), name,
                       [&](std::uint32_t i, std::string_view n) { return objects[i].name < n; });
  if (it == sorted.end() || objects[*it].name != name) return std::nullopt;
  return *it;
}

std::size_t heap_bytes(const std::string& s) {
  // Short strings live inside the object (libstdc++ keeps up to 15 characters in place).
  return s.capacity() > 15 ? s.capacity() + 1 : 0;
}

}  // namespace

std::string_view to_string(PipeShape shape) { return detail::name_of(kPipeShapes, shape); }

std::optional<PipeShape> pipe_shape_from_string(std::string_view name) {
  return detail::value_of(kPipeShapes, name);
}

std::string pipe_shape_names() { return detail::names_joined(kPipeShapes); }

const Manhole& SewerMap::manhole(ManholeId id) const {
  SEWER_CHECK(id.index() < manholes_.size(), "manhole id does not belong to this map");
  return manholes_[id.index()];
}

const Pipe& SewerMap::pipe(PipeId id) const {
  SEWER_CHECK(id.index() < pipes_.size(), "pipe id does not belong to this map");
  return pipes_[id.index()];
}

const InspectionPoint& SewerMap::point(PointId id) const {
  SEWER_CHECK(id.index() < points_.size(), "inspection point id does not belong to this map");
  return points_[id.index()];
}

std::span<const Slot> SewerMap::slots(ManholeId id) const {
  const Manhole& m = manhole(id);
  return std::span<const Slot>(slots_).subspan(m.first_slot, m.slot_count);
}

const Slot& SewerMap::slot(ManholeId id, SlotIndex slot) const {
  const Manhole& m = manhole(id);
  SEWER_CHECK(slot.value() < m.slot_count, "slot index out of range for this manhole");
  return slots_[m.first_slot + slot.value()];
}

std::span<const Finding> SewerMap::findings(PipeId pipe) const {
  const auto first = std::lower_bound(findings_.begin(), findings_.end(), pipe,
                                      [](const Finding& f, PipeId p) { return f.pipe < p; });
  const auto last = std::upper_bound(first, findings_.end(), pipe,
                                     [](PipeId p, const Finding& f) { return p < f.pipe; });
  return {first, last};
}

std::optional<ManholeId> SewerMap::find_manhole(std::string_view name) const {
  auto i = find_by_name(manholes_by_name_, manholes_, name);
  return i ? std::optional(ManholeId{*i}) : std::nullopt;
}

std::optional<PipeId> SewerMap::find_pipe(std::string_view name) const {
  auto i = find_by_name(pipes_by_name_, pipes_, name);
  return i ? std::optional(PipeId{*i}) : std::nullopt;
}

std::optional<PointId> SewerMap::find_point(std::string_view name) const {
  auto i = find_by_name(points_by_name_, points_, name);
  return i ? std::optional(PointId{*i}) : std::nullopt;
}

std::size_t SewerMap::memory_bytes() const {
  std::size_t bytes = sizeof(*this) + heap_bytes(name_) + (crs_ ? heap_bytes(crs_->authority) : 0);
  bytes += manholes_.capacity() * sizeof(Manhole) + slots_.capacity() * sizeof(Slot) +
           pipes_.capacity() * sizeof(Pipe) + points_.capacity() * sizeof(InspectionPoint) +
           findings_.capacity() * sizeof(Finding);
  bytes += (manholes_by_name_.capacity() + pipes_by_name_.capacity() + points_by_name_.capacity()) *
           sizeof(std::uint32_t);
  for (const Manhole& m : manholes_) bytes += heap_bytes(m.name);
  for (const Pipe& p : pipes_) bytes += heap_bytes(p.name);
  for (const InspectionPoint& p : points_) bytes += heap_bytes(p.name);
  for (const Finding& f : findings_) bytes += heap_bytes(f.code) + heap_bytes(f.characterisation);
  return bytes;
}

bool operator==(const SewerMap& a, const SewerMap& b) {
  return a.name_ == b.name_ && a.crs_ == b.crs_ && a.manholes_ == b.manholes_ &&
         a.slots_ == b.slots_ && a.pipes_ == b.pipes_ && a.points_ == b.points_ &&
         a.findings_ == b.findings_;
}

}  // namespace sewerplan
