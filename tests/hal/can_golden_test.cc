// SPDX-License-Identifier: MIT
// Golden frames of the job protocol (docs/can-protocol.md): for every job kind and every error
// code of a RESULT, the exact frames on the bus. A change of the wire (a reordered Job variant, a
// renumbered code: hal/can/wire_codes.h) breaks these, not a robot in the field. The frames were
// written from the protocol's document by an encoder of its own (Python, zlib's CRC-32), not by
// sewerplan's.
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/hal/can/can_bus.h"
#include "sewerplan/hal/can/can_frame.h"
#include "sewerplan/hal/can/job_protocol.h"
#include "sewerplan/hal/can/sim_node.h"
#include "sewerplan/hal/can/wire_codes.h"
#include "sewerplan/hal/sim_robot.h"

#include "support/ais_testbed.h"

namespace sewerplan::hal {
namespace {

std::vector<std::string> texts(const std::vector<CanFrame>& frames) {
  std::vector<std::string> out;
  for (const CanFrame& f : frames) out.push_back(to_candump_text(f));
  return out;
}

// The message the frames decode to, through a MessageDecoder, or a test failure.
std::optional<Message> decoded(const std::vector<std::string>& frames) {
  MessageDecoder decoder;
  std::optional<Decoded> out;
  for (const std::string& text : frames) {
    Result<CanFrame> frame = parse_candump_frame(text);
    if (!frame.has_value()) {
      ADD_FAILURE() << text << ": " << frame.error().message;
      return std::nullopt;
    }
    out = decoder.push(*frame);
  }
  if (!out || !std::holds_alternative<Message>(*out)) {
    ADD_FAILURE() << "not decoded: "
                  << (out ? std::get<Malformed>(*out).reason : std::string("no message"));
    return std::nullopt;
  }
  return std::get<Message>(*out);
}

struct GoldenJob {
  Job job;
  std::uint8_t seq = 0;
  std::vector<std::string> frames;
};

// One of each kind, sequence numbers 1 to 10; numbers exact in binary64.
const std::vector<GoldenJob>& golden_jobs() {
  static const std::vector<GoldenJob> kJobs{
      {DriveForward{0.5, 2.0, true},
       1,
       {"01001000#0101000000000000", "01001001#000000000000E03F", "01001002#0000000000000040",
        "01001FFF#030031062109"}},
      {DriveBackward{0.25, 1.0},
       2,
       {"01002000#0200000000000000", "01002001#000000000000D03F", "01002002#000000000000F03F",
        "01002FFF#0300E54AB976"}},
      {Push{0.5, 0.25, true},
       3,
       {"01003000#0301000000000000", "01003001#000000000000E03F", "01003002#000000000000D03F",
        "01003FFF#03008C639891"}},
      {TurnInManhole{1, 3, 90.0, -0.5, 1.0, 20.0, {Waypoint{0.5, 0, 0, 90.0}}},
       4,
       {"01004000#0400010003000100", "01004001#0000000000805640", "01004002#000000000000E0BF",
        "01004003#000000000000F03F", "01004004#0000000000003440", "01004005#000000000000E03F",
        "01004006#0000000000000000", "01004007#0000000000000000", "01004008#0000000000805640",
        "01004FFF#09002693F82E"}},
      {EnterPipeFromManhole{2, 4.0},
       5,
       {"01005000#0500020000000000", "01005001#0000000000001040", "01005FFF#02002F01924B"}},
      {LiftHead{}, 6, {"01006000#0600000000000000", "01006FFF#0100EED64DA3"}},
      {LowerHead{}, 7, {"01007000#0700000000000000", "01007FFF#010070D6E76F"}},
      {TakeSample{30.0},
       8,
       {"01008000#0800000000000000", "01008001#0000000000003E40", "01008FFF#0200F78EB1A8"}},
      {Scan{0.25, 2.0, false},
       9,
       {"01009000#0900000000000000", "01009001#000000000000D03F", "01009002#0000000000000040",
        "01009FFF#03006352AC28"}},
      {Stop{}, 10, {"0100A000#0A00000000000000", "0100AFFF#0100A1C3E2F4"}},
  };
  return kJobs;
}

TEST(CanGoldenFrames, EveryJobKindHasItsFramesOnTheBus) {
  std::set<std::size_t> kinds;
  for (const GoldenJob& g : golden_jobs()) {
    SCOPED_TRACE(std::string(job_kind(g.job)));
    kinds.insert(g.job.index());
    const JobCommand command{g.seq, g.job};
    EXPECT_EQ(texts(encode(command)), g.frames);
    EXPECT_EQ(decoded(g.frames), std::optional<Message>(command));
  }
  EXPECT_EQ(kinds.size(), std::variant_size_v<Job>) << "a job kind without golden frames";
}

// A RESULT of sequence number 0x21: progress 1 m, 2 s, 0.5 Wh; battery 100 Wh, odometry 1 m,
// elapsed 2 s; no flags; the reason "stop" for an error. Only the header's byte 0 (the outcome
// code) and the end frame's CRC differ from code to code.
const std::vector<std::string> kResultNumbers{
    "02221001#000000000000F03F", "02221002#0000000000000040", "02221003#000000000000E03F",
    "02221004#0000000000005940", "02221005#000000000000F03F", "02221006#0000000000000040"};
const std::string kStopReason = "02221007#73746F70";

JobResult golden_result(std::optional<RobotError> error) {
  JobResult r;
  r.seq = 0x21;
  r.report.error = std::move(error);
  r.report.progress_m = 1.0;
  r.report.duration_s = 2.0;
  r.report.energy_wh = 0.5;
  r.status.battery_wh = 100.0;
  r.status.odometry_m = 1.0;
  r.status.elapsed_s = 2.0;
  return r;
}

std::vector<std::string> result_frames(const std::string& header, const std::string& end) {
  std::vector<std::string> frames{header};
  frames.insert(frames.end(), kResultNumbers.begin(), kResultNumbers.end());
  if (header != "02221000#00000000") frames.push_back(kStopReason);
  frames.push_back(end);
  return frames;
}

TEST(CanGoldenFrames, ADoneJobsResult) {
  const JobResult done = golden_result(std::nullopt);
  const std::vector<std::string> frames =
      result_frames("02221000#00000000", "02221FFF#070053FF907F");
  EXPECT_EQ(texts(encode(done)), frames);
  EXPECT_EQ(decoded(frames), std::optional<Message>(done));
}

struct GoldenError {
  RobotErrorCause cause;
  std::string header;  // data frame 0: the outcome code, flags 0, reason length 4
  std::string end;
};

// Codes 1-3 (an error known by its kind alone) are the frames of earlier versions, byte for byte.
const std::vector<GoldenError>& golden_errors() {
  static const std::vector<GoldenError> kErrors{
      {RobotErrorCause::kOtherBlockage, "02221000#01000400", "02221FFF#0800AFD18E74"},
      {RobotErrorCause::kOtherDanger, "02221000#02000400", "02221FFF#0800D6E53152"},
      {RobotErrorCause::kOtherMalfunction, "02221000#03000400", "02221FFF#080001F6A44F"},
      {RobotErrorCause::kObstacle, "02221000#11000400", "02221FFF#08009EEAAE76"},
      {RobotErrorCause::kBlindEnd, "02221000#12000400", "02221FFF#0800E7DE1150"},
      {RobotErrorCause::kNoManholeSeen, "02221000#13000400", "02221FFF#080030CD844D"},
      {RobotErrorCause::kNoMouth, "02221000#14000400", "02221FFF#080015B66F1D"},
      {RobotErrorCause::kDangerSpot, "02221000#21000400", "02221FFF#0800CDA7CE70"},
      {RobotErrorCause::kDangerousPassage, "02221000#22000400", "02221FFF#0800B4937156"},
      {RobotErrorCause::kFault, "02221000#31000400", "02221FFF#0800FC9CEE72"},
      {RobotErrorCause::kBatteryEmpty, "02221000#32000400", "02221FFF#080085A85154"},
      {RobotErrorCause::kInvalidJob, "02221000#33000400", "02221FFF#080052BBC449"},
      {RobotErrorCause::kEmergencyStop, "02221000#34000400", "02221FFF#080077C02F19"},
      {RobotErrorCause::kLink, "02221000#35000400", "02221FFF#0800A0D3BA04"},
      {RobotErrorCause::kNotAtStart, "02221000#36000400", "02221FFF#0800D9E70522"},
  };
  return kErrors;
}

TEST(CanGoldenFrames, EveryErrorCauseHasItsFramesOnTheBus) {
  std::set<RobotErrorCause> causes;
  for (const GoldenError& g : golden_errors()) {
    SCOPED_TRACE(std::string(to_string(g.cause)));
    causes.insert(g.cause);
    const JobResult result = golden_result(RobotError{g.cause, "stop"});
    const std::vector<std::string> frames = result_frames(g.header, g.end);
    EXPECT_EQ(texts(encode(result)), frames);
    const std::optional<Message> back = decoded(frames);
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(*back, Message{result});
    const RobotError& error = *std::get<JobResult>(*back).report.error;
    EXPECT_EQ(error.cause, g.cause);
    EXPECT_EQ(error.kind, kind_of(g.cause));
  }
  EXPECT_EQ(causes.size(), kRobotErrorCauses) << "an error cause without golden frames";
}

// An error built from its kind alone is the kind's code of earlier versions.
TEST(CanGoldenFrames, AnErrorKnownByItsKindAloneKeepsTheEarlierCodes) {
  EXPECT_EQ(encode(golden_result(RobotError{RobotErrorKind::kBlockage, "stop"}))[0],
            encode(golden_result(RobotError{RobotErrorCause::kOtherBlockage, "stop"}))[0]);
  EXPECT_EQ(encode(golden_result(RobotError{RobotErrorKind::kDanger, "x"}))[0].data[0], 2);
  EXPECT_EQ(encode(golden_result(RobotError{RobotErrorKind::kMalfunction, "x"}))[0].data[0], 3);
}

// An unknown code (a node of a later version, a damaged log) is a malformed message that names the
// code and the frame; the decoder goes on with the next message.
TEST(CanGoldenFrames, AnUnknownCodeIsNamedWithItsFrame) {
  // Job kinds: a code no kind has, with the message's CRC right.
  for (const int kind : {0, 11, 0x42, 0xff}) {
    const auto code = static_cast<std::uint8_t>(kind);
    SCOPED_TRACE(int{code});
    std::vector<CanFrame> frames = encode(JobCommand{9, Stop{}});
    frames[0].data[0] = code;
    std::vector<std::uint8_t> data(frames[0].bytes().begin(), frames[0].bytes().end());
    const std::uint32_t crc = crc32(data);
    for (std::size_t i = 0; i < 4; ++i)
      frames[1].data[2 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
    MessageDecoder decoder;
    EXPECT_FALSE(decoder.push(frames[0]).has_value());
    const std::optional<Decoded> d = decoder.push(frames[1]);
    ASSERT_TRUE(d.has_value());
    ASSERT_TRUE(std::holds_alternative<Malformed>(*d));
    EXPECT_EQ(std::get<Malformed>(*d).reason, "job 9: frame 0: unknown job kind " +
                                                  std::to_string(code) +
                                                  " (the kinds are 1, 2, 3, 4, 5, 6, 7, 8, 9, 10)");
    // The next message decodes.
    for (const CanFrame& f : encode(JobCommand{10, LiftHead{}})) {
      if (const std::optional<Decoded> next = decoder.push(f)) {
        EXPECT_TRUE(std::holds_alternative<Message>(*next));
      }
    }
  }
  // Errors: codes between and beyond the table's.
  const std::vector<std::pair<int, std::string>> outcomes{
      {4, "4 (0x04)"},     {0x10, "16 (0x10)"}, {0x15, "21 (0x15)"},
      {0x23, "35 (0x23)"}, {0x37, "55 (0x37)"}, {0xff, "255 (0xFF)"}};
  for (const auto& [code, named] : outcomes) {
    SCOPED_TRACE(code);
    std::vector<CanFrame> frames =
        encode(golden_result(RobotError{RobotErrorCause::kLink, "stop"}));
    frames.pop_back();
    frames[0].data[0] = static_cast<std::uint8_t>(code);
    const Decoded d = decode_message(MessageType::kResult, 0x21, frames);
    ASSERT_TRUE(std::holds_alternative<Malformed>(d));
    EXPECT_EQ(std::get<Malformed>(d).reason, "result 33: frame 0: unknown outcome " + named);
  }
}

// The tables, read through their functions: every code decodes to what encodes to it.
TEST(CanGoldenFrames, TheCodeTablesInvertEachOther) {
  for (const GoldenJob& g : golden_jobs()) {
    const std::optional<Job> blank = blank_job(job_code(g.job));
    ASSERT_TRUE(blank.has_value());
    EXPECT_EQ(blank->index(), g.job.index());
  }
  for (const GoldenError& g : golden_errors()) {
    EXPECT_EQ(error_cause(error_code(g.cause)), g.cause);
  }
  EXPECT_FALSE(error_cause(kDoneCode).has_value());
  EXPECT_FALSE(blank_job(0).has_value());
}

// The node answers a JOB whose end frame counted frames that never came with ACK 1 (incomplete),
// and one whose frames all came and do not make a job with ACK 2 (corrupt), by the decoder's typed
// Malformed::incomplete: a JOB too short for its kind was ACK 1 while the word "missing" in the
// reason decided.
TEST(CanGoldenFrames, TheNodeTellsMissingFramesFromACorruptJobByType) {
  const auto ais = testing::load_ais_testbed();
  SimRobot robot(ais.map, ais.mission.profile, InPipe{PipeId{0}, 0, Heading::kTowardsEnd1});
  auto buses = make_memory_can_pair();  // not a structured binding: a lambda uses it (clang)
  CanBus& controller = *buses.first;
  SimNode node(*buses.second, robot, {.heartbeat_s = 0});
  const auto answer = [&](const std::vector<CanFrame>& frames) -> std::optional<JobAck> {
    for (const CanFrame& f : frames) EXPECT_TRUE(controller.send(f).has_value());
    for (std::size_t i = 0; i < frames.size(); ++i) EXPECT_TRUE(node.poll(0.01).has_value());
    MessageDecoder decoder;
    for (;;) {
      Result<std::optional<CanFrame>> in = controller.receive(0.01);
      if (!in.has_value() || !in->has_value()) return std::nullopt;
      if (const std::optional<Decoded> d = decoder.push(**in)) {
        if (const auto* m = std::get_if<Message>(&*d)) {
          if (const auto* ack = std::get_if<JobAck>(m)) return *ack;
        }
      }
    }
  };
  // A gap: data frame 1 of a drive lost.
  std::vector<CanFrame> gap = encode(JobCommand{5, DriveForward{0.5, 2.0}});
  gap.erase(gap.begin() + 1);
  const std::optional<JobAck> incomplete = answer(gap);
  ASSERT_TRUE(incomplete.has_value());
  EXPECT_EQ(incomplete->code, AckCode::kIncomplete);
  // A drive without its numbers, its frame count and CRC right: "frame 1 missing (1 frames)".
  std::vector<CanFrame> short_drive = encode(JobCommand{6, LiftHead{}});
  short_drive[0].data[0] = job_code(DriveForward{});
  const std::vector<std::uint8_t> data(short_drive[0].bytes().begin(),
                                       short_drive[0].bytes().end());
  const std::uint32_t crc = crc32(data);
  for (std::size_t i = 0; i < 4; ++i) {
    short_drive[1].data[2 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
  }
  const std::optional<JobAck> corrupt = answer(short_drive);
  ASSERT_TRUE(corrupt.has_value());
  EXPECT_EQ(corrupt->code, AckCode::kCorrupt);
}

}  // namespace
}  // namespace sewerplan::hal
