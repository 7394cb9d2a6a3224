// SPDX-License-Identifier: MIT
// CanFrame: one classic CAN 2.0 frame, the unit that every CAN bus (can_bus.h) carries.
//
// MAKRO's processors talk over a CAN bus (paper, section 2.3). A frame has an 11-bit (standard) or
// 29-bit (extended) identifier, up to 8 data bytes, or is a remote request (RTR) with a length and
// no data. sewerplan's job protocol (job_protocol.h) uses extended frames only; the transports
// (slcan.h, socketcan.h) carry any frame. A plain value: data bytes beyond `dlc` are always zero,
// so that == compares what is on the wire.
//
//   Result<CanFrame> f = make_can_frame(0x123, false, {0xde, 0xad});
//   std::cout << *f;  // "123#DEAD", the candump notation (candump.h)
//
// Thread safety: Plain values: safe to copy and read from any thread.
#pragma once

#include <array>
#include <cstdint>
#include <initializer_list>
#include <ostream>
#include <span>
#include <string>

#include "sewerplan/core/result.h"

namespace sewerplan::hal {

inline constexpr std::uint32_t kMaxStandardCanId = 0x7ff;
inline constexpr std::uint32_t kMaxExtendedCanId = 0x1fffffff;
inline constexpr std::size_t kMaxCanData = 8;

struct CanFrame {
  std::uint32_t id = 0;
  bool extended = false;  // 29-bit identifier
  bool remote = false;    // remote transmission request: dlc bytes asked for, no data
  std::uint8_t dlc = 0;   // 0..8
  std::array<std::uint8_t, kMaxCanData> data{};

  std::span<const std::uint8_t> bytes() const { return {data.data(), remote ? 0U : dlc}; }
  friend bool operator==(const CanFrame&, const CanFrame&) = default;
};

// A data frame; an error if the identifier does not fit its width or there are more than 8 bytes.
Result<CanFrame> make_can_frame(std::uint32_t id, bool extended,
                                std::span<const std::uint8_t> data);
Result<CanFrame> make_can_frame(std::uint32_t id, bool extended,
                                std::initializer_list<std::uint8_t> data);
// A remote request for `dlc` bytes.
Result<CanFrame> make_remote_frame(std::uint32_t id, bool extended, std::uint8_t dlc);

// The candump notation: "123#DEADBEEF", "1F334455#00", "123#R" (RTR, dlc 0), "123#R4".
std::string to_candump_text(const CanFrame& frame);
// Parses the candump notation back; the error says what is wrong with the text.
Result<CanFrame> parse_candump_frame(std::string_view text);

std::ostream& operator<<(std::ostream& os, const CanFrame& frame);

}  // namespace sewerplan::hal
