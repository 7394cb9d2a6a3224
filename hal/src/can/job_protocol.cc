// SPDX-License-Identifier: MIT
// The job protocol's frames (docs/can-protocol.md): identifiers, message types, encoding.
#include "sewerplan/hal/can/job_protocol.h"

#include <array>
#include <cmath>
#include <cstring>

#include "sewerplan/core/check.h"
#include "sewerplan/core/overloaded.h"
#include "sewerplan/hal/can/wire_codes.h"

#include "protocol_wire.h"

namespace sewerplan::hal {

namespace {

using namespace wire;  // NOLINT: this file's own byte layouts

MessageType request_type(RequestKind kind) {
  switch (kind) {
    case RequestKind::kStatus:
      return MessageType::kStatusRequest;
    case RequestKind::kResult:
      return MessageType::kResultRequest;
    case RequestKind::kReboot:
      return MessageType::kRebootRequest;
    case RequestKind::kBeacon:
      return MessageType::kBeaconRequest;
  }
  return MessageType::kStatusRequest;
}

// Builds a multi-frame message: data frames, then the end frame.
class Writer {
 public:
  Writer(MessageType type, std::uint8_t seq) : type_(type), seq_(seq) {}
  void bytes(std::span<const std::uint8_t> data) {
    frames_.push_back(frame_of({type_, seq_, static_cast<std::uint16_t>(frames_.size())}, data));
  }
  void number(double value) { bytes(f64_bytes(value)); }
  void text(std::string_view text) {
    for (std::size_t at = 0; at < text.size(); at += 8) {
      const std::size_t n = std::min<std::size_t>(8, text.size() - at);
      std::array<std::uint8_t, 8> chunk{};
      std::memcpy(chunk.data(), text.data() + at, n);
      bytes(std::span(chunk.data(), n));
    }
  }
  void status(const RobotStatus& s) {
    number(s.battery_wh);
    number(s.odometry_m);
    number(s.elapsed_s);
  }
  std::vector<CanFrame> finish() {
    std::vector<std::uint8_t> all;
    for (const CanFrame& f : frames_) all.insert(all.end(), f.bytes().begin(), f.bytes().end());
    std::array<std::uint8_t, 6> end{};
    put_u16(end.data(), static_cast<std::uint16_t>(frames_.size()));
    const std::uint32_t crc = crc32(all);
    for (std::size_t i = 0; i < 4; ++i) end[2 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
    frames_.push_back(frame_of({type_, seq_, kEndFrameIndex}, end));
    return std::move(frames_);
  }

 private:
  MessageType type_;
  std::uint8_t seq_;
  std::vector<CanFrame> frames_;
};

std::string cut_reason(const std::string& reason) { return reason.substr(0, kMaxReasonBytes); }

std::vector<CanFrame> single(MessageType type, std::uint8_t seq,
                             std::initializer_list<std::uint8_t> data) {
  return {frame_of({type, seq, 0}, std::span(data.begin(), data.size()))};
}

std::vector<CanFrame> encode_job(const JobCommand& c) {
  std::array<std::uint8_t, 8> header{};
  header[0] = job_code(c.job);
  std::vector<double> numbers;
  std::visit(Overloaded{
                 [&](const DriveForward& j) {
                   header[1] = j.to_manhole ? 1 : 0;
                   numbers = {j.speed_mps, j.distance_m};
                 },
                 [&](const DriveBackward& j) {
                   header[1] = j.to_manhole ? 1 : 0;
                   numbers = {j.speed_mps, j.distance_m};
                 },
                 [&](const Push& j) {
                   header[1] = j.backward ? 1 : 0;
                   numbers = {j.speed_mps, j.distance_m};
                 },
                 [&](const Scan& j) {
                   header[1] = j.backward ? 1 : 0;
                   numbers = {j.speed_mps, j.distance_m};
                 },
                 [&](const TurnInManhole& j) {
                   SEWER_CHECK(j.waypoints.size() <= (kMaxDataFrames - 5) / 4,
                               "encode: too many waypoints for one message");
                   put_u16(&header[2], j.from_slot);
                   put_u16(&header[4], j.to_slot);
                   put_u16(&header[6], static_cast<std::uint16_t>(j.waypoints.size()));
                   numbers = {j.turn_deg, j.step_m, j.manhole_diameter_m, j.duration_s};
                   for (const Waypoint& w : j.waypoints) {
                     numbers.insert(numbers.end(), {w.x_m, w.y_m, w.z_m, w.heading_deg});
                   }
                 },
                 [&](const EnterPipeFromManhole& j) {
                   put_u16(&header[2], j.slot);
                   numbers = {j.duration_s};
                 },
                 [&](const TakeSample& j) { numbers = {j.duration_s}; },
                 [](const LiftHead&) {},
                 [](const LowerHead&) {},
                 [](const Stop&) {},
             },
             c.job);
  Writer w(MessageType::kJob, c.seq);
  w.bytes(header);
  for (double n : numbers) w.number(n);
  return w.finish();
}

// A result's header is 4 bytes without an observation (the layout of earlier versions, byte for
// byte) and 6 with one: bytes 4-5 are the observed slot count, and the observation follows the
// reason; 5 with a measured turn: byte 4 says so, and its angle follows the reason
// (docs/can-protocol.md).
std::vector<CanFrame> encode_result(const JobResult& r) {
  const std::string reason = r.report.error ? cut_reason(r.report.error->reason) : std::string();
  const std::optional<ManholeSignature>& seen = r.report.observation;
  const std::optional<double>& turned = r.report.turn_measured_deg;
  if (seen) {
    SEWER_CHECK(seen->slots.size() <= kMaxObservedSlots && check_signature(*seen).has_value(),
                "encode: an observation the protocol cannot carry");
  }
  SEWER_CHECK(!(seen && turned), "encode: an observation and a measured turn in one result");
  if (turned) {
    SEWER_CHECK(std::isfinite(*turned) && *turned >= 0 && *turned < 360,
                "encode: a measured turn not in [0, 360)");
  }
  if (r.report.error) {
    SEWER_CHECK(kind_of(r.report.error->cause) == r.report.error->kind,
                "encode: an error whose kind is not its cause's");
  }
  std::array<std::uint8_t, 6> header{};
  header[0] = r.report.error ? error_code(r.report.error->cause) : kDoneCode;
  header[1] =
      static_cast<std::uint8_t>(status_flags(r.status) | (r.report.in_water ? kInWater : 0));
  put_u16(&header[2], static_cast<std::uint16_t>(reason.size()));
  if (seen) put_u16(&header[4], static_cast<std::uint16_t>(seen->slots.size()));
  if (turned) header[4] = kTurnMeasured;
  Writer w(MessageType::kResult, r.seq);
  w.bytes(std::span(header.data(), seen     ? kObservationHeaderBytes
                                   : turned ? kTurnHeaderBytes
                                            : kResultHeaderBytes));
  w.number(r.report.progress_m);
  w.number(r.report.duration_s);
  w.number(r.report.energy_wh);
  w.status(r.status);
  w.text(reason);
  if (seen) {
    // slots[0]'s direction is 0 by definition (core/manhole_signature.h): not sent.
    w.number(seen->shaft_diameter_m);
    for (std::size_t i = 0; i < seen->slots.size(); ++i) {
      if (i > 0) w.number(seen->slots[i].relative_deg);
      w.number(seen->slots[i].step_m);
      w.number(seen->slots[i].diameter_m);
    }
  }
  if (turned) w.number(*turned);
  return w.finish();
}

std::vector<CanFrame> encode_reboot(const RebootResult& r) {
  const std::string reason = r.failure ? cut_reason(*r.failure) : std::string();
  std::array<std::uint8_t, 4> header{};
  header[0] = r.failure ? 1 : 0;
  header[1] = status_flags(r.status);
  put_u16(&header[2], static_cast<std::uint16_t>(reason.size()));
  Writer w(MessageType::kRebootResult, r.seq);
  w.bytes(header);
  w.status(r.status);
  w.text(reason);
  return w.finish();
}

bool known_type(std::uint32_t value) {
  switch (static_cast<MessageType>(value)) {
    case MessageType::kEmergencyStop:
    case MessageType::kEmergencyStopAck:
    case MessageType::kJob:
    case MessageType::kAck:
    case MessageType::kProgress:
    case MessageType::kResult:
    case MessageType::kStatus:
    case MessageType::kRebootResult:
    case MessageType::kStatusRequest:
    case MessageType::kResultRequest:
    case MessageType::kRebootRequest:
    case MessageType::kBeaconRequest:
    case MessageType::kControllerHeartbeat:
    case MessageType::kNodeHeartbeat:
      return true;
  }
  return false;
}

}  // namespace

std::string_view to_string(MessageType type) {
  switch (type) {
    case MessageType::kEmergencyStop:
      return "emergency-stop";
    case MessageType::kEmergencyStopAck:
      return "emergency-stop-ack";
    case MessageType::kJob:
      return "job";
    case MessageType::kAck:
      return "ack";
    case MessageType::kProgress:
      return "progress";
    case MessageType::kResult:
      return "result";
    case MessageType::kStatus:
      return "status";
    case MessageType::kRebootResult:
      return "reboot-result";
    case MessageType::kStatusRequest:
      return "status-request";
    case MessageType::kResultRequest:
      return "result-request";
    case MessageType::kRebootRequest:
      return "reboot-request";
    case MessageType::kBeaconRequest:
      return "beacon-request";
    case MessageType::kControllerHeartbeat:
      return "controller-heartbeat";
    case MessageType::kNodeHeartbeat:
      return "node-heartbeat";
  }
  return "unknown";
}

bool is_multi_frame(MessageType type) {
  return type == MessageType::kJob || type == MessageType::kResult ||
         type == MessageType::kStatus || type == MessageType::kRebootResult;
}

bool sent_by_node(MessageType type) {
  switch (type) {
    case MessageType::kEmergencyStopAck:
    case MessageType::kAck:
    case MessageType::kProgress:
    case MessageType::kResult:
    case MessageType::kStatus:
    case MessageType::kRebootResult:
    case MessageType::kNodeHeartbeat:
      return true;
    case MessageType::kEmergencyStop:
    case MessageType::kJob:
    case MessageType::kStatusRequest:
    case MessageType::kResultRequest:
    case MessageType::kRebootRequest:
    case MessageType::kBeaconRequest:
    case MessageType::kControllerHeartbeat:
      return false;
  }
  return false;
}

std::uint32_t to_can_id(const FrameId& id) {
  return (static_cast<std::uint32_t>(id.type) << 20U) | (std::uint32_t{id.seq} << 12U) |
         (id.index & 0xfffU);
}

std::optional<FrameId> frame_id(const CanFrame& frame) {
  if (!frame.extended || frame.remote) return std::nullopt;
  const std::uint32_t type = frame.id >> 20U;
  if (!known_type(type)) return std::nullopt;
  return FrameId{static_cast<MessageType>(type),
                 static_cast<std::uint8_t>((frame.id >> 12U) & 0xffU),
                 static_cast<std::uint16_t>(frame.id & 0xfffU)};
}

MessageType message_type(const Message& message) {
  return std::visit(Overloaded{
                        [](const JobCommand&) { return MessageType::kJob; },
                        [](const JobAck&) { return MessageType::kAck; },
                        [](const JobProgress&) { return MessageType::kProgress; },
                        [](const JobResult&) { return MessageType::kResult; },
                        [](const StatusReply&) { return MessageType::kStatus; },
                        [](const RebootResult&) { return MessageType::kRebootResult; },
                        [](const Request& r) { return request_type(r.kind); },
                        [](const EmergencyStop&) { return MessageType::kEmergencyStop; },
                        [](const EmergencyStopAck&) { return MessageType::kEmergencyStopAck; },
                        [](const Heartbeat& h) {
                          return h.from_node ? MessageType::kNodeHeartbeat
                                             : MessageType::kControllerHeartbeat;
                        },
                    },
                    message);
}

std::ostream& operator<<(std::ostream& os, const Message& message) {
  os << to_string(message_type(message));
  std::visit(Overloaded{
                 [&](const JobCommand& m) { os << ' ' << int{m.seq} << ": " << m.job; },
                 [&](const JobAck& m) {
                   os << ' ' << int{m.seq} << ": code " << static_cast<int>(m.code);
                 },
                 [&](const JobProgress& m) { os << ' ' << int{m.seq} << ": " << m.progress_m; },
                 [&](const JobResult& m) {
                   os << ' ' << int{m.seq} << ": ";
                   if (m.report.error) {
                     os << *m.report.error;
                   } else {
                     os << "done";
                   }
                   if (m.report.observation) {
                     os << ", a manhole of " << m.report.observation->slots.size() << " slots seen";
                   }
                   if (m.report.turn_measured_deg) {
                     os << ", turned to " << *m.report.turn_measured_deg << " deg";
                   }
                 },
                 [&](const StatusReply& m) { os << ' ' << int{m.seq}; },
                 [&](const RebootResult& m) {
                   os << ' ' << int{m.seq} << ": " << (m.failure ? *m.failure : "rebooted");
                 },
                 [&](const Request& m) { os << ' ' << int{m.seq}; },
                 [&](const EmergencyStop&) {},
                 [&](const EmergencyStopAck&) {},
                 [&](const Heartbeat& m) { os << ' ' << int{m.counter}; },
             },
             message);
  return os;
}

std::vector<CanFrame> encode(const Message& message) {
  return std::visit(
      Overloaded{
          [](const JobCommand& m) { return encode_job(m); },
          [](const JobAck& m) {
            return single(
                MessageType::kAck, m.seq,
                {static_cast<std::uint8_t>(m.code), static_cast<std::uint8_t>(m.detail & 0xffU),
                 static_cast<std::uint8_t>(m.detail >> 8U)});
          },
          [](const JobProgress& m) {
            const auto b = f64_bytes(m.progress_m);
            return std::vector<CanFrame>{frame_of({MessageType::kProgress, m.seq, 0}, b)};
          },
          [](const JobResult& m) { return encode_result(m); },
          [](const StatusReply& m) {
            Writer w(MessageType::kStatus, m.seq);
            const std::array<std::uint8_t, 1> flags{status_flags(m.status)};
            w.bytes(flags);
            w.status(m.status);
            return w.finish();
          },
          [](const RebootResult& m) { return encode_reboot(m); },
          [](const Request& m) { return single(request_type(m.kind), m.seq, {}); },
          [](const EmergencyStop& m) {
            return single(MessageType::kEmergencyStop, 0, {static_cast<std::uint8_t>(m.reason)});
          },
          [](const EmergencyStopAck&) { return single(MessageType::kEmergencyStopAck, 0, {}); },
          [](const Heartbeat& m) {
            return single(
                m.from_node ? MessageType::kNodeHeartbeat : MessageType::kControllerHeartbeat, 0,
                {static_cast<std::uint8_t>(m.state), m.counter, m.last_seq});
          },
      },
      message);
}

std::uint32_t crc32(const std::vector<std::uint8_t>& bytes) {
  std::uint32_t crc = 0xffffffffU;
  for (std::uint8_t b : bytes) {
    crc ^= b;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1U) ^ (0xedb88320U & (0U - (crc & 1U)));
  }
  return ~crc;
}

}  // namespace sewerplan::hal
