// SPDX-License-Identifier: MIT
// ZeroedArray: an array of plain values that start as all-zero bytes and are never filled.
//
// Private to domain. A route search's arrays span every node of the position graph (5.4 million
// on a 1,000,000-manhole map: 64 MB), but a search stops at the battery's reach and touches a
// small part of them. Filled with a start value, every page was written (and, fresh, first
// zeroed by the kernel): a tenth of the whole `plan` on that map (issue 16). Here the memory
// comes from calloc, which takes fresh pages as they are (already zero) and writes nothing: only
// the pages a search writes ever become resident. A user encodes its start value as zero (a
// distance d as kInfiniteCost - d, a node n as n + 1). It only grows: an entry, once written, is
// the user's to restore.
//
//   ZeroedArray<Cost> left;   // kInfiniteCost - distance: zero is "not reached"
//   left.grow(graph.size());  // every new entry zero; nothing written
//   left[n] = kInfiniteCost - d;
//
// Thread safety: as a std::vector.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>

namespace sewerplan::domain::detail {

template <class T>
class ZeroedArray {
  static_assert(std::is_trivially_copyable_v<T>, "entries are copied and zeroed as bytes");

 public:
  ZeroedArray() = default;
  ZeroedArray(ZeroedArray&& other) noexcept
      : data_(std::move(other.data_)),
        size_(std::exchange(other.size_, 0)),
        capacity_(std::exchange(other.capacity_, 0)) {}
  ZeroedArray& operator=(ZeroedArray&& other) noexcept {
    data_ = std::move(other.data_);
    size_ = std::exchange(other.size_, 0);
    capacity_ = std::exchange(other.capacity_, 0);
    return *this;
  }

  std::size_t size() const { return size_; }
  T& operator[](std::size_t i) { return data_.get()[i]; }
  const T& operator[](std::size_t i) const { return data_.get()[i]; }

  // At least `n` entries; the new ones are zero. Room for twice the old size is taken at once
  // (untouched, it costs no memory), so growing by a few entries per call copies rarely.
  void grow(std::size_t n) {
    if (n <= size_) return;
    if (n > capacity_) {
      const std::size_t capacity = std::max(n, 2 * capacity_);
      std::unique_ptr<T, Free> data(static_cast<T*>(std::calloc(capacity, sizeof(T))));
      if (!data) throw std::bad_alloc();
      if (size_ > 0) std::memcpy(data.get(), data_.get(), size_ * sizeof(T));
      data_ = std::move(data);
      capacity_ = capacity;
    }
    size_ = n;
  }
  // The same for an array whose every entry is zero again (its user restored them): a larger block
  // is taken fresh, with nothing copied, so growing a clean array never touches its pages.
  void grow_clean(std::size_t n) {
    if (n <= size_) return;
    if (n > capacity_) {
      data_.reset();  // first: the old block is not needed for the new one
      data_.reset(static_cast<T*>(std::calloc(n, sizeof(T))));
      if (!data_) {
        size_ = capacity_ = 0;
        throw std::bad_alloc();
      }
      capacity_ = n;
    }
    size_ = n;
  }

 private:
  struct Free {
    void operator()(T* p) const { std::free(p); }
  };
  std::unique_ptr<T, Free> data_;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

}  // namespace sewerplan::domain::detail
