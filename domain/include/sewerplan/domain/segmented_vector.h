// SPDX-License-Identifier: MIT
// SegmentedVector: an array that grows a fixed-size segment at a time, so that no growth moves or
// copies the elements already stored.
//
// A search's side arrays (its data per StateId: search/) grow with the states it stores. A
// std::vector doubling under them copied everything stored into fresh memory at once: 4.7 ms at
// 16,000 states of enforced hill-climbing between two checks of its stop condition (issue 14: a
// cancel within 1 ms; on a loaded machine a first touch of a page costs 10 to 25 us). Here a
// growth allocates one segment of about kSegmentBytes of value-initialised elements (and now and
// then doubles the small table of segment pointers). After Fast Downward's SegmentedVector
// (algorithms/segmented_vector.h there).
//
//   SegmentedVector<NodeInfo> info;
//   info.grow_to(registry.size());
//   info[id.index()].g = 0;
//
// Thread-safety: as std::vector.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <memory>
#include <vector>

namespace sewerplan::domain {

template <typename T>
class SegmentedVector {
 public:
  static constexpr std::size_t kSegmentBytes = 16384;
  static constexpr std::size_t kSegmentSize =
      std::bit_floor(std::max<std::size_t>(kSegmentBytes / sizeof(T), 1));
  static constexpr std::size_t kSegmentBits = std::countr_zero(kSegmentSize);

  std::size_t size() const { return size_; }
  // Elements held, in use or not: whole segments.
  std::size_t capacity() const { return segments_.size() * kSegmentSize; }
  // Grows to `n` elements if it holds fewer; the new elements are value-initialised.
  void grow_to(std::size_t n) {
    while (capacity() < n) segments_.push_back(std::make_unique<T[]>(kSegmentSize));
    if (n > size_) size_ = n;
  }
  // Precondition: i < size().
  T& operator[](std::size_t i) { return segments_[i >> kSegmentBits][i & (kSegmentSize - 1)]; }
  const T& operator[](std::size_t i) const {
    return segments_[i >> kSegmentBits][i & (kSegmentSize - 1)];
  }

 private:
  std::vector<std::unique_ptr<T[]>> segments_;
  std::size_t size_ = 0;
};

}  // namespace sewerplan::domain
