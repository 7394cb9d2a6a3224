// SPDX-License-Identifier: MIT
// Rng: a small seeded random number generator with the same output on every platform.
//
// std::uniform_*_distribution are implementation-defined, so the same seed could give another
// network or fault scenario with another standard library. Rng is xoshiro256** (Blackman and
// Vigna 2018, "Scrambled linear pseudorandom number generators") seeded through splitmix64, with
// its own distributions. All randomness in sewerplan comes from an Rng passed in by the caller.
//
//   Rng rng(42);
//   double length_m = rng.uniform(20.0, 80.0);
//   if (rng.bernoulli(0.1)) { ... }
//
// Thread safety: An Rng is not thread-safe: one per thread (seed each from the run's seed).
#pragma once

#include <array>
#include <cstdint>

namespace sewerplan {

class Rng {
 public:
  explicit Rng(std::uint64_t seed);

  std::uint64_t next();
  // Uniform in [0, 1).
  double uniform01();
  // Uniform in [lo, hi).
  double uniform(double lo, double hi);
  // Uniform integer in [0, n); n > 0. Unbiased (Lemire's rejection method).
  std::uint64_t below(std::uint64_t n);
  bool bernoulli(double p);
  // A new generator whose stream is independent of this one (for per-run seeds).
  Rng split();

 private:
  std::array<std::uint64_t, 4> s_;
};

}  // namespace sewerplan
