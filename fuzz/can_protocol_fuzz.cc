// SPDX-License-Identifier: MIT
// libFuzzer target: the CAN job protocol's decoder (hal/can/job_protocol.h) on any sequence of
// frames; every message it decodes must encode to frames that decode to the same frames again (so
// a RESULT's manhole observation that the decoder accepts passes the encoder's check_signature:
// the decoder never lets an invalid one through). The corpus holds a session, a job and results
// with observations (result-observation.bin, docs/can-protocol.md).
// Input: frames of 13 bytes each - 4 bytes identifier (little-endian, bit 31 = extended), 1 byte
// length (0..8, higher values are cut), 8 data bytes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "sewerplan/hal/can/job_protocol.h"

namespace {

std::vector<sewerplan::hal::CanFrame> reencode(const sewerplan::hal::Message& m) {
  return sewerplan::hal::encode(m);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sewerplan::hal;  // NOLINT: a fuzz target's body
  MessageDecoder decoder;
  for (std::size_t at = 0; at + 13 <= size; at += 13) {
    const std::uint32_t raw = static_cast<std::uint32_t>(data[at]) |
                              (static_cast<std::uint32_t>(data[at + 1]) << 8U) |
                              (static_cast<std::uint32_t>(data[at + 2]) << 16U) |
                              (static_cast<std::uint32_t>(data[at + 3]) << 24U);
    CanFrame frame;
    frame.extended = (raw & 0x80000000U) != 0;
    frame.id = raw & (frame.extended ? kMaxExtendedCanId : kMaxStandardCanId);
    frame.dlc = static_cast<std::uint8_t>(data[at + 4] % 9U);
    for (std::size_t i = 0; i < frame.dlc; ++i) frame.data[i] = data[at + 5 + i];
    std::optional<Decoded> decoded = decoder.push(frame);
    if (!decoded) continue;
    const auto* message = std::get_if<Message>(&*decoded);
    if (message == nullptr) continue;
    const std::vector<CanFrame> frames = reencode(*message);
    MessageDecoder again;
    std::optional<Decoded> back;
    for (const CanFrame& f : frames) back = again.push(f);
    if (!back || !std::holds_alternative<Message>(*back)) std::abort();
    if (reencode(std::get<Message>(*back)) != frames) std::abort();
  }
  return 0;
}
