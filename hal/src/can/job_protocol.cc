// SPDX-License-Identifier: MIT
// The job protocol's frames (docs/can-protocol.md): identifiers, payload layouts, assembly.
#include "sewerplan/hal/can/job_protocol.h"

#include <array>
#include <bit>
#include <cmath>
#include <cstring>

#include "sewerplan/core/check.h"
#include "sewerplan/core/overloaded.h"

#include "can_text.h"

namespace sewerplan::hal {
namespace {

constexpr std::uint8_t kHeadLifted = 0x01;
constexpr std::uint8_t kBeaconOn = 0x02;
constexpr std::size_t kStatusFrames = 3;  // battery, odometry, elapsed

// The job kinds' codes on the bus: the Job variant's index + 1.
constexpr std::size_t kJobKinds = std::variant_size_v<Job>;

CanFrame frame_of(FrameId id, std::span<const std::uint8_t> bytes) {
  CanFrame frame;
  frame.id = to_can_id(id);
  frame.extended = true;
  frame.dlc = static_cast<std::uint8_t>(bytes.size());
  std::copy(bytes.begin(), bytes.end(), frame.data.begin());
  return frame;
}

std::array<std::uint8_t, 8> f64_bytes(double value) {
  const auto bits = std::bit_cast<std::uint64_t>(value);
  std::array<std::uint8_t, 8> bytes{};
  for (std::size_t i = 0; i < 8; ++i) bytes[i] = static_cast<std::uint8_t>(bits >> (8 * i));
  return bytes;
}

double f64_of(const CanFrame& frame) {
  std::uint64_t bits = 0;
  for (std::size_t i = 0; i < 8; ++i) bits |= std::uint64_t{frame.data[i]} << (8 * i);
  return std::bit_cast<double>(bits);
}

std::uint16_t u16_of(const CanFrame& frame, std::size_t at) {
  return static_cast<std::uint16_t>(frame.data[at] | (frame.data[at + 1] << 8));
}

void put_u16(std::uint8_t* at, std::uint16_t value) {
  at[0] = static_cast<std::uint8_t>(value & 0xffU);
  at[1] = static_cast<std::uint8_t>(value >> 8U);
}

std::uint8_t status_flags(const RobotStatus& s) {
  return static_cast<std::uint8_t>((s.head_lifted ? kHeadLifted : 0) |
                                   (s.beacon_on ? kBeaconOn : 0));
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
  header[0] = static_cast<std::uint8_t>(c.job.index() + 1);
  std::vector<double> numbers;
  std::visit(Overloaded{
                 [&](const DriveForward& j) {
                   numbers = {j.speed_mps, j.distance_m};
                 },
                 [&](const DriveBackward& j) {
                   numbers = {j.speed_mps, j.distance_m};
                 },
                 [&](const Push& j) {
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

std::vector<CanFrame> encode_result(const JobResult& r) {
  const std::string reason = r.report.error ? cut_reason(r.report.error->reason) : std::string();
  std::array<std::uint8_t, 4> header{};
  header[0] =
      r.report.error ? static_cast<std::uint8_t>(1 + static_cast<int>(r.report.error->kind)) : 0;
  header[1] = status_flags(r.status);
  put_u16(&header[2], static_cast<std::uint16_t>(reason.size()));
  Writer w(MessageType::kResult, r.seq);
  w.bytes(header);
  w.number(r.report.progress_m);
  w.number(r.report.duration_s);
  w.number(r.report.energy_wh);
  w.status(r.status);
  w.text(reason);
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

// --- Decoding --------------------------------------------------------------------------------

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

Decoded decode_job(Reader& r, std::uint8_t seq) {
  const CanFrame& h = r.frame(0, 8);
  if (!r.ok()) return r.malformed();
  const std::uint8_t kind = h.data[0];
  const std::uint16_t a = u16_of(h, 2);
  const std::uint16_t b = u16_of(h, 4);
  const std::uint16_t waypoints = u16_of(h, 6);
  const auto n = [&](std::size_t i) { return r.number(1 + i, "a parameter", false); };
  Job job;
  std::size_t numbers = 0;
  switch (kind) {
    case 1:
      job = DriveForward{n(0), n(1)};
      numbers = 2;
      break;
    case 2:
      job = DriveBackward{n(0), n(1)};
      numbers = 2;
      break;
    case 3:
      job = Push{n(0), n(1)};
      numbers = 2;
      break;
    case 4: {
      if (waypoints > (kMaxDataFrames - 5) / 4) r.fail("too many waypoints");
      TurnInManhole t{a, b, n(0), n(1), n(2), n(3), {}};
      for (std::size_t w = 0; w < waypoints && r.ok(); ++w) {
        const std::size_t at = 4 + 4 * w;
        t.waypoints.push_back(Waypoint{n(at), n(at + 1), n(at + 2), n(at + 3)});
      }
      job = std::move(t);
      numbers = 4 + 4 * std::size_t{waypoints};
      break;
    }
    case 5:
      job = EnterPipeFromManhole{a, n(0)};
      numbers = 1;
      break;
    case 6:
      job = LiftHead{};
      break;
    case 7:
      job = LowerHead{};
      break;
    case 8:
      job = TakeSample{n(0)};
      numbers = 1;
      break;
    case 9:
      if (h.data[1] > 1) r.fail("unknown scan flags");
      job = Scan{n(0), n(1), h.data[1] == 1};
      numbers = 2;
      break;
    case 10:
      job = Stop{};
      break;
    default:
      r.fail("unknown job kind " + std::to_string(kind) + " (1.." + std::to_string(kJobKinds) +
             ")");
  }
  r.expect_frames(1 + numbers);
  if (!r.ok()) return r.malformed();
  return Message{JobCommand{seq, std::move(job)}};
}

Decoded decode_result(Reader& r, std::uint8_t seq) {
  const CanFrame& h = r.frame(0, 4);
  if (!r.ok()) return r.malformed();
  JobResult result{seq, {}, {}};
  result.report.progress_m = r.number(1, "progress_m", true);
  result.report.duration_s = r.number(2, "duration_s", true);
  result.report.energy_wh = r.number(3, "energy_wh", true);
  result.status = r.status(4, h.data[1]);
  const std::uint16_t length = u16_of(h, 2);
  const std::string reason = r.text(4 + kStatusFrames, length);
  r.expect_frames(4 + kStatusFrames + (std::size_t{length} + 7) / 8);
  const std::uint8_t outcome = h.data[0];
  if (outcome > 3) r.fail("unknown outcome " + std::to_string(outcome));
  if (outcome == 0 && length != 0) r.fail("a reason for a job that was done");
  if (outcome != 0 && length == 0) r.fail("an error without a reason");
  if (!r.ok()) return r.malformed();
  if (outcome != 0) {
    result.report.error = RobotError{static_cast<RobotErrorKind>(outcome - 1), reason};
  }
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
      if (r.ok() && c.data[0] > 3) r.fail("unknown acknowledgement code");
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
  if (id->index != kEndFrameIndex) {
    if (id->index >= kMaxDataFrames) {
      return Malformed{id->type, id->seq,
                       what + ": frame index " + std::to_string(id->index) + " out of range"};
    }
    Partial& p = partial_[id->type];
    if (p.seq != id->seq || p.frames.empty()) p = Partial{id->seq, {}};
    p.frames[id->index] = frame;
    return std::nullopt;
  }
  const auto it = partial_.find(id->type);
  if (it == partial_.end() || it->second.seq != id->seq || it->second.frames.empty()) {
    return Malformed{id->type, id->seq, what + ": end frame without data frames"};
  }
  const Partial p = std::move(it->second);
  partial_.erase(it);
  if (frame.dlc != 6) {
    return Malformed{id->type, id->seq,
                     what + ": end frame has " + std::to_string(frame.dlc) + " bytes, expected 6"};
  }
  const std::uint16_t count = u16_of(frame, 0);
  std::uint32_t crc = 0;
  for (std::size_t i = 0; i < 4; ++i) crc |= std::uint32_t{frame.data[2 + i]} << (8 * i);
  std::vector<CanFrame> frames;
  std::vector<std::uint8_t> all;
  for (std::uint16_t i = 0; i < count; ++i) {
    const auto f = p.frames.find(i);
    if (f == p.frames.end()) {
      return Malformed{
          id->type, id->seq,
          what + ": frame " + std::to_string(i) + " of " + std::to_string(count) + " missing"};
    }
    frames.push_back(f->second);
    all.insert(all.end(), f->second.bytes().begin(), f->second.bytes().end());
  }
  if (p.frames.size() != count) {
    return Malformed{id->type, id->seq,
                     what + ": " + std::to_string(p.frames.size()) +
                         " data frames, the end frame says " + std::to_string(count)};
  }
  if (crc32(all) != crc) {
    return Malformed{id->type, id->seq,
                     what + ": CRC mismatch (0x" + hex_text(crc32(all), 8) + " computed, 0x" +
                         hex_text(crc, 8) + " sent)"};
  }
  return decode_message(id->type, id->seq, frames);
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
