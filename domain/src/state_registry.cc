// SPDX-License-Identifier: MIT
#include "sewerplan/domain/state_registry.h"

#include <algorithm>
#include <bit>

#include "sewerplan/core/check.h"

namespace sewerplan::domain {

StatePacker::StatePacker(const CompiledTask& task) {
  // First fit, variables in order; a variable never straddles two bins.
  std::uint32_t bin = 0;
  std::uint32_t used = 0;
  for (std::size_t v = 0; v < task.variable_count(); ++v) {
    const auto size =
        static_cast<std::uint64_t>(task.domain_size(VarId{static_cast<std::uint32_t>(v)}));
    const auto bits = static_cast<std::uint32_t>(size <= 1 ? 1 : std::bit_width(size - 1));
    if (used + bits > 64) {
      ++bin;
      used = 0;
    }
    const std::uint64_t mask = bits == 64 ? ~0ULL : (1ULL << bits) - 1;
    slots_.push_back({bin, used, mask});
    used += bits;
  }
  bins_ = bin + 1;
}

void StatePacker::pack(std::span<const std::int32_t> values, std::uint64_t* out) const {
  std::fill(out, out + bins_, 0);
  for (std::size_t v = 0; v < slots_.size(); ++v) {
    const Slot& s = slots_[v];
    out[s.bin] |= (static_cast<std::uint64_t>(values[v]) & s.mask) << s.shift;
  }
}

std::int32_t StatePacker::get(const std::uint64_t* packed, VarId var) const {
  const Slot& s = slots_[var.index()];
  return static_cast<std::int32_t>((packed[s.bin] >> s.shift) & s.mask);
}

void StatePacker::unpack(const std::uint64_t* packed, std::span<std::int32_t> out) const {
  for (std::size_t v = 0; v < slots_.size(); ++v) {
    out[v] = get(packed, VarId{static_cast<std::uint32_t>(v)});
  }
}

StateRegistry::StateRegistry(const CompiledTask& task) : packer_(task), scratch_(packer_.bins()) {
  table_.size = 64;
  table_.slots = std::make_unique_for_overwrite<std::uint32_t[]>(table_.size);
  std::fill_n(table_.slots.get(), table_.size, kEmpty);
}

const std::uint64_t* StateRegistry::packed(std::uint32_t id) const {
  return segments_[id / kSegmentStates].data() + (id % kSegmentStates) * packer_.bins();
}

std::uint64_t StateRegistry::hash(const std::uint64_t* p) const {
  std::uint64_t h = 0x9e3779b97f4a7c15ULL;
  for (std::size_t i = 0; i < packer_.bins(); ++i) {
    h ^= p[i] + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
  }
  return h;
}

bool StateRegistry::equal(const std::uint64_t* a, const std::uint64_t* b) const {
  return std::equal(a, a + packer_.bins(), b);
}

std::size_t StateRegistry::probe(const Table& table, std::uint64_t h) const {
  const std::size_t mask = table.size - 1;
  std::size_t i = h & mask;
  while (table.slots[i] != kEmpty && !equal(packed(table.slots[i]), scratch_.data())) {
    i = (i + 1) & mask;
  }
  return i;
}

void StateRegistry::grow_slice() {
  if (filled_ < next_.size) {
    // Allocated untouched: its pages are also faulted in a slice at a time.
    const std::size_t n = std::min(kFillSlice, next_.size - filled_);
    std::fill_n(next_.slots.get() + filled_, n, kEmpty);
    filled_ += n;
    return;
  }
  const std::size_t mask = next_.size - 1;
  const std::size_t end = std::min(moved_ + kMoveSlice, table_.size);
  for (; moved_ < end; ++moved_) {
    const std::uint32_t id = table_.slots[moved_];
    if (id == kEmpty) continue;
    std::size_t i = hash(packed(id)) & mask;
    while (next_.slots[i] != kEmpty) i = (i + 1) & mask;
    next_.slots[i] = id;
  }
  if (moved_ == table_.size) {
    table_ = std::move(next_);
    next_ = Table{};
    filled_ = 0;
    moved_ = 0;
  }
}

std::pair<StateId, bool> StateRegistry::insert(std::span<const std::int32_t> values) {
  packer_.pack(values, scratch_.data());
  if (next_.size == 0 && 4 * (size_ + 1) > table_.size) {
    next_.size = 2 * table_.size;
    next_.slots = std::make_unique_for_overwrite<std::uint32_t[]>(next_.size);
  }
  if (next_.size > 0) grow_slice();
  const std::uint64_t h = hash(scratch_.data());
  // While the states move, a state is in the next table (moved, or new since) or still only in
  // the current one; new states go to the next.
  Table& target = moving() ? next_ : table_;
  const std::size_t i = probe(target, h);
  if (target.slots[i] != kEmpty) return {StateId{target.slots[i]}, false};
  if (moving()) {
    const std::size_t j = probe(table_, h);
    if (table_.slots[j] != kEmpty) return {StateId{table_.slots[j]}, false};
  }
  SEWER_CHECK(size_ < kEmpty, "state registry full");
  // Never fails while the slices keep their promise (a table at most half full).
  SEWER_CHECK(2 * size_ < target.size, "state registry: hash table over half full");
  const auto id = static_cast<std::uint32_t>(size_);
  if (id % kSegmentStates == 0) segments_.emplace_back(kSegmentStates * packer_.bins());
  std::copy(scratch_.begin(), scratch_.end(),
            segments_.back().begin() +
                static_cast<std::ptrdiff_t>((id % kSegmentStates) * packer_.bins()));
  target.slots[i] = id;
  ++size_;
  return {StateId{id}, true};
}

void StateRegistry::unpack(StateId id, std::vector<std::int32_t>& out) const {
  SEWER_CHECK(id.index() < size_, "state id does not belong to this registry");
  out.resize(packer_.variables());
  packer_.unpack(packed(id.value()), out);
}

std::size_t StateRegistry::memory_bytes() const {
  return segments_.size() * kSegmentStates * packer_.bins() * sizeof(std::uint64_t) +
         (table_.size + next_.size) * sizeof(std::uint32_t);
}

}  // namespace sewerplan::domain
