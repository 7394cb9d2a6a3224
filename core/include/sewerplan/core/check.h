// SPDX-License-Identifier: MIT
// SEWER_CHECK: a safety invariant that stays on in release builds.
//
// Three tiers of errors in sewerplan: bugs (assert on hot paths, SEWER_CHECK where continuing
// would be worse than stopping, as in Abseil's CHECK), expected failures (Result<T>, result.h), and
// typed exceptions only at load and configuration boundaries. A failed SEWER_CHECK prints the
// condition, file and line to stderr and aborts: it marks a bug in sewerplan, never bad input.
//
//   SEWER_CHECK(id.index() < size_, "manhole id out of range");
//
// Thread safety: SEWER_CHECK shares nothing: use it on any thread.
#pragma once

namespace sewerplan::detail {
[[noreturn]] void check_failed(const char* condition, const char* file, int line,
                               const char* message);
}  // namespace sewerplan::detail

#define SEWER_CHECK(condition, message)                                             \
  do {                                                                              \
    if (!(condition)) [[unlikely]] {                                                \
      ::sewerplan::detail::check_failed(#condition, __FILE__, __LINE__, (message)); \
    }                                                                               \
  } while (false)
