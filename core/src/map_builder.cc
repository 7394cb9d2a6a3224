// SPDX-License-Identifier: MIT
#include "sewerplan/core/map_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <optional>
#include <sstream>
#include <tuple>

#include "sewerplan/core/check.h"
#include "sewerplan/core/limits.h"
#include "sewerplan/core/map_queries.h"
#include "sewerplan/core/message_text.h"
#include "sewerplan/core/text_file.h"

#include "huge_pages.h"

namespace sewerplan {
namespace {

using Kind = RecordRef::Kind;

std::string format_number(double v) { return number_text(v); }

// No white space or control characters, and valid UTF-8: every name may end up in JSON output
// (readers convert Latin-1 input to UTF-8 first: text_file.h).
bool is_valid_name(std::string_view name) {
  if (name.empty() || !is_valid_utf8(name)) return false;
  return std::none_of(name.begin(), name.end(), [](char c) {
    auto u = static_cast<unsigned char>(c);
    return u <= 0x20 || u == 0x7f;
  });
}

// The names of records of one kind, by index: names[i] is record i's name, names.line(i) its line,
// names.record(i) where it lies (to fetch ahead).
template <class Record, class NameOf>
class RecordNames {
 public:
  RecordNames(const std::vector<Record>& records, NameOf name_of)
      : records_(&records), name_of_(name_of) {}
  std::size_t size() const { return records_->size(); }
  std::string_view operator[](std::size_t i) const { return name_of_((*records_)[i]); }
  std::uint32_t line(std::size_t i) const { return (*records_)[i].line; }
  const void* record(std::size_t i) const { return &(*records_)[i]; }

 private:
  const std::vector<Record>* records_;
  NameOf name_of_;
};

struct OwnName {
  template <class Record>
  std::string_view operator()(const Record& r) const {
    return r.name;
  }
};

// Indices of the records named by `names` sorted by name, and whether no two share a name;
// reports empty, malformed and duplicate names.
struct SortedNames {
  std::vector<std::uint32_t> order;
  bool unique = true;
};

template <class Names>
SortedNames sorted_names(const Names& names, std::string_view kind, Kind ref_kind,
                         const Locator& locate, Diagnostics& diagnostics) {
  // Sorted by the names' first 8 bytes held beside the index, the full names compared only where
  // those are equal: comparing through the index to a million names scattered in memory was a
  // quarter of reading a 1,000,000-manhole map (issue 16). The order is the same: a smaller
  // prefix (zero-padded, big-endian) means a smaller name.
  struct Key {
    std::uint64_t prefix;
    std::uint32_t index;
  };
  std::vector<Key> keys;
  detail::reserve_huge(keys, names.size());
  bool all_valid = true;  // checked here, in the records' order, not in the names' order
  for (std::uint32_t i = 0; i < names.size(); ++i) {
    std::uint64_t prefix = 0;
    const std::string_view name = names[i];
    for (std::size_t k = 0; k < 8; ++k) {
      prefix = (prefix << 8U) | (k < name.size() ? static_cast<unsigned char>(name[k]) : 0U);
    }
    keys.push_back({prefix, i});
    all_valid = all_valid && is_valid_name(name);
  }
  std::sort(keys.begin(), keys.end(), [&](const Key& a, const Key& b) {
    if (a.prefix != b.prefix) return a.prefix < b.prefix;
    const std::string_view x = names[a.index];
    const std::string_view y = names[b.index];
    return x < y || (x == y && a.index < b.index);
  });
  // Two names with different prefixes differ, so only neighbours with the same prefix are read
  // again: a million names fetched in sorted order, scattered in memory, were a tenth of the
  // build (issue 16).
  SortedNames result;
  for (std::size_t k = 1; k < keys.size() && result.unique; ++k) {
    result.unique =
        keys[k].prefix != keys[k - 1].prefix || names[keys[k].index] != names[keys[k - 1].index];
  }
  std::vector<std::uint32_t>& order = result.order;
  detail::reserve_huge(order, names.size());
  for (const Key& k : keys) order.push_back(k.index);
  std::vector<Key>().swap(keys);
  if (all_valid && result.unique) return result;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::string_view name = names[order[k]];
    RecordRef ref{ref_kind, order[k], 0, names.line(order[k])};
    if (!is_valid_name(name)) {
      diagnostics.error(locate(ref, "name"),
                        std::string(kind) + " name " + input_quoted(name) +
                            " is empty, contains white space or control characters, or is not "
                            "valid UTF-8");
    } else if (k > 0 && names[order[k - 1]] == name) {
      RecordRef first_ref{ref_kind, order[k - 1], 0, names.line(order[k - 1])};
      diagnostics.error(locate(ref, "name"), "duplicate " + std::string(kind) + " name '" +
                                                 std::string(name) + "' (first defined at " +
                                                 locate(first_ref, "") + ")");
    }
  }
  return result;
}

// Names to the first record of that name (by index; a repeated name is an error): open addressing
// over record indices, so a reference resolves with one or two probes where a binary search over a
// million sorted names touched some twenty records far apart. 4 bytes per slot, at most half full.
template <class Names>
class NameIndex {
 public:
  // `unique`: no two of `names` are the same (sorted_names said so), so a name goes to the first
  // empty slot without reading the names it passes (records far apart in memory).
  NameIndex(Names names, bool unique) : names_(names) {
    std::size_t capacity = 16;
    while (capacity < 2 * names.size()) capacity <<= 1U;
    mask_ = capacity - 1;
    detail::reserve_huge(slots_, capacity);
    slots_.assign(capacity, kEmpty);
    for (std::uint32_t i = 0; i < names.size(); ++i) {
      const std::string_view name = names[i];
      std::size_t h = std::hash<std::string_view>{}(name)&mask_;
      for (; slots_[h] != kEmpty; h = (h + 1) & mask_) {
        if (!unique && names[slots_[h]] == name) break;
      }
      if (slots_[h] == kEmpty) slots_[h] = i;
    }
  }

  std::optional<std::uint32_t> find(std::string_view name) const {
    return probe(name, std::hash<std::string_view>{}(name)&mask_);
  }

  // find(name_of(i)) for every i < n, handed to found(i, result) in the order of i. The look-ups'
  // memory reads overlap: a name's table slot is fetched kAhead names before it is probed, its
  // record kAhead / 2 names before and the record's name kAhead / 4 before (issue 16: two million
  // look-ups in a table and records far larger than the caches, each waiting for memory in turn,
  // were a tenth of reading a 1,000,000-manhole map). The same results as find().
  template <class NameOf, class Found>
  void find_each(std::size_t n, NameOf name_of, Found found) const {
    constexpr std::size_t kAhead = 16;
    std::array<std::size_t, kAhead> hashes{};
    auto fetch_slot = [&](std::size_t i) {
      const std::size_t h = std::hash<std::string_view>{}(name_of(i)) & mask_;
      hashes[i % kAhead] = h;
      __builtin_prefetch(&slots_[h]);
    };
    auto fetch_record = [&](std::size_t i) {
      const std::uint32_t r = slots_[hashes[i % kAhead]];
      if (r != kEmpty) __builtin_prefetch(names_.record(r));
    };
    auto fetch_name = [&](std::size_t i) {
      const std::uint32_t r = slots_[hashes[i % kAhead]];
      if (r != kEmpty) __builtin_prefetch(names_[r].data());
    };
    for (std::size_t i = 0; i < n && i < kAhead; ++i) fetch_slot(i);
    for (std::size_t i = 0; i < n && i < kAhead / 2; ++i) fetch_record(i);
    for (std::size_t i = 0; i < n && i < kAhead / 4; ++i) fetch_name(i);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t h = hashes[i % kAhead];
      if (i + kAhead < n) fetch_slot(i + kAhead);
      if (i + kAhead / 2 < n) fetch_record(i + kAhead / 2);
      if (i + kAhead / 4 < n) fetch_name(i + kAhead / 4);
      found(i, probe(name_of(i), h));
    }
  }

 private:
  std::optional<std::uint32_t> probe(std::string_view name, std::size_t h) const {
    for (; slots_[h] != kEmpty; h = (h + 1) & mask_) {
      if (names_[slots_[h]] == name) return slots_[h];
    }
    return std::nullopt;
  }

  static constexpr std::uint32_t kEmpty = 0xffffffffU;
  Names names_;
  std::vector<std::uint32_t> slots_;
  std::size_t mask_ = 0;
};

}  // namespace

Locator line_locator(std::string file) {
  return [file = std::move(file)](const RecordRef& ref, std::string_view) {
    return ref.line > 0 ? file + ":" + std::to_string(ref.line) : file;
  };
}

MapBuilder::MapBuilder(std::string map_name, Locator locator)
    : name_(to_utf8_lossy(map_name)), locator_(std::move(locator)) {}

MapBuilder::Name MapBuilder::keep(std::string_view name) {
  if (name.size() >= Name::kNone || names_.size() > Name::kNone - name.size()) {
    names_overflow_ = true;  // build() says so; the name is not kept
    return Name{0, 0};
  }
  const Name n{static_cast<std::uint32_t>(names_.size()), static_cast<std::uint32_t>(name.size())};
  names_.append(name);
  return n;
}

void MapBuilder::add_manhole(ManholeRecord record) {
  StoredManhole m{.name = keep(record.name),
                  .position = record.position,
                  .diameter_m = record.diameter_m,
                  .shaft_length_m = record.shaft_length_m.value_or(0),
                  .shaft_width_m = record.shaft_width_m.value_or(0),
                  .depth_m = record.depth_m.value_or(0),
                  .line = record.line,
                  .exit = record.exit,
                  .variant = record.variant.value_or('\0'),
                  .given = 0};
  if (record.variant) m.given |= kVariant;
  if (record.shaft_length_m) m.given |= kShaftLength;
  if (record.shaft_width_m) m.given |= kShaftWidth;
  if (record.depth_m) m.given |= kDepth;
  manholes_.push_back(m);
  slot_end_.push_back(static_cast<std::uint32_t>(slots_.size()));
  for (SlotRecord& slot : record.slots) add_slot(std::move(slot));
}

void MapBuilder::add_slot(SlotRecord slot) {
  SEWER_CHECK(!manholes_.empty(), "add_slot before any add_manhole");
  slots_.push_back({.pipe = keep(slot.pipe),
                    .azimuth_deg = slot.azimuth_deg,
                    .invert_z_m = slot.invert_z_m,
                    .line = slot.line});
  slot_end_.back() = static_cast<std::uint32_t>(slots_.size());
}

std::span<const MapBuilder::StoredSlot> MapBuilder::slots_of(std::size_t manhole) const {
  const std::uint32_t begin = manhole == 0 ? 0 : slot_end_[manhole - 1];
  return std::span<const StoredSlot>(slots_).subspan(begin, slot_end_[manhole] - begin);
}

void MapBuilder::add_pipe(PipeRecord record) {
  StoredPipe p{.name = keep(record.name),
               .from = record.from ? keep(*record.from) : Name{},
               .to = record.to ? keep(*record.to) : Name{},
               .length_m = record.length_m,
               .diameter_m = record.diameter_m,
               .height_m = record.height_m.value_or(0),
               .blockage_risk = record.blockage_risk.value_or(0),
               .line = record.line,
               .shape = record.shape,
               .given = 0};
  if (record.height_m) p.given |= kHeight;
  if (record.blockage_risk) p.given |= kBlockageRisk;
  pipes_.push_back(p);
}
void MapBuilder::add_point(PointRecord record) { points_.push_back(std::move(record)); }
void MapBuilder::add_finding(FindingRecord record) { findings_.push_back(std::move(record)); }
void MapBuilder::set_name(std::string map_name) { name_ = to_utf8_lossy(map_name); }
void MapBuilder::set_crs(std::optional<Crs> crs) { crs_ = std::move(crs); }

SewerMap MapBuilder::with_crs(SewerMap map, std::optional<Crs> crs) {
  map.crs_ = std::move(crs);
  return map;
}

SewerMap MapBuilder::add_findings(SewerMap map, std::vector<FindingRecord> findings,
                                  const Locator& locator, Diagnostics& diagnostics) {
  std::size_t unknown = 0;
  std::string first_unknown;
  for (std::uint32_t i = 0; i < findings.size(); ++i) {
    FindingRecord& r = findings[i];
    const std::optional<PipeId> pipe = map.find_pipe(r.pipe);
    if (!pipe) {
      if (unknown++ == 0) first_unknown = r.pipe;
      continue;
    }
    const double length = map.pipe(*pipe).length_m;
    double offset = r.against_flow ? length - r.station_m : r.station_m;
    if (!(offset >= 0 && offset <= length)) {
      const double clamped = std::clamp(std::isfinite(offset) ? offset : 0.0, 0.0, length);
      const LimitText t = limit_text(r.station_m, r.station_m < 0 ? 0.0 : length);
      diagnostics.warning(locator(RecordRef{Kind::kFinding, i, 0, r.line}, "station"),
                          "finding " + input_text(r.code) + " in pipe " + input_text(r.pipe) +
                              ": station " + t.value + " m lies off the pipe (0 to " +
                              limit_text(length, r.station_m).value + " m): placed at " +
                              format_number(clamped) + " m");
      offset = clamped;
    }
    map.findings_.push_back({.pipe = *pipe,
                             .code = std::move(r.code),
                             .characterisation = std::move(r.characterisation),
                             .offset_m = offset,
                             .quantity1 = r.quantity1,
                             .quantity2 = r.quantity2});
  }
  if (unknown > 0) {
    diagnostics.warning(locator(RecordRef{}, ""),
                        std::to_string(unknown) + " findings name no pipe of the map (the first: " +
                            input_quoted(first_unknown) + "): left out");
  }
  std::stable_sort(map.findings_.begin(), map.findings_.end(),
                   [](const Finding& a, const Finding& b) {
                     return a.pipe < b.pipe || (a.pipe == b.pipe && a.offset_m < b.offset_m);
                   });
  return map;
}

void MapBuilder::reserve(std::size_t manholes, std::size_t pipes, std::size_t slots) {
  detail::reserve_huge(manholes_, manholes);
  detail::reserve_huge(slot_end_, manholes);
  detail::reserve_huge(slots_, slots);
  detail::reserve_huge(pipes_, pipes);
}

void MapBuilder::reserve_names(std::size_t bytes) {
  if (names_.capacity() >= bytes) return;
  names_.reserve(bytes);
  detail::advise_huge_pages(names_.data(), names_.capacity());
}

// The checks of build(), one function per concern so that each stays readable.
class MapBuilder::Validation {
 public:
  Validation(MapBuilder& b, Diagnostics& d) : b_(b), d_(d), before_(d.mark()) {}

  Result<SewerMap> run() {
    SewerMap map;
    map.name_ = std::move(b_.name_);
    map.crs_ = std::move(b_.crs_);
    SortedNames manholes =
        sorted_names(manhole_names(), "manhole", Kind::kManhole, b_.locator_, d_);
    map.manholes_by_name_ = std::move(manholes.order);
    SortedNames pipes =
        sorted_names(RecordNames(b_.pipes_, StoredName{&b_}), "pipe", Kind::kPipe, b_.locator_, d_);
    map.pipes_by_name_ = std::move(pipes.order);
    pipes_unique_ = pipes.unique;
    map.points_by_name_ = sorted_names(RecordNames(b_.points_, OwnName{}), "inspection point",
                                       Kind::kPoint, b_.locator_, d_)
                              .order;
    check_numbers();
    manhole_index_.emplace(manhole_names(), manholes.unique);
    build_pipes(map);
    manhole_index_.reset();
    match_slots_from_pipes(map);
    build_manholes(map);
    std::vector<std::uint32_t>().swap(slot_pipe_);
    check_unmatched_pipe_ends(map);
    build_points(map);
    pipe_index_.reset();
    if (d_.has_errors_since(before_))
      return Error{ErrorCode::kInvalidMap, d_.error_summary(before_)};
    warn_about_topology(map);
    if (b_.findings_.empty()) return map;
    return MapBuilder::add_findings(std::move(map), std::move(b_.findings_), b_.locator_, d_);
  }

 private:
  // A stored record's name.
  struct StoredName {
    const MapBuilder* b;
    template <class Record>
    std::string_view operator()(const Record& r) const {
      return b->name(r.name);
    }
  };
  using ManholeNames = RecordNames<StoredManhole, StoredName>;
  ManholeNames manhole_names() const { return {b_.manholes_, StoredName{&b_}}; }
  // A record's name as a message shows it (control characters escaped: message_text.h).
  std::string name(Name n) const { return input_text(b_.name(n)); }

  std::string at(Kind kind, std::uint32_t index, std::uint32_t line, std::string_view field,
                 std::uint32_t slot = 0) const {
    return b_.locator_(RecordRef{kind, index, slot, line}, field);
  }

  // Where a field of a record is; computed only when a problem is reported, since a valid map of a
  // million objects would otherwise build millions of location strings for nothing.
  struct FieldRef {
    Kind kind;
    std::uint32_t index;
    std::uint32_t line;
    std::string_view field;
    std::uint32_t slot = 0;
  };

  std::string at(const FieldRef& f) const { return at(f.kind, f.index, f.line, f.field, f.slot); }

  template <class Object>
  void require_positive(double v, std::string_view what, const Object& object, const FieldRef& f) {
    if (!std::isfinite(v) || v <= 0) {
      d_.error(at(f), object() + ": " + std::string(what) +
                          " must be a positive number of metres, got " + format_number(v));
    }
  }

  template <class Object>
  void require_finite(double v, std::string_view what, const Object& object, const FieldRef& f) {
    if (!std::isfinite(v)) {
      d_.error(at(f), object() + ": " + std::string(what) + " must be a finite number, got " +
                          format_number(v));
    }
  }

  // Numbers beyond core/limits.h: later stages (costs in integer milliseconds) could not hold them.
  template <class Object>
  void require_at_most(double v, double limit, std::string_view what, const Object& object,
                       const FieldRef& f) {
    if (std::isfinite(v) && std::abs(v) > limit) {
      const LimitText t = limit_text(v, v < 0 ? -limit : limit);
      d_.error(at(f), object() + ": " + std::string(what) + " must be at most " +
                          limit_text(limit, std::abs(v)).value + " m, got " + t.value);
    }
  }

  void check_numbers() {
    for (std::uint32_t i = 0; i < b_.manholes_.size(); ++i) check_manhole_numbers(i);
    for (std::uint32_t i = 0; i < b_.pipes_.size(); ++i) check_pipe_numbers(i);
  }

  void check_manhole_numbers(std::uint32_t i) {
    const StoredManhole& m = b_.manholes_[i];
    auto object = [&] { return "manhole " + name(m.name); };
    require_positive(m.diameter_m, "diameter", object, {Kind::kManhole, i, m.line, "diameter_m"});
    require_finite(m.position.x_m, "x", object, {Kind::kManhole, i, m.line, "x_m"});
    require_finite(m.position.y_m, "y", object, {Kind::kManhole, i, m.line, "y_m"});
    require_finite(m.position.z_m, "z", object, {Kind::kManhole, i, m.line, "z_m"});
    require_at_most(m.diameter_m, kMaxDiameter_m, "diameter", object,
                    {Kind::kManhole, i, m.line, "diameter_m"});
    require_at_most(m.position.x_m, kMaxCoordinate_m, "x", object,
                    {Kind::kManhole, i, m.line, "x_m"});
    require_at_most(m.position.y_m, kMaxCoordinate_m, "y", object,
                    {Kind::kManhole, i, m.line, "y_m"});
    require_at_most(m.position.z_m, kMaxCoordinate_m, "z", object,
                    {Kind::kManhole, i, m.line, "z_m"});
    if ((m.given & kVariant) != 0 && (m.variant < 'A' || m.variant > 'Z')) {
      d_.error(at(Kind::kManhole, i, m.line, "variant"),
               object() + ": variant must be one capital letter A..Z");
    }
    const std::span<const StoredSlot> slots = b_.slots_of(i);
    for (std::uint32_t s = 0; s < slots.size(); ++s) {
      const StoredSlot& slot = slots[s];
      auto slot_object = [&] { return object() + " slot " + std::to_string(s + 1); };
      require_finite(slot.azimuth_deg, "azimuth", slot_object,
                     {Kind::kSlot, i, slot.line, "azimuth_deg", s});
      require_finite(slot.invert_z_m, "invert", slot_object,
                     {Kind::kSlot, i, slot.line, "invert_m", s});
      require_at_most(slot.invert_z_m, kMaxCoordinate_m, "invert", slot_object,
                      {Kind::kSlot, i, slot.line, "invert_m", s});
    }
    for (auto [v, bit, field] : {std::tuple{m.shaft_length_m, kShaftLength, "shaft_length_m"},
                                 std::tuple{m.shaft_width_m, kShaftWidth, "shaft_width_m"},
                                 std::tuple{m.depth_m, kDepth, "depth_m"}}) {
      if ((m.given & bit) != 0)
        require_positive(v, field, object, {Kind::kManhole, i, m.line, field});
    }
    if (slots.size() > kMaxSlotsPerManhole) {
      d_.error(at(Kind::kManhole, i, m.line, "slots"),
               object() + ": " + std::to_string(slots.size()) +
                   " pipe ends (slots); a manhole has at most " +
                   std::to_string(kMaxSlotsPerManhole));
    }
  }

  void check_pipe_numbers(std::uint32_t i) {
    const StoredPipe& p = b_.pipes_[i];
    auto object = [&] { return "pipe " + name(p.name); };
    require_positive(p.length_m, "length", object, {Kind::kPipe, i, p.line, "length_m"});
    require_positive(p.diameter_m, "diameter", object, {Kind::kPipe, i, p.line, "diameter_m"});
    require_at_most(p.length_m, kMaxLength_m, "length", object,
                    {Kind::kPipe, i, p.line, "length_m"});
    require_at_most(p.diameter_m, kMaxDiameter_m, "diameter", object,
                    {Kind::kPipe, i, p.line, "diameter_m"});
    if ((p.given & kHeight) != 0) {
      require_positive(p.height_m, "height", object, {Kind::kPipe, i, p.line, "height_m"});
      require_at_most(p.height_m, kMaxDiameter_m, "height", object,
                      {Kind::kPipe, i, p.line, "height_m"});
    }
    if ((p.given & kBlockageRisk) != 0 && !(p.blockage_risk >= 0 && p.blockage_risk <= 1)) {
      d_.error(at(Kind::kPipe, i, p.line, "blockage_risk"),
               object() + ": blockage_risk must be between 0 and 1, got " +
                   limit_text(p.blockage_risk, p.blockage_risk < 0 ? 0.0 : 1.0).value);
    }
  }

  // `m`: the manhole named `name`, if any (looked up before).
  std::optional<ManholeId> resolve_end(Name end, std::optional<std::uint32_t> m, std::uint32_t pipe,
                                       std::string_view field) {
    if (!end.given()) return std::nullopt;
    const StoredPipe& p = b_.pipes_[pipe];
    if (!m) {
      d_.error(at(Kind::kPipe, pipe, p.line, field),
               "pipe " + name(p.name) + ": " + std::string(field) + " names unknown manhole " +
                   "'" + name(end) + "'");
      return std::nullopt;
    }
    return ManholeId{*m};
  }

  void build_pipes(SewerMap& map) {
    // Every end's manhole looked up at once (NameIndex::find_each), 2 * pipe + end.
    std::vector<std::optional<std::uint32_t>> ends;
    detail::reserve_huge(ends, 2 * b_.pipes_.size());
    manhole_index_->find_each(
        2 * b_.pipes_.size(),
        [&](std::size_t k) {
          return b_.name(k % 2 == 0 ? b_.pipes_[k / 2].from : b_.pipes_[k / 2].to);
        },
        [&](std::size_t, std::optional<std::uint32_t> m) { ends.push_back(m); });
    detail::reserve_huge(map.pipes_, b_.pipes_.size());
    for (std::uint32_t i = 0; i < b_.pipes_.size(); ++i) {
      const StoredPipe& r = b_.pipes_[i];
      Pipe p;
      p.ends[0].manhole = resolve_end(r.from, ends[2 * std::size_t{i}], i, "from");
      p.ends[1].manhole = resolve_end(r.to, ends[2 * std::size_t{i} + 1], i, "to");
      if (p.ends[0].manhole && p.ends[0].manhole == p.ends[1].manhole) {
        d_.error(at(Kind::kPipe, i, r.line, "to"),
                 "pipe " + name(r.name) + ": joins manhole " + name(r.from) + " to itself");
      }
      p.length_m = r.length_m;
      p.diameter_m = r.diameter_m;
      p.shape = r.shape;
      p.height_m = (r.given & kHeight) != 0 ? r.height_m : r.diameter_m;
      if ((r.given & kBlockageRisk) != 0) p.blockage_risk = r.blockage_risk;
      p.name = b_.name(r.name);
      map.pipes_.push_back(std::move(p));
    }
    slot_seen_.assign(2 * map.pipes_.size(), false);
  }

  // Issue 16: the slots of a valid map need no look-up by name (a million of them were a seventh
  // of reading a 1,000,000-manhole map). Each pipe end, resolved to its manhole already, finds its
  // slot among that manhole's few: a slot found so names that pipe, and as names are unique when
  // no error was reported, the look-up would give the same pipe. Only after an error, or for a
  // slot no pipe end found, does build_slot look the name up (and report what is wrong).
  void match_slots_from_pipes(const SewerMap& map) {
    if (d_.has_errors_since(before_)) return;
    slot_pipe_.assign(b_.slots_.size(), kNoPipe);
    for (std::uint32_t i = 0; i < map.pipes_.size(); ++i) {
      const Pipe& p = map.pipes_[i];
      for (const PipeEnd& end : p.ends) {
        if (!end.manhole) continue;
        const std::size_t m = end.manhole->index();
        const std::uint32_t first = m == 0 ? 0 : b_.slot_end_[m - 1];
        for (std::uint32_t s = first; s < b_.slot_end_[m]; ++s) {
          if (slot_pipe_[s] == kNoPipe && b_.name(b_.slots_[s].pipe) == p.name) {
            slot_pipe_[s] = i;
            break;
          }
        }
      }
    }
  }

  // The pipe named `name`, by the pipe of the slot `flat` (match_slots_from_pipes) or by name.
  std::optional<std::uint32_t> find_pipe(const SewerMap& map, std::string_view name,
                                         std::size_t flat) {
    if (flat < slot_pipe_.size() && slot_pipe_[flat] != kNoPipe) return slot_pipe_[flat];
    // Built only when needed: map.pipes_ is complete, its names stay where they are.
    if (!pipe_index_) pipe_index_.emplace(RecordNames(map.pipes_, OwnName{}), pipes_unique_);
    return pipe_index_->find(name);
  }

  void build_manholes(SewerMap& map) {
    detail::reserve_huge(map.manholes_, b_.manholes_.size());
    detail::reserve_huge(map.slots_, b_.slots_.size());
    for (std::uint32_t i = 0; i < b_.manholes_.size(); ++i) {
      const StoredManhole& r = b_.manholes_[i];
      Manhole m;
      m.position = r.position;
      m.diameter_m = r.diameter_m;
      m.exit = r.exit;
      if ((r.given & kVariant) != 0) m.variant = r.variant;
      if ((r.given & kShaftLength) != 0) m.shaft_length_m = r.shaft_length_m;
      if ((r.given & kShaftWidth) != 0) m.shaft_width_m = r.shaft_width_m;
      if ((r.given & kDepth) != 0) m.depth_m = r.depth_m;
      m.first_slot = static_cast<std::uint32_t>(map.slots_.size());
      m.slot_count =
          static_cast<std::uint16_t>(std::min<std::size_t>(b_.slots_of(i).size(), 0xffff));
      for (std::uint16_t s = 0; s < m.slot_count; ++s) {
        map.slots_.push_back(build_slot(map, ManholeId{i}, SlotIndex{s}));
      }
      map.manholes_.push_back(std::move(m));
    }
    for (std::size_t i = 0; i < b_.manholes_.size(); ++i) {
      map.manholes_[i].name = b_.name(b_.manholes_[i].name);
    }
  }

  Slot build_slot(SewerMap& map, ManholeId manhole, SlotIndex index) {
    const StoredManhole& r = b_.manholes_[manhole.index()];
    const StoredSlot& rs = b_.slots_of(manhole.index())[index.index()];
    const auto flat = static_cast<std::size_t>(&rs - b_.slots_.data());
    Slot slot;
    slot.azimuth_deg = rs.azimuth_deg;
    slot.invert_z_m = rs.invert_z_m;
    auto where = [&] { return at(Kind::kSlot, manhole.value(), rs.line, "pipe", index.value()); };
    auto object = [&] {
      return "manhole " + name(r.name) + " slot " + std::to_string(index.value() + 1);
    };
    auto pipe = find_pipe(map, b_.name(rs.pipe), flat);
    if (!pipe) {
      d_.error(where(), object() + " names unknown pipe " + "'" + name(rs.pipe) + "'");
      return slot;
    }
    Pipe& p = map.pipes_[*pipe];
    slot.pipe = PipeId{*pipe};
    if (joins_itself(p)) return slot;  // build_pipes said so: one error, not three
    int end = p.ends[0].manhole == manhole ? 0 : p.ends[1].manhole == manhole ? 1 : -1;
    if (end < 0) {
      d_.error(where(), object() + " names pipe " + input_text(p.name) + ", but " +
                            input_text(p.name) + " " + describe_ends(p));
      return slot;
    }
    auto e = static_cast<std::size_t>(end);
    if (slot_seen_[2 * pipe.value() + e]) {
      d_.error(where(), object() + " names pipe " + input_text(p.name) + " a second time");
      return slot;
    }
    slot_seen_[2 * pipe.value() + e] = true;
    slot.pipe_end = static_cast<std::uint8_t>(end);
    p.ends[e].slot = index;
    return slot;
  }

  // A pipe from a manhole to itself: an error of its own (build_pipes), whose slots are not
  // checked, since no slot could be right.
  static bool joins_itself(const Pipe& p) {
    return p.ends[0].manhole && p.ends[0].manhole == p.ends[1].manhole;
  }

  std::string describe_ends(const Pipe& p) const {
    auto end = [&](const PipeEnd& e) {
      return e.manhole ? "manhole " + name(b_.manholes_[e.manhole->index()].name)
                       : std::string("a blind end");
    };
    return "joins " + end(p.ends[0]) + " and " + end(p.ends[1]);
  }

  void check_unmatched_pipe_ends(const SewerMap& map) {
    for (std::uint32_t i = 0; i < map.pipes_.size(); ++i) {
      const Pipe& p = map.pipes_[i];
      for (std::size_t e = 0; e < 2; ++e) {
        if (p.ends[e].manhole && !slot_seen_[2 * i + e] && !joins_itself(p)) {
          const std::string m = input_text(map.manholes_[p.ends[e].manhole->index()].name);
          d_.error(at(Kind::kPipe, i, b_.pipes_[i].line, e == 0 ? "from" : "to"),
                   "pipe " + input_text(p.name) + " ends in manhole " + m + ", but " + m +
                       " has no slot for it");
        }
      }
    }
  }

  void build_points(SewerMap& map) {
    detail::reserve_huge(map.points_, b_.points_.size());
    for (std::uint32_t i = 0; i < b_.points_.size(); ++i) {
      PointRecord& r = b_.points_[i];
      InspectionPoint point;
      point.offset_m = r.offset_m;
      auto pipe = find_pipe(map, r.pipe, kNoPipe);
      if (!pipe) {
        d_.error(at(Kind::kPoint, i, r.line, "pipe"), "inspection point " + input_text(r.name) +
                                                          " names unknown pipe " +
                                                          input_quoted(r.pipe));
      } else {
        point.pipe = PipeId{*pipe};
        const double length = map.pipes_[*pipe].length_m;
        if (!(r.offset_m >= 0 && r.offset_m <= length)) {
          const LimitText t = limit_text(r.offset_m, r.offset_m < 0 ? 0.0 : length);
          d_.error(at(Kind::kPoint, i, r.line, "offset_m"),
                   "inspection point " + input_text(r.name) + ": offset " + t.value +
                       " m is outside pipe " + r.pipe + " (0 to " +
                       limit_text(length, r.offset_m).value + " m)");
        }
      }
      point.name = std::move(r.name);
      map.points_.push_back(std::move(point));
    }
  }

  void warn_about_topology(const SewerMap& map) {
    if (map.manhole_count() == 0) {
      // Nothing to plan on: not an error for a library that builds maps piece by piece, but no
      // network (`validate --strict` fails on it).
      d_.warning(at(Kind::kMap, 0, 0, ""), "the network is empty: no manholes and no pipes");
      return;
    }
    for (ManholeId m : map.manhole_ids()) {
      if (map.manhole(m).slot_count == 0) {
        d_.warning(at(Kind::kManhole, m.value(), b_.manholes_[m.index()].line, ""),
                   "manhole " + input_text(map.manhole(m).name) + " has no pipes");
      }
    }
    const Components components = connected_components(map);
    if (components.count > 1) {
      std::ostringstream msg;
      msg << "the network falls into " << components.count << " disconnected parts (sizes";
      std::vector<std::uint32_t> sizes = components.sizes;
      std::sort(sizes.rbegin(), sizes.rend());
      for (std::size_t k = 0; k < sizes.size() && k < 5; ++k) msg << ' ' << sizes[k];
      if (sizes.size() > 5) msg << " ...";
      msg << " manholes)";
      d_.warning(at(Kind::kMap, 0, 0, ""), msg.str());
    }
  }

  MapBuilder& b_;
  Diagnostics& d_;
  Diagnostics::Mark before_;     // errors before the build are the caller's
  std::vector<bool> slot_seen_;  // per pipe end: 2 * pipe + end
  static constexpr std::uint32_t kNoPipe = 0xffffffffU;
  std::vector<std::uint32_t> slot_pipe_;  // per slot of b_.slots_: its pipe, or kNoPipe
  std::optional<NameIndex<ManholeNames>> manhole_index_;
  std::optional<NameIndex<RecordNames<Pipe, OwnName>>> pipe_index_;
  bool pipes_unique_ = true;  // no two pipes share a name (sorted_names)
};

Result<SewerMap> MapBuilder::build(Diagnostics& diagnostics) && {
  if (names_overflow_) {
    const std::string message =
        "the names of the map's records take more than 4 GiB, more than sewerplan reads";
    const std::string where = locator_ ? locator_(RecordRef{}, "") : name_;  // the file, as a rule
    diagnostics.error(where, message);
    return Error{ErrorCode::kInvalidMap, where + ": " + message};
  }
  return Validation(*this, diagnostics).run();
}

}  // namespace sewerplan
