// SPDX-License-Identifier: MIT
// The job protocol's decoder (docs/can-protocol.md): frames assembled into messages, every field
// checked, and what is wrong with a malformed message named.
#include <cmath>
#include <optional>
#include <string>

#include "sewerplan/core/manhole_signature.h"
#include "sewerplan/core/overloaded.h"
#include "sewerplan/hal/can/job_protocol.h"
#include "sewerplan/hal/can/wire_codes.h"

#include "can_text.h"
#include "protocol_wire.h"

namespace sewerplan::hal {
namespace {

using namespace wire;  // NOLINT: this file's own byte layouts

// Reads a message's data frames with checks; the first problem wins.
class Reader {
 public:
  Reader(MessageType type, std::uint8_t seq, const std::vector<CanFrame>& frames)
      : type_(type), seq_(seq), frames_(frames) {}
  bool ok() const { return problem_.empty(); }
  Malformed malformed() const { return Malformed{type_, seq_, where() + ": " + problem_}; }
  void fail(const std::string& problem) {
    if (problem_.empty()) problem_ = problem;
  }
  // Frame `i` with exactly `dlc` bytes (a dummy frame after a failure).
  const CanFrame& frame(std::size_t i, std::size_t dlc) {
    static const CanFrame kEmpty{};
    if (i >= frames_.size()) {
      fail("frame " + std::to_string(i) + " missing (" + std::to_string(frames_.size()) +
           " frames)");
      return kEmpty;
    }
    if (frames_[i].dlc != dlc) {
      fail("frame " + std::to_string(i) + " has " + std::to_string(frames_[i].dlc) +
           " bytes, expected " + std::to_string(dlc));
      return kEmpty;
    }
    return frames_[i];
  }
  double number(std::size_t i, std::string_view what, bool finite) {
    const double value = f64_of(frame(i, 8));
    if (finite && !(std::isfinite(value) && value >= 0)) {
      fail(std::string(what) + " is not a finite number >= 0");
      return 0;
    }
    return value;
  }
  RobotStatus status(std::size_t first, std::uint8_t flags) {
    RobotStatus s;
    s.battery_wh = number(first, "battery_wh", true);
    s.odometry_m = number(first + 1, "odometry_m", true);
    s.elapsed_s = number(first + 2, "elapsed_s", true);
    s.head_lifted = (flags & kHeadLifted) != 0;
    s.beacon_on = (flags & kBeaconOn) != 0;
    if ((flags & ~(kHeadLifted | kBeaconOn)) != 0) fail("unknown status flags");
    return s;
  }
  std::string text(std::size_t first, std::size_t length) {
    std::string text;
    std::size_t i = first;
    while (text.size() < length && ok()) {
      const CanFrame& f = frame(i++, std::min<std::size_t>(8, length - text.size()));
      text.append(f.data.begin(), f.data.begin() + f.dlc);
    }
    return text;
  }
  bool empty() const { return frames_.empty(); }
  std::size_t dlc(std::size_t i) const { return frames_[i].dlc; }
  void expect_frames(std::size_t n) {
    if (ok() && frames_.size() != n) {
      fail(std::to_string(frames_.size()) + " frames, expected " + std::to_string(n));
    }
  }

 private:
  std::string where() const { return std::string(to_string(type_)) + " " + std::to_string(seq_); }
  MessageType type_;
  std::uint8_t seq_;
  const std::vector<CanFrame>& frames_;
  std::string problem_;
};

// "1, 2, ..., 10": the job kinds' codes, for an error naming an unknown one.
std::string job_codes_text() {
  std::string text;
  for (unsigned code = 1; code < 256; ++code) {
    if (blank_job(static_cast<std::uint8_t>(code))) {
      text += (text.empty() ? "" : ", ") + std::to_string(code);
    }
  }
  return text;
}

Decoded decode_job(Reader& r, std::uint8_t seq) {
  const CanFrame& h = r.frame(0, 8);
  if (!r.ok()) return r.malformed();
  const std::uint8_t code = h.data[0];
  std::optional<Job> blank = blank_job(code);
  if (!blank) {
    r.fail("frame 0: unknown job kind " + std::to_string(code) + " (the kinds are " +
           job_codes_text() + ")");
    return r.malformed();
  }
  const std::uint16_t a = u16_of(h, 2);
  const std::uint16_t b = u16_of(h, 4);
  const std::uint16_t waypoints = u16_of(h, 6);
  const auto n = [&](std::size_t i) { return r.number(1 + i, "a parameter", false); };
  // Bit 0 of byte 1 (docs/can-protocol.md); other bits are refused.
  const auto flag = [&](std::string_view what) {
    if (h.data[1] > 1) r.fail("unknown " + std::string(what) + " flags");
    return h.data[1] == 1;
  };
  Job job = std::move(*blank);
  std::size_t numbers = 0;
  std::visit(Overloaded{
                 [&](DriveForward& j) {
                   j.to_manhole = flag("drive");
                   j.speed_mps = n(0);
                   j.distance_m = n(1);
                   numbers = 2;
                 },
                 [&](DriveBackward& j) {
                   j.to_manhole = flag("drive");
                   j.speed_mps = n(0);
                   j.distance_m = n(1);
                   numbers = 2;
                 },
                 [&](Push& j) {
                   j.backward = flag("push");
                   j.speed_mps = n(0);
                   j.distance_m = n(1);
                   numbers = 2;
                 },
                 [&](Scan& j) {
                   j.backward = flag("scan");
                   j.speed_mps = n(0);
                   j.distance_m = n(1);
                   numbers = 2;
                 },
                 [&](TurnInManhole& j) {
                   if (waypoints > (kMaxDataFrames - 5) / 4) r.fail("too many waypoints");
                   j = TurnInManhole{a, b, n(0), n(1), n(2), n(3), {}};
                   for (std::size_t w = 0; w < waypoints && r.ok(); ++w) {
                     const std::size_t at = 4 + 4 * w;
                     j.waypoints.push_back(Waypoint{n(at), n(at + 1), n(at + 2), n(at + 3)});
                   }
                   numbers = 4 + 4 * std::size_t{waypoints};
                 },
                 [&](EnterPipeFromManhole& j) {
                   j = EnterPipeFromManhole{a, n(0)};
                   numbers = 1;
                 },
                 [&](TakeSample& j) {
                   j.duration_s = n(0);
                   numbers = 1;
                 },
                 [](LiftHead&) {},
                 [](LowerHead&) {},
                 [](Stop&) {},
             },
             job);
  r.expect_frames(1 + numbers);
  if (!r.ok()) return r.malformed();
  return Message{JobCommand{seq, std::move(job)}};
}

// The observation after a result's reason (docs/can-protocol.md): the shaft, then per slot its
// direction (not slots[0]'s, 0 by definition), step and diameter; checked as core checks any.
std::optional<ManholeSignature> read_observation(Reader& r, std::size_t first,
                                                 std::uint16_t slots) {
  if (slots == 0) {
    r.fail("an observation of 0 slots (a result without one has a 4-byte header)");
    return std::nullopt;
  }
  if (slots > kMaxObservedSlots) {
    r.fail("an observation of " + std::to_string(slots) + " slots (at most " +
           std::to_string(kMaxObservedSlots) + ")");
    return std::nullopt;
  }
  ManholeSignature seen;
  std::size_t at = first;
  seen.shaft_diameter_m = r.number(at++, "the observed shaft", false);
  for (std::size_t i = 0; i < slots && r.ok(); ++i) {
    SlotSighting s;
    if (i > 0) s.relative_deg = r.number(at++, "an observed direction", false);
    s.step_m = r.number(at++, "an observed step", false);
    s.diameter_m = r.number(at++, "an observed diameter", false);
    seen.slots.push_back(s);
  }
  if (!r.ok()) return std::nullopt;
  if (Result<void> valid = check_signature(seen); !valid.has_value()) {
    r.fail("observation: " + valid.error().message);
    return std::nullopt;
  }
  return seen;
}

Decoded decode_result(Reader& r, std::uint8_t seq) {
  const bool observed = !r.empty() && r.dlc(0) == kObservationHeaderBytes;
  const bool turned = !r.empty() && r.dlc(0) == kTurnHeaderBytes;
  const CanFrame& h = r.frame(0, observed ? kObservationHeaderBytes
                                 : turned ? kTurnHeaderBytes
                                          : kResultHeaderBytes);
  if (!r.ok()) return r.malformed();
  JobResult result{seq, {}, {}};
  result.report.progress_m = r.number(1, "progress_m", true);
  result.report.duration_s = r.number(2, "duration_s", true);
  result.report.energy_wh = r.number(3, "energy_wh", true);
  result.report.in_water = (h.data[1] & kInWater) != 0;
  result.status = r.status(4, static_cast<std::uint8_t>(h.data[1] & ~kInWater));
  const std::uint16_t length = u16_of(h, 2);
  const std::string reason = r.text(1 + kResultNumberFrames, length);
  const std::size_t reason_frames = (std::size_t{length} + 7) / 8;
  const std::uint16_t slots = observed ? u16_of(h, 4) : 0;
  if (observed && r.ok()) {
    result.report.observation = read_observation(r, 1 + kResultNumberFrames + reason_frames, slots);
  }
  if (turned && r.ok()) {
    if (h.data[4] != kTurnMeasured) {
      r.fail("frame 0: unknown measurement " + std::to_string(h.data[4]) + " (1: a measured turn)");
    } else {
      const double deg = r.number(1 + kResultNumberFrames + reason_frames, "a turn", false);
      if (r.ok() && !(std::isfinite(deg) && deg >= 0 && deg < 360)) {
        r.fail("a measured turn of " + std::to_string(deg) + " degrees is not in [0, 360)");
      }
      result.report.turn_measured_deg = deg;
    }
  }
  r.expect_frames(1 + kResultNumberFrames + reason_frames + observation_frames(slots) +
                  (turned ? 1 : 0));
  const std::uint8_t outcome = h.data[0];
  const std::optional<RobotErrorCause> cause = error_cause(outcome);
  if (outcome != kDoneCode && !cause) {
    r.fail("frame 0: unknown outcome " + std::to_string(outcome) + " (0x" + hex_text(outcome, 2) +
           ")");
  }
  if (outcome == kDoneCode && length != 0) r.fail("a reason for a job that was done");
  if (outcome != kDoneCode && length == 0) r.fail("an error without a reason");
  if (!r.ok()) return r.malformed();
  if (cause) result.report.error = RobotError{*cause, reason};
  return Message{std::move(result)};
}

Decoded decode_status(Reader& r, std::uint8_t seq) {
  const CanFrame& h = r.frame(0, 1);
  if (!r.ok()) return r.malformed();
  StatusReply reply{seq, r.status(1, h.data[0])};
  r.expect_frames(1 + kStatusFrames);
  if (!r.ok()) return r.malformed();
  return Message{reply};
}

Decoded decode_reboot(Reader& r, std::uint8_t seq) {
  const CanFrame& h = r.frame(0, 4);
  if (!r.ok()) return r.malformed();
  RebootResult result{seq, std::nullopt, r.status(1, h.data[1])};
  const std::uint16_t length = u16_of(h, 2);
  const std::string reason = r.text(1 + kStatusFrames, length);
  r.expect_frames(1 + kStatusFrames + (std::size_t{length} + 7) / 8);
  if (h.data[0] > 1) r.fail("unknown reboot outcome " + std::to_string(h.data[0]));
  if ((h.data[0] == 1) != (length > 0)) r.fail("a failure comes with a reason, success without");
  if (!r.ok()) return r.malformed();
  if (h.data[0] == 1) result.failure = reason;
  return Message{std::move(result)};
}

Decoded decode_single(MessageType type, std::uint8_t seq, const CanFrame& f) {
  const std::vector<CanFrame> frames{f};
  Reader r(type, seq, frames);
  Decoded decoded = Malformed{type, seq, "unknown"};
  switch (type) {
    case MessageType::kEmergencyStop: {
      const CanFrame& c = r.frame(0, 1);
      if (r.ok() && c.data[0] > 2) r.fail("unknown stop reason");
      decoded = Message{EmergencyStop{static_cast<StopReason>(c.data[0])}};
      break;
    }
    case MessageType::kEmergencyStopAck:
      r.frame(0, 0);
      decoded = Message{EmergencyStopAck{}};
      break;
    case MessageType::kAck: {
      const CanFrame& c = r.frame(0, 3);
      if (r.ok() && c.data[0] > 4) r.fail("unknown acknowledgement code");
      decoded = Message{JobAck{seq, static_cast<AckCode>(c.data[0]), u16_of(c, 1)}};
      break;
    }
    case MessageType::kProgress:
      decoded = Message{JobProgress{seq, r.number(0, "progress_m", true)}};
      break;
    case MessageType::kStatusRequest:
    case MessageType::kResultRequest:
    case MessageType::kRebootRequest:
    case MessageType::kBeaconRequest: {
      r.frame(0, 0);
      const auto kind = static_cast<RequestKind>(static_cast<int>(type) -
                                                 static_cast<int>(MessageType::kStatusRequest));
      decoded = Message{Request{kind, seq}};
      break;
    }
    case MessageType::kControllerHeartbeat:
    case MessageType::kNodeHeartbeat: {
      const CanFrame& c = r.frame(0, 3);
      if (r.ok() && c.data[0] > 3) r.fail("unknown node state");
      decoded = Message{Heartbeat{type == MessageType::kNodeHeartbeat,
                                  static_cast<NodeState>(c.data[0]), c.data[1], c.data[2]}};
      break;
    }
    case MessageType::kJob:
    case MessageType::kResult:
    case MessageType::kStatus:
    case MessageType::kRebootResult:
      r.fail("a multi-frame type");
      break;
  }
  if (!r.ok()) return r.malformed();
  return decoded;
}

}  // namespace

Decoded decode_message(MessageType type, std::uint8_t seq, const std::vector<CanFrame>& frames) {
  Reader r(type, seq, frames);
  switch (type) {
    case MessageType::kJob:
      return decode_job(r, seq);
    case MessageType::kResult:
      return decode_result(r, seq);
    case MessageType::kStatus:
      return decode_status(r, seq);
    case MessageType::kRebootResult:
      return decode_reboot(r, seq);
    case MessageType::kEmergencyStop:
    case MessageType::kEmergencyStopAck:
    case MessageType::kAck:
    case MessageType::kProgress:
    case MessageType::kStatusRequest:
    case MessageType::kResultRequest:
    case MessageType::kRebootRequest:
    case MessageType::kBeaconRequest:
    case MessageType::kControllerHeartbeat:
    case MessageType::kNodeHeartbeat:
      if (frames.size() != 1) {
        return Malformed{type, seq, std::string(to_string(type)) + " is one frame"};
      }
      return decode_single(type, seq, frames[0]);
  }
  return Malformed{type, seq, "unknown type"};
}

std::optional<Decoded> MessageDecoder::push(const CanFrame& frame) {
  const std::optional<FrameId> id = frame_id(frame);
  if (!id) {
    ++foreign_frames_;
    return std::nullopt;
  }
  const std::string what = std::string(to_string(id->type)) + " " + std::to_string(id->seq);
  if (!is_multi_frame(id->type)) {
    if (id->index != 0)
      return Malformed{id->type, id->seq,
                       what + ": a one-frame message with index " + std::to_string(id->index)};
    return decode_single(id->type, id->seq, frame);
  }
  Partial& p = partial_[id->type];
  if (id->index != kEndFrameIndex) {
    if (id->index >= kMaxDataFrames) {
      return Malformed{id->type, id->seq,
                       what + ": frame index " + std::to_string(id->index) + " out of range"};
    }
    if (p.seq != id->seq || (p.frames.empty() && !p.end)) p = Partial{id->seq, {}, {}};
    p.frames[id->index] = frame;
    // A frame that an earlier copy missed completes the message its end frame announced.
    if (!p.end || p.frames.size() < u16_of(*p.end, 0)) return std::nullopt;
    return finish(id->type, what);
  }
  if (p.seq != id->seq || p.frames.empty()) {
    if (p.frames.empty()) partial_.erase(id->type);
    return Malformed{id->type, id->seq, what + ": end frame without data frames"};
  }
  if (frame.dlc != 6) {
    partial_.erase(id->type);
    return Malformed{id->type, id->seq,
                     what + ": end frame has " + std::to_string(frame.dlc) + " bytes, expected 6"};
  }
  p.end = frame;
  return finish(id->type, what);
}

std::optional<Decoded> MessageDecoder::finish(MessageType type, const std::string& what) {
  Partial& p = partial_[type];
  const std::uint8_t seq = p.seq;
  const CanFrame& end = *p.end;
  const std::uint16_t count = u16_of(end, 0);
  std::uint32_t crc = 0;
  for (std::size_t i = 0; i < 4; ++i) crc |= std::uint32_t{end.data[2 + i]} << (8 * i);
  for (std::uint16_t i = 0; i < count; ++i) {
    if (!p.frames.contains(i)) {
      // Kept: a copy of the message sent again (a retry, the same sequence number) fills the gap.
      return Malformed{
          type, seq,
          what + ": frame " + std::to_string(i) + " of " + std::to_string(count) + " missing",
          true};
    }
  }
  const Partial whole = std::move(p);
  partial_.erase(type);
  if (whole.frames.size() != count) {
    return Malformed{type, seq,
                     what + ": " + std::to_string(whole.frames.size()) +
                         " data frames, the end frame says " + std::to_string(count)};
  }
  std::vector<CanFrame> frames;
  std::vector<std::uint8_t> all;
  for (const auto& [index, f] : whole.frames) {
    frames.push_back(f);
    all.insert(all.end(), f.bytes().begin(), f.bytes().end());
  }
  if (crc32(all) != crc) {
    return Malformed{type, seq,
                     what + ": CRC mismatch (0x" + hex_text(crc32(all), 8) + " computed, 0x" +
                         hex_text(crc, 8) + " sent)"};
  }
  return decode_message(type, seq, frames);
}

}  // namespace sewerplan::hal
