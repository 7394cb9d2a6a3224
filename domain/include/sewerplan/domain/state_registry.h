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
  static constexpr std::size_t kSegmentStates = 4096;
  static constexpr std::uint32_t kEmpty = 0xffffffffU;

  const std::uint64_t* packed(std::uint32_t id) const;
  std::uint64_t hash(const std::uint64_t* packed) const;
  bool equal(const std::uint64_t* a, const std::uint64_t* b) const;
  void grow_table();

  StatePacker packer_;
  std::vector<std::vector<std::uint64_t>> segments_;
  std::vector<std::uint32_t> table_;  // open addressing, linear probing; kEmpty or a state's ID
  std::size_t size_ = 0;
  std::vector<std::uint64_t> scratch_;
};

}  // namespace sewerplan::domain
