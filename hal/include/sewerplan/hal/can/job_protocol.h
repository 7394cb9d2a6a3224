// SPDX-License-Identifier: MIT
// The job protocol: how the controller (can_robot.h) and the base machine's node (sim_node.h, or
// MAKRO's microcontroller) exchange jobs, reports, status, heartbeats and an emergency stop over
// CAN frames. The normative description, with byte layouts, is docs/can-protocol.md.
//
// Every frame is extended (29 bits): type (9 bits) << 20 | sequence (8 bits) << 12 | index (12
// bits). Numbers are little-endian; real numbers are IEEE 754 binary64, one per frame, so that a
// report crosses the bus bit for bit and a run over the bus equals one in process. A message that
// needs more than one frame (a job, a result, a status, a reboot result) is a run of data frames
// (index 0, 1, ...) closed by an end frame (index 0xFFF) that holds the frame count and a CRC-32
// of the data. Everything is a pure function: encode() gives the frames of a message; a
// MessageDecoder assembles frames back into messages and names what is wrong with a malformed one.
//
//   std::vector<CanFrame> frames = encode(JobCommand{.seq = 7, .job = LiftHead{}});
//   MessageDecoder decoder;
//   for (const CanFrame& f : frames) {
//     if (std::optional<Decoded> d = decoder.push(f)) ...  // the JobCommand, once the end arrives
//   }
//
// Thread safety: The codecs are pure functions; a MessageDecoder is not thread-safe (one per
// receiving thread).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "sewerplan/core/job.h"
#include "sewerplan/core/limits.h"
#include "sewerplan/hal/can/can_frame.h"
#include "sewerplan/hal/robot.h"

namespace sewerplan::hal {

// The message types; the value is the identifier's top 9 bits, so lower types win arbitration.
enum class MessageType : std::uint16_t {
  kEmergencyStop = 0x001,     // controller -> node
  kEmergencyStopAck = 0x002,  // node -> controller
  kJob = 0x010,               // controller -> node, multi-frame
  kAck = 0x020,               // node -> controller
  kProgress = 0x021,          // node -> controller
  kResult = 0x022,            // node -> controller, multi-frame
  kStatus = 0x023,            // node -> controller, multi-frame
  kRebootResult = 0x024,      // node -> controller, multi-frame
  kStatusRequest = 0x030,     // controller -> node
  kResultRequest = 0x031,     // controller -> node
  kRebootRequest = 0x032,     // controller -> node
  kBeaconRequest = 0x033,     // controller -> node
  kControllerHeartbeat = 0x070,
  kNodeHeartbeat = 0x071,
};

std::string_view to_string(MessageType type);
bool is_multi_frame(MessageType type);
bool sent_by_node(MessageType type);

inline constexpr std::uint16_t kEndFrameIndex = 0xfff;
// At most this many data frames in a message (a turn with 1,000 waypoints needs 4,005).
inline constexpr std::size_t kMaxDataFrames = 4094;
// Reasons longer than this are cut.
inline constexpr std::size_t kMaxReasonBytes = 1024;
// A RESULT carries an observation of at most this many slots (a map's own limit per manhole).
inline constexpr std::size_t kMaxObservedSlots = kMaxSlotsPerManhole;

struct FrameId {
  MessageType type = MessageType::kJob;
  std::uint8_t seq = 0;
  std::uint16_t index = 0;
  friend bool operator==(const FrameId&, const FrameId&) = default;
};
std::uint32_t to_can_id(const FrameId& id);
// The frame's place in the protocol; empty for a frame of another protocol (standard id, remote
// frame or unknown type), which the protocol ignores.
std::optional<FrameId> frame_id(const CanFrame& frame);

// --- Messages ----------------------------------------------------------------------------------

enum class AckCode : std::uint8_t {
  kAccepted = 0,
  kIncomplete = 1,  // frames are missing: send again
  kCorrupt = 2,     // a frame's content is wrong: send again
  kRefused = 3,     // the node will not run it: emergency stop latched, or a fault
  kUnknown = 4,     // the answer to a RESULT_REQUEST for a job the node never ran (or forgot)
};
// How many jobs' answers the node keeps, by sequence number, to answer a job sent again or a
// RESULT_REQUEST from memory (also after a reboot). Fewer than the 255 sequence numbers a wrap
// takes, so that no two kept jobs share a number.
inline constexpr std::size_t kKeptJobs = 16;
enum class StopReason : std::uint8_t { kController = 0, kLinkLost = 1, kProtocolError = 2 };
enum class NodeState : std::uint8_t { kIdle = 0, kBusy = 1, kStopped = 2, kFaulted = 3 };

struct JobCommand {
  std::uint8_t seq = 0;
  Job job;
  friend bool operator==(const JobCommand&, const JobCommand&) = default;
};
struct JobAck {
  std::uint8_t seq = 0;
  AckCode code = AckCode::kAccepted;
  std::uint16_t detail = 0;  // kIncomplete: the first missing index
  friend bool operator==(const JobAck&, const JobAck&) = default;
};
struct JobProgress {
  std::uint8_t seq = 0;
  double progress_m = 0;
  friend bool operator==(const JobProgress&, const JobProgress&) = default;
};
struct JobResult {
  std::uint8_t seq = 0;
  JobReport report;
  RobotStatus status;
  friend bool operator==(const JobResult&, const JobResult&) = default;
};
// The answer to a status request and to a beacon request.
struct StatusReply {
  std::uint8_t seq = 0;
  RobotStatus status;
  friend bool operator==(const StatusReply&, const StatusReply&) = default;
};
struct RebootResult {
  std::uint8_t seq = 0;
  std::optional<std::string> failure;  // empty: rebooted
  RobotStatus status;
  friend bool operator==(const RebootResult&, const RebootResult&) = default;
};
enum class RequestKind : std::uint8_t { kStatus, kResult, kReboot, kBeacon };
struct Request {
  RequestKind kind = RequestKind::kStatus;
  std::uint8_t seq = 0;
  friend bool operator==(const Request&, const Request&) = default;
};
struct EmergencyStop {
  StopReason reason = StopReason::kController;
  friend bool operator==(const EmergencyStop&, const EmergencyStop&) = default;
};
struct EmergencyStopAck {
  friend bool operator==(const EmergencyStopAck&, const EmergencyStopAck&) = default;
};
struct Heartbeat {
  bool from_node = false;
  NodeState state = NodeState::kIdle;
  std::uint8_t counter = 0;
  std::uint8_t last_seq = 0;  // the node: the last job it finished
  friend bool operator==(const Heartbeat&, const Heartbeat&) = default;
};

using Message = std::variant<JobCommand, JobAck, JobProgress, JobResult, StatusReply, RebootResult,
                             Request, EmergencyStop, EmergencyStopAck, Heartbeat>;

MessageType message_type(const Message& message);
std::ostream& operator<<(std::ostream& os, const Message& message);

// The frames of `message`. A reason is cut to kMaxReasonBytes. The codes of job kinds and errors
// are wire_codes.h's. Preconditions (checked): a turn has at most (kMaxDataFrames - 5) / 4
// waypoints; a result's observation passes check_signature (core/manhole_signature.h) and has at
// most kMaxObservedSlots slots; a result's error is of its cause's kind (as RobotError builds it).
std::vector<CanFrame> encode(const Message& message);

// A message of the protocol that could not be read: which one, and why.
struct Malformed {
  MessageType type = MessageType::kJob;
  std::uint8_t seq = 0;
  std::string reason;  // "job 7: frame 2 of 3 missing"
  // Data frames that the end frame counts never arrived: a copy sent again fills the gaps (a
  // node answers a JOB so with ACK 1, incomplete; any other fault with ACK 2, corrupt).
  bool incomplete = false;
  friend bool operator==(const Malformed&, const Malformed&) = default;
};
using Decoded = std::variant<Message, Malformed>;

// Assembles frames into messages. Keeps at most one partial message per type (a new sequence
// number drops the old one), so memory is bounded whatever arrives. A message whose end frame
// arrived with data frames missing is reported malformed and kept: the frames of a copy sent
// again with the same sequence number fill the gaps, so a retry repairs a loss without every
// frame having to cross in one copy. Frames of other protocols are counted and ignored.
class MessageDecoder {
 public:
  // A complete message, a malformed one, or nothing yet.
  std::optional<Decoded> push(const CanFrame& frame);
  std::size_t foreign_frames() const { return foreign_frames_; }

 private:
  struct Partial {
    std::uint8_t seq = 0;
    std::map<std::uint16_t, CanFrame> frames;
    std::optional<CanFrame> end;  // once it arrived
  };
  // Decodes the partial of `type` once its end frame and every data frame are there.
  std::optional<Decoded> finish(MessageType type, const std::string& what);
  std::map<MessageType, Partial> partial_;
  std::size_t foreign_frames_ = 0;
};

// The decoding of one message's data frames (in index order), for tests and fuzzing.
Decoded decode_message(MessageType type, std::uint8_t seq, const std::vector<CanFrame>& frames);

// CRC-32 (IEEE 802.3, reflected, as zlib) of `bytes`.
std::uint32_t crc32(const std::vector<std::uint8_t>& bytes);

}  // namespace sewerplan::hal
