// SPDX-License-Identifier: MIT
// StateRegistry: every state a search has seen, bit-packed, each with a StateId.
//
// As in Fast Downward's state registry (state_registry.h there): a state's variable values are
// packed into 64-bit bins (StatePacker gives each variable just the bits its domain needs), the
// packed states live in one pool that grows in fixed segments (so earlier states never move), and a
// hash set of StateIds, hashing and comparing the packed bins, finds duplicates. Search data
// (g, parent, status) lives in side arrays indexed by StateId, owned by the search engine.
// Only the registry mints StateIds; they belong to one registry.
//
// The hash set grows without a pause (issue 14: a cancel within 1 ms): rehashing every state at
// once when the table doubled took milliseconds on a few hundred thousand states, between two
// checks of a search's stop condition. So the next table is prepared while the current one fills
// (from a quarter full, a slice of its slots set empty per insert), then the states move to it a
// slice of slots per insert (meanwhile a lookup asks both tables, and new states go to the new
// one): every insert does a bounded share of the growth. IDs are assigned in insertion order, so
// the table's layout never changes which ID a state gets.
//
// A sewer task's state is a position and a bit per task: one 64-bit bin for up to 40 tasks on a
// network of a million positions.
//
//   StateRegistry registry(task);
//   auto [id, inserted] = registry.insert(task.initial_state());
//   std::vector<std::int32_t> values;
//   registry.unpack(id, values);
//
// Thread-safety: a StateRegistry belongs to one thread (insert() grows it; even lookups are not
// safe while another thread inserts).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "sewerplan/domain/compiled_task.h"

namespace sewerplan::domain {

using StateId = StrongId<struct StateTag>;

class StatePacker {
 public:
  explicit StatePacker(const CompiledTask& task);
  std::size_t bins() const { return bins_; }
  std::size_t variables() const { return slots_.size(); }
  void pack(std::span<const std::int32_t> values, std::uint64_t* out) const;
  void unpack(const std::uint64_t* packed, std::span<std::int32_t> out) const;
  std::int32_t get(const std::uint64_t* packed, VarId var) const;

 private:
  struct Slot {
    std::uint32_t bin;
    std::uint32_t shift;
    std::uint64_t mask;  // unshifted
  };
  std::vector<Slot> slots_;
  std::size_t bins_ = 1;
};

class StateRegistry {
 public:
  explicit StateRegistry(const CompiledTask& task);

  // The state's ID, and whether it was new.
  std::pair<StateId, bool> insert(std::span<const std::int32_t> values);
  void unpack(StateId id, std::vector<std::int32_t>& out) const;
  std::size_t size() const { return size_; }
  std::size_t bins_per_state() const { return packer_.bins(); }
  // Bytes held: packed states and the hash table.
  std::size_t memory_bytes() const;

 private:
  // Small segments: each is fresh memory, touched between two stop checks of a search.
  static constexpr std::size_t kSegmentStates = 1024;
  static constexpr std::uint32_t kEmpty = 0xffffffffU;
  // Per insert while the table grows: slots of the next table set empty, then slots of the current
  // table whose states are moved. With the growth begun at a quarter full, the next table (twice
  // the size) is ready and filled before the current one is half full (2n / kFillSlice inserts
  // and n / kMoveSlice inserts, fewer than n / 4).
  static constexpr std::size_t kFillSlice = 256;
  static constexpr std::size_t kMoveSlice = 32;

  // Open addressing, linear probing; each slot kEmpty or a state's ID. Size a power of two.
  struct Table {
    std::unique_ptr<std::uint32_t[]> slots;
    std::size_t size = 0;
  };

  const std::uint64_t* packed(std::uint32_t id) const;
  std::uint64_t hash(const std::uint64_t* packed) const;
  bool equal(const std::uint64_t* a, const std::uint64_t* b) const;
  // The slot of `table` that holds the state packed in scratch_ (hash `h`), or the empty slot
  // that ends its probe.
  std::size_t probe(const Table& table, std::uint64_t h) const;
  // One insert's share of the growth: prepares or moves a slice; swaps the tables when all moved.
  void grow_slice();
  bool moving() const { return next_.size > 0 && filled_ == next_.size; }

  StatePacker packer_;
  std::vector<std::vector<std::uint64_t>> segments_;
  Table table_;
  Table next_;              // the table being prepared (size 0: none)
  std::size_t filled_ = 0;  // slots of next_ set to kEmpty
  std::size_t moved_ = 0;   // slots of table_ whose state is in next_ (once next_ is filled)
  std::size_t size_ = 0;
  std::vector<std::uint64_t> scratch_;
};

}  // namespace sewerplan::domain
