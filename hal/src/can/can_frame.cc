// SPDX-License-Identifier: MIT
#include "sewerplan/hal/can/can_frame.h"

#include <algorithm>
#include <cstdio>

#include "can_text.h"

namespace sewerplan::hal {

Result<CanFrame> make_can_frame(std::uint32_t id, bool extended,
                                std::span<const std::uint8_t> data) {
  if (id > (extended ? kMaxExtendedCanId : kMaxStandardCanId)) {
    return Error{ErrorCode::kInvalidArgument, "CAN identifier 0x" + hex_text(id, 1) +
                                                  " does not fit " +
                                                  (extended ? "29 bits" : "11 bits")};
  }
  if (data.size() > kMaxCanData) {
    return Error{ErrorCode::kInvalidArgument,
                 "a CAN frame holds at most 8 bytes, not " + std::to_string(data.size())};
  }
  CanFrame frame;
  frame.id = id;
  frame.extended = extended;
  frame.dlc = static_cast<std::uint8_t>(data.size());
  std::copy(data.begin(), data.end(), frame.data.begin());
  return frame;
}

Result<CanFrame> make_can_frame(std::uint32_t id, bool extended,
                                std::initializer_list<std::uint8_t> data) {
  return make_can_frame(id, extended, std::span<const std::uint8_t>(data.begin(), data.size()));
}

Result<CanFrame> make_remote_frame(std::uint32_t id, bool extended, std::uint8_t dlc) {
  Result<CanFrame> frame = make_can_frame(id, extended, {});
  if (!frame.has_value()) return frame;
  if (dlc > kMaxCanData) {
    return Error{ErrorCode::kInvalidArgument,
                 "a remote frame asks for at most 8 bytes, not " + std::to_string(dlc)};
  }
  frame->remote = true;
  frame->dlc = dlc;
  return frame;
}

std::string to_candump_text(const CanFrame& frame) {
  std::string text = hex_text(frame.id, frame.extended ? 8 : 3) + '#';
  if (frame.remote) {
    text += 'R';
    if (frame.dlc > 0) text += static_cast<char>('0' + frame.dlc);
    return text;
  }
  for (std::uint8_t b : frame.bytes()) text += hex_text(b, 2);
  return text;
}

Result<CanFrame> parse_candump_frame(std::string_view text) {
  const auto hash = text.find('#');
  if (hash == std::string_view::npos) {
    return Error{ErrorCode::kParse, "expected ID#DATA, found no '#' in '" + printable(text) + "'"};
  }
  const std::string_view id_text = text.substr(0, hash);
  std::string_view data = text.substr(hash + 1);
  if (id_text.size() != 3 && id_text.size() != 8) {
    return Error{ErrorCode::kParse,
                 "a CAN identifier has 3 (standard) or 8 (extended) hex digits, "
                 "not '" +
                     printable(id_text) + "'"};
  }
  const std::optional<std::uint32_t> id = parse_hex(id_text);
  if (!id) return Error{ErrorCode::kParse, "bad hex identifier '" + printable(id_text) + "'"};
  const bool extended = id_text.size() == 8;
  if (!data.empty() && (data[0] == 'R' || data[0] == 'r')) {
    if (data.size() > 2)
      return Error{ErrorCode::kParse, "bad remote frame '" + printable(text) + "'"};
    const int dlc = data.size() == 2 ? data[1] - '0' : 0;
    if (dlc < 0 || dlc > 8) {
      return Error{ErrorCode::kParse, "bad remote frame length in '" + printable(text) + "'"};
    }
    return make_remote_frame(*id, extended, static_cast<std::uint8_t>(dlc));
  }
  if (data.size() % 2 != 0 || data.size() > 2 * kMaxCanData) {
    return Error{ErrorCode::kParse, "expected 0 to 8 data bytes as pairs of hex digits, not '" +
                                        printable(data) + "'"};
  }
  std::array<std::uint8_t, kMaxCanData> bytes{};
  for (std::size_t i = 0; i * 2 < data.size(); ++i) {
    const std::optional<std::uint32_t> b = parse_hex(data.substr(i * 2, 2));
    if (!b) return Error{ErrorCode::kParse, "bad hex data '" + printable(data) + "'"};
    bytes[i] = static_cast<std::uint8_t>(*b);
  }
  return make_can_frame(*id, extended,
                        std::span<const std::uint8_t>(bytes.data(), data.size() / 2));
}

std::ostream& operator<<(std::ostream& os, const CanFrame& frame) {
  return os << to_candump_text(frame);
}

}  // namespace sewerplan::hal
