// SPDX-License-Identifier: MIT
// MoveMap: the cheapest move between two places of a tour shape (tour_shape.h), by key
// (at * places + to), where places are too many for a places x places matrix.
//
// One flat open-addressing table (linear probing, at most half full) sized once for all the
// moves it may hold: a node-based hash map's 160,000 nodes were freed one by one after a stop,
// milliseconds between the last stop check and the return (issue 14), a flat table is one block.
// Its slots are laid out in slices with a stop check between them (fresh memory is what costs).
// Keys are never removed. Private to search.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "sewerplan/core/check.h"
#include "sewerplan/core/stop_condition.h"
#include "sewerplan/domain/compiled_task.h"

namespace sewerplan::search::detail {

class MoveMap {
 public:
  struct Move {
    domain::Cost cost = 0;
    domain::ActionId action{0};
  };

  // Room for `keys` keys; false if `stop` (may be null) fired, then the map is empty. Called once,
  // before any insert.
  bool reserve(std::size_t keys, const StopCondition* stop) {
    const std::size_t capacity = std::bit_ceil(std::max<std::size_t>(2 * keys, kMinCapacity));
    slots_.reserve(capacity);
    while (slots_.size() < capacity) {
      if (stop != nullptr && stop->interrupted()) {
        slots_ = {};
        return false;
      }
      slots_.resize(std::min(capacity, slots_.size() + kSlice));
    }
    mask_ = capacity - 1;
    shift_ = 64 - std::countr_zero(capacity);
    return true;
  }

  // The move under `key`, or null.
  const Move* find(std::int64_t key) const {
    if (slots_.empty()) return nullptr;
    for (std::size_t i = home(key);; i = (i + 1) & mask_) {
      const Slot& s = slots_[i];
      if (s.key == key) return &s.move;
      if (s.key == kEmpty) return nullptr;
    }
  }
  bool contains(std::int64_t key) const { return find(key) != nullptr; }

  // The move under `key`, added as `move` if there was none (then the bool is true). The map
  // must have room: at most the reserved number of keys.
  std::pair<Move*, bool> try_emplace(std::int64_t key, Move move) {
    // read_shape reserves a slot pair per action, and each action adds at most one move.
    SEWER_CHECK(2 * (size_ + 1) <= slots_.size(), "MoveMap: more keys than reserved");
    for (std::size_t i = home(key);; i = (i + 1) & mask_) {
      Slot& s = slots_[i];
      if (s.key == key) return {&s.move, false};
      if (s.key == kEmpty) {
        s.key = key;
        s.move = move;
        ++size_;
        return {&s.move, true};
      }
    }
  }

  std::size_t size() const { return size_; }

 private:
  static constexpr std::int64_t kEmpty = -1;  // keys are at least 0
  static constexpr std::size_t kMinCapacity = 16;
  static constexpr std::size_t kSlice = 16384;  // slots laid out between two checks, 384 KB

  struct Slot {
    std::int64_t key = kEmpty;
    Move move;
  };

  std::size_t home(std::int64_t key) const {
    // Fibonacci hashing (the product's top bits): one place's neighbouring keys spread out.
    return static_cast<std::size_t>((static_cast<std::uint64_t>(key) * 0x9E3779B97F4A7C15ULL) >>
                                    shift_);
  }

  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
  int shift_ = 64;
  std::size_t size_ = 0;
};

}  // namespace sewerplan::search::detail
