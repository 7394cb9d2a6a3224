// SPDX-License-Identifier: MIT
// Vectors of a million records backed by transparent huge pages where the system offers them.
//
// Private to core. Reading a 1,000,000-manhole map fills about 1 GB of fresh memory; at 4 KB a
// page that was 280,000 page faults, a quarter of the reader's time, and the records' scattered
// reads missed the TLB (issue 16). Where the kernel gives huge pages on request (transparent_
// hugepage "madvise", Debian's default), a vector reserved here asks for them before its memory is
// first touched: one fault per 2 MB. Below 4 MB, or where the request is refused, it is an
// ordinary reserve; nothing else changes.
//
//   reserve_huge(records, count);  // then push_back as usual
//
// Thread safety: as std::vector::reserve.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <sys/mman.h>

namespace sewerplan::detail {

inline void advise_huge_pages(void* data, std::size_t bytes) {
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20U;
  if (bytes < 2 * kHuge) return;
  const auto begin = (reinterpret_cast<std::uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
  const auto end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kHuge - 1);
  if (end > begin) {
    // Advice only: a refusal leaves ordinary pages.
    (void)::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
  }
}

template <class T>
void reserve_huge(std::vector<T>& v, std::size_t n) {
  const bool fresh = v.capacity() < n;
  v.reserve(n);
  if (fresh) advise_huge_pages(v.data(), v.capacity() * sizeof(T));
}

}  // namespace sewerplan::detail
