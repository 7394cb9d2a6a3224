// SPDX-License-Identifier: MIT
// Limits: the largest numbers a map and a robot profile may hold, so that every later stage can
// work with what validation accepted.
//
// Planning turns distances and speeds into integer milliseconds (domain/compiled_task.h), sums
// them along plans and compares them with the battery's bound; a pipe of 1e16 m passed `validate`
// and then stopped `plan` and `simulate` on an internal check (exit 134). Validation rejects what
// lies beyond these limits instead, naming the field; within them, a plan over a million pipes at
// the slowest speed still fits the planner's 64-bit costs with room to spare (1e5 m / 1e-3 m/s =
// 1e11 ms a pipe).
//
// Thread safety: Compile-time constants only: safe from any thread.
#pragma once

namespace sewerplan {

inline constexpr double kMaxLength_m = 100'000;         // a pipe: 100 km (real ones: metres to km)
inline constexpr double kMaxDiameter_m = 100;           // a pipe's or manhole's diameter, height
inline constexpr double kMaxCoordinate_m = 10'000'000;  // |x|, |y|, |z|, inverts: 10,000 km
// Pipe ends (slots) at one manhole: a real manhole has a few dozen connections at most. The
// passages through a manhole are its ordered pairs of slots, so this bounds a manhole's passages
// (9,900) and keeps every per-manhole listing small; 10,000 slots made it 10^8.
inline constexpr unsigned kMaxSlotsPerManhole = 100;
inline constexpr double kMinSpeed_mps = 0.001;  // a profile's speeds: 1 mm/s
inline constexpr double kMaxSpeed_mps = 100;
inline constexpr double kMaxBattery_wh = 1'000'000;  // 1 MWh
inline constexpr double kMinPower_w = 0.001;
inline constexpr double kMaxPower_w = 1'000'000;
inline constexpr double kMaxDuration_s = 1'000'000;  // a profile's fixed times (pass, sample)

}  // namespace sewerplan
