// SPDX-License-Identifier: MIT
// The job protocol's byte layouts shared by its encoder (job_protocol.cc) and decoder
// (message_decoder.cc): little-endian integers, binary64 numbers, status flags (hal/src/can only).
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>

#include "sewerplan/hal/can/job_protocol.h"

namespace sewerplan::hal::wire {

inline constexpr std::uint8_t kHeadLifted = 0x01;
inline constexpr std::uint8_t kBeaconOn = 0x02;
// A RESULT's flags byte only (not the status's): the job drove through water (JobReport::in_water).
inline constexpr std::uint8_t kInWater = 0x04;
inline constexpr std::size_t kStatusFrames = 3;  // battery, odometry, elapsed
// A RESULT's header frame: outcome, flags, reason length; and with an observation, its slot count.
inline constexpr std::size_t kResultHeaderBytes = 4;
inline constexpr std::size_t kObservationHeaderBytes = 6;
// ... and with a measured turn: byte 4 is kTurnMeasured, and one number follows the reason.
inline constexpr std::size_t kTurnHeaderBytes = 5;
inline constexpr std::uint8_t kTurnMeasured = 0x01;
// A RESULT's numbers before the reason: progress, duration, energy and the status.
inline constexpr std::size_t kResultNumberFrames = 3 + kStatusFrames;
// The frames of an observation of `slots` slots: the shaft, then per slot its direction (not for
// slots[0], always 0), step and diameter.
inline constexpr std::size_t observation_frames(std::size_t slots) { return 3 * slots; }

inline CanFrame frame_of(FrameId id, std::span<const std::uint8_t> bytes) {
  CanFrame frame;
  frame.id = to_can_id(id);
  frame.extended = true;
  frame.dlc = static_cast<std::uint8_t>(bytes.size());
  std::copy(bytes.begin(), bytes.end(), frame.data.begin());
  return frame;
}

inline std::array<std::uint8_t, 8> f64_bytes(double value) {
  const auto bits = std::bit_cast<std::uint64_t>(value);
  std::array<std::uint8_t, 8> bytes{};
  for (std::size_t i = 0; i < 8; ++i) bytes[i] = static_cast<std::uint8_t>(bits >> (8 * i));
  return bytes;
}

inline double f64_of(const CanFrame& frame) {
  std::uint64_t bits = 0;
  for (std::size_t i = 0; i < 8; ++i) bits |= std::uint64_t{frame.data[i]} << (8 * i);
  return std::bit_cast<double>(bits);
}

inline std::uint16_t u16_of(const CanFrame& frame, std::size_t at) {
  return static_cast<std::uint16_t>(frame.data[at] | (frame.data[at + 1] << 8));
}

inline void put_u16(std::uint8_t* at, std::uint16_t value) {
  at[0] = static_cast<std::uint8_t>(value & 0xffU);
  at[1] = static_cast<std::uint8_t>(value >> 8U);
}

inline std::uint8_t status_flags(const RobotStatus& s) {
  return static_cast<std::uint8_t>((s.head_lifted ? kHeadLifted : 0) |
                                   (s.beacon_on ? kBeaconOn : 0));
}

}  // namespace sewerplan::hal::wire
