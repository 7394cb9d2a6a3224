// SPDX-License-Identifier: MIT
// Strong integer IDs: a ManholeId cannot be passed where a PipeId is expected.
//
// Every object kind of the world model, and later every variable, action and state of a compiled
// task, is named by an ID of its own type, minted by the container that owns the objects (the
// SewerMap mints ManholeId and PipeId). IDs are dense indices from 0, so side arrays can be indexed
// by them. They carry no reference to their container: do not mix IDs of different maps or tasks.
// "No ID" is std::optional<Id>. There is no arithmetic on IDs.
//
//   using ManholeId = StrongId<struct ManholeTag>;
//   ManholeId m{3};
//   std::vector<double> depth(map.manhole_count());
//   depth[m.value()] = 2.5;
//   for (ManholeId id : id_range<ManholeId>(map.manhole_count())) { ... }
//
// Thread safety: Plain values: safe to copy and read from any thread.
#pragma once

#include <compare>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iterator>
#include <ostream>

namespace sewerplan {

template <class Tag, class Rep = std::uint32_t>
class StrongId {
 public:
  using rep_type = Rep;
  constexpr explicit StrongId(Rep value) : value_(value) {}
  constexpr Rep value() const { return value_; }
  // The value as an index into a side array.
  constexpr std::size_t index() const { return static_cast<std::size_t>(value_); }
  friend constexpr auto operator<=>(StrongId, StrongId) = default;
  friend std::ostream& operator<<(std::ostream& os, StrongId id) { return os << '#' << +id.value_; }

 private:
  Rep value_;
};

// A forward range over the IDs 0 .. count-1 of one kind.
template <class Id>
class IdRange {
 public:
  class iterator {
   public:
    using value_type = Id;
    using difference_type = std::ptrdiff_t;
    constexpr iterator() = default;
    constexpr explicit iterator(typename Id::rep_type v) : v_(v) {}
    constexpr Id operator*() const { return Id{v_}; }
    constexpr iterator& operator++() {
      ++v_;
      return *this;
    }
    constexpr iterator operator++(int) {
      iterator old = *this;
      ++v_;
      return old;
    }
    friend constexpr bool operator==(iterator, iterator) = default;

   private:
    typename Id::rep_type v_ = 0;
  };
  constexpr explicit IdRange(std::size_t count)
      : count_(static_cast<typename Id::rep_type>(count)) {}
  constexpr iterator begin() const { return iterator{0}; }
  constexpr iterator end() const { return iterator{count_}; }
  constexpr std::size_t size() const { return count_; }

 private:
  typename Id::rep_type count_;
};

template <class Id>
constexpr IdRange<Id> id_range(std::size_t count) {
  return IdRange<Id>(count);
}

}  // namespace sewerplan

template <class Tag, class Rep>
struct std::hash<sewerplan::StrongId<Tag, Rep>> {
  std::size_t operator()(sewerplan::StrongId<Tag, Rep> id) const noexcept {
    return std::hash<Rep>{}(id.value());
  }
};
