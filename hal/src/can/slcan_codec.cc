// SPDX-License-Identifier: MIT
// The SLCAN line codec: frames to lines and back, and the byte stream cut into lines.
#include <array>

#include "sewerplan/hal/can/slcan.h"

#include "can_text.h"

namespace sewerplan::hal {
namespace {

constexpr char kBell = '\a';

Error bad_line(std::string_view line, const std::string& what) {
  return Error{ErrorCode::kParse, "slcan: " + what + " in '" + printable(line) + "'"};
}

}  // namespace

std::string encode_slcan_frame(const CanFrame& frame) {
  std::string line;
  line += frame.remote ? (frame.extended ? 'R' : 'r') : (frame.extended ? 'T' : 't');
  line += hex_text(frame.id, frame.extended ? 8 : 3);
  line += static_cast<char>('0' + frame.dlc);
  for (std::uint8_t b : frame.bytes()) line += hex_text(b, 2);
  line += '\r';
  return line;
}

Result<CanFrame> parse_slcan_frame(std::string_view line) {
  if (line.empty()) return bad_line(line, "empty line");
  const char kind = line[0];
  if (kind != 't' && kind != 'T' && kind != 'r' && kind != 'R') {
    return bad_line(line, std::string("unknown line type '") + printable(line.substr(0, 1)) + "'");
  }
  const bool extended = kind == 'T' || kind == 'R';
  const bool remote = kind == 'r' || kind == 'R';
  const std::size_t id_digits = extended ? 8 : 3;
  if (line.size() < 1 + id_digits + 1) return bad_line(line, "short frame");
  const std::optional<std::uint32_t> id = parse_hex(line.substr(1, id_digits));
  if (!id) return bad_line(line, "bad identifier");
  const char dlc_char = line[1 + id_digits];
  if (dlc_char < '0' || dlc_char > '8') return bad_line(line, "bad length");
  const auto dlc = static_cast<std::uint8_t>(dlc_char - '0');
  std::string_view rest = line.substr(2 + id_digits);
  const std::size_t data_digits = remote ? 0 : 2U * dlc;
  // After the data, nothing or a 4-digit timestamp.
  if (rest.size() != data_digits && rest.size() != data_digits + 4) {
    return bad_line(line, "length " + std::to_string(dlc) + " does not match the data");
  }
  if (rest.size() == data_digits + 4 && !parse_hex(rest.substr(data_digits))) {
    return bad_line(line, "bad timestamp");
  }
  if (remote) return make_remote_frame(*id, extended, dlc);
  std::array<std::uint8_t, kMaxCanData> data{};
  for (std::size_t i = 0; i < dlc; ++i) {
    const std::optional<std::uint32_t> b = parse_hex(rest.substr(2 * i, 2));
    if (!b) return bad_line(line, "bad data");
    data[i] = static_cast<std::uint8_t>(*b);
  }
  Result<CanFrame> frame = make_can_frame(*id, extended, std::span(data.data(), dlc));
  if (!frame.has_value()) return bad_line(line, frame.error().message);
  return frame;
}

void SlcanSplitter::feed(std::string_view bytes) { pending_.append(bytes); }

std::optional<SlcanSplitter::Token> SlcanSplitter::next() {
  while (scanned_ < pending_.size()) {
    const char c = pending_[scanned_++];
    if (c == kBell) {
      pending_.erase(0, scanned_);
      scanned_ = 0;
      return Token{Token::Kind::kBell, {}};
    }
    if (c == '\r' || c == '\n') {
      pending_.erase(0, scanned_);
      scanned_ = 0;
      Token token{overlong_ ? Token::Kind::kOverlong : Token::Kind::kLine, std::move(line_)};
      line_.clear();
      const bool was_overlong = overlong_;
      overlong_ = false;
      // LF after CR, or a lone LF, ends nothing new.
      if (!was_overlong && token.text.empty() && c == '\n') continue;
      return token;
    }
    if (line_.size() < kMaxSlcanLine) {
      line_ += c;
    } else {
      overlong_ = true;
    }
  }
  pending_.clear();
  scanned_ = 0;
  return std::nullopt;
}

}  // namespace sewerplan::hal
