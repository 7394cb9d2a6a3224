// SPDX-License-Identifier: MIT
// The job protocol's frames (docs/can-protocol.md): every message survives encode and decode bit
// for bit, and malformed input is named, never trusted.
#include <bit>
#include <cmath>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/hal/can/job_protocol.h"

namespace sewerplan::hal {
namespace {

using ::testing::HasSubstr;

// Feeds all frames; the one message they make, or a test failure.
Decoded decode_all(const std::vector<CanFrame>& frames) {
  MessageDecoder decoder;
  std::optional<Decoded> out;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    std::optional<Decoded> d = decoder.push(frames[i]);
    if (d) {
      EXPECT_EQ(i + 1, frames.size()) << "a message before the last frame";
      out = std::move(d);
    }
  }
  if (!out) {
    ADD_FAILURE() << "no message";
    return Malformed{};
  }
  return *out;
}

Message round_trip(const Message& m) {
  const Decoded d = decode_all(encode(m));
  if (const auto* bad = std::get_if<Malformed>(&d)) {
    ADD_FAILURE() << bad->reason;
    return m;
  }
  return std::get<Message>(d);
}

std::string malformed_reason(const std::vector<CanFrame>& frames) {
  const Decoded d = decode_all(frames);
  const auto* bad = std::get_if<Malformed>(&d);
  return bad != nullptr ? bad->reason : std::string("decoded");
}

TEST(JobProtocol, EveryJobKindRoundTripsBitForBit) {
  const std::vector<Job> jobs{
      DriveForward{0.3, 12.345678901234567},
      DriveBackward{0.25, 1e-9},
      DriveForward{0.3, 7.5, true},
      DriveBackward{0.3, 0, true},
      Push{0.1, 0.5},
      Push{0.1, 0.5, true},
      TurnInManhole{2, 3, -94.5, -0.1, 1.0, 20.25, {}},
      TurnInManhole{0,
                    65535,
                    45,
                    0.05,
                    1.2,
                    7,
                    {{0.1, 0.2, 0.0, 90}, {-0.3, 0.4, 0.05, 180.5}, {0, 0, 0, 0}}},
      EnterPipeFromManhole{4, 12.5},
      LiftHead{},
      LowerHead{},
      TakeSample{60},
      Scan{0.2, 40.75, true},
      Scan{0.2, 40.75, false},
      Stop{},
  };
  for (const Job& job : jobs) {
    const Message m = JobCommand{200, job};
    EXPECT_EQ(round_trip(m), m) << job;
  }
}

TEST(JobProtocol, ATurnCarriesAThousandWaypointsAsASequenceOfFrames) {
  TurnInManhole t{1, 2, 30, 0, 1, 10, {}};
  for (int i = 0; i < 1000; ++i) t.waypoints.push_back({i * 0.001, -i * 0.002, 0.01, i * 0.36});
  const std::vector<CanFrame> frames = encode(JobCommand{9, t});
  EXPECT_EQ(frames.size(), 1U + 4U + 4000U + 1U);  // header, 4 numbers, waypoints, end
  EXPECT_EQ(round_trip(JobCommand{9, t}), Message(JobCommand{9, t}));
}

TEST(JobProtocol, ReportsStatusAndRebootsRoundTrip) {
  const RobotStatus status{123.456, 789.01, 3600.5, true, false};
  JobReport failed;
  failed.error = RobotError{RobotErrorKind::kBlockage, "obstacle in P5 at 4.00 m"};
  failed.progress_m = 3.95;
  failed.duration_s = 13.166666666666666;
  failed.energy_wh = 0.7315;
  const std::vector<Message> messages{
      JobResult{1, JobReport{std::nullopt, 10, 33.3, 1.5}, status},
      JobResult{2, failed, status},
      JobResult{3, {RobotError{RobotErrorKind::kDanger, "danger in P7 at 1.00 m"}, 0, 0, 0}, {}},
      JobResult{4, {RobotError{RobotErrorKind::kMalfunction, std::string(300, 'x')}, 0, 0, 0}, {}},
      StatusReply{5, status},
      RebootResult{6, std::nullopt, status},
      RebootResult{7, "reboot failed: permanent malfunction at job 3", status},
      JobAck{8, AckCode::kIncomplete, 513},
      JobProgress{9, 2.5},
      Request{RequestKind::kReboot, 10},
      Request{RequestKind::kBeacon, 11},
      Request{RequestKind::kResult, 12},
      Request{RequestKind::kStatus, 13},
      EmergencyStop{StopReason::kLinkLost},
      EmergencyStopAck{},
      Heartbeat{true, NodeState::kStopped, 255, 17},
      Heartbeat{false, NodeState::kIdle, 1, 0},
  };
  for (const Message& m : messages) EXPECT_EQ(round_trip(m), m) << m;
}

TEST(JobProtocol, IdentifiersAreExtendedAndOrderedByPriority) {
  const std::vector<CanFrame> stop = encode(EmergencyStop{});
  const std::vector<CanFrame> job = encode(JobCommand{1, Stop{}});
  ASSERT_EQ(stop.size(), 1U);
  EXPECT_TRUE(stop[0].extended);
  EXPECT_EQ(stop[0].id, 0x00100000U);
  EXPECT_EQ(job.front().id, 0x01001000U);  // type 0x010, seq 1, index 0
  EXPECT_EQ(job.back().id, 0x01001FFFU);   // the end frame
  EXPECT_LT(stop[0].id, job.front().id);   // an emergency stop wins arbitration
}

TEST(JobProtocol, NumbersAreLittleEndianBinary64) {
  const std::vector<CanFrame> frames = encode(JobProgress{1, 1.0});
  ASSERT_EQ(frames.size(), 1U);
  const std::array<std::uint8_t, 8> one{0, 0, 0, 0, 0, 0, 0xf0, 0x3f};
  EXPECT_EQ(frames[0].data, one);
}

TEST(JobProtocol, AMissingFrameIsNamed) {
  std::vector<CanFrame> frames = encode(JobCommand{5, DriveForward{0.3, 2}});
  frames.erase(frames.begin() + 1);
  EXPECT_THAT(malformed_reason(frames), HasSubstr("job 5: frame 1 of 3 missing"));
}

TEST(JobProtocol, ACorruptedByteFailsTheCrc) {
  std::vector<CanFrame> frames = encode(JobCommand{5, DriveForward{0.3, 2}});
  frames[2].data[3] ^= 0x10U;
  EXPECT_THAT(malformed_reason(frames), HasSubstr("CRC mismatch"));
}

TEST(JobProtocol, WrongLengthsKindsAndCountsAreMalformed) {
  // Unknown job kind, with a correct CRC: the content is checked too.
  std::vector<CanFrame> header{encode(JobCommand{1, Stop{}})[0]};
  header[0].data[0] = 42;
  EXPECT_THAT(std::get<Malformed>(decode_message(MessageType::kJob, 1, header)).reason,
              HasSubstr("unknown job kind 42"));
  // A drive without its distance.
  std::vector<CanFrame> drive = encode(JobCommand{1, DriveForward{1, 2}});
  drive.resize(2);
  EXPECT_THAT(std::get<Malformed>(decode_message(MessageType::kJob, 1, drive)).reason,
              HasSubstr("frame 2 missing"));
  // A progress of 7 bytes, a NaN progress, an unknown outcome.
  CanFrame progress = encode(JobProgress{3, 1})[0];
  progress.dlc = 7;
  EXPECT_THAT(std::get<Malformed>(decode_message(MessageType::kProgress, 3, {progress})).reason,
              HasSubstr("has 7 bytes, expected 8"));
  EXPECT_THAT(std::get<Malformed>(
                  decode_all(encode(JobProgress{3, std::numeric_limits<double>::quiet_NaN()})))
                  .reason,
              HasSubstr("not a finite number"));
  std::vector<CanFrame> result = encode(JobResult{4, {}, {}});
  result.pop_back();
  result[0].data[0] = 9;
  EXPECT_THAT(std::get<Malformed>(decode_message(MessageType::kResult, 4, result)).reason,
              HasSubstr("unknown outcome 9"));
}

// Issue 30: a push met while backing is pushed backward, with the rear head. The direction is bit
// 0 of the header's flags byte, as a Scan's; a forward push is the frames it always was, and
// other bits are refused.
TEST(JobProtocol, IssueThirtyAPushCarriesItsDirectionInTheFlagsByte) {
  const std::vector<CanFrame> backward = encode(JobCommand{7, Push{0.1, 0.5, true}});
  const std::vector<CanFrame> forward = encode(JobCommand{7, Push{0.1, 0.5, false}});
  ASSERT_EQ(backward.size(), 4U);     // header, speed, distance, end
  EXPECT_EQ(backward[0].data[0], 3);  // Push
  EXPECT_EQ(backward[0].data[1], 1);
  EXPECT_EQ(forward[0].data[1], 0);
  for (std::size_t i = 1; i + 1 < backward.size(); ++i) EXPECT_EQ(backward[i], forward[i]);
  const Decoded d = decode_all(backward);
  ASSERT_TRUE(std::holds_alternative<Message>(d));
  const auto& command = std::get<JobCommand>(std::get<Message>(d));
  ASSERT_TRUE(std::holds_alternative<Push>(command.job));
  EXPECT_TRUE(std::get<Push>(command.job).backward);
  std::vector<CanFrame> header{backward[0], backward[1], backward[2]};
  header[0].data[1] = 2;
  EXPECT_THAT(std::get<Malformed>(decode_message(MessageType::kJob, 7, header)).reason,
              HasSubstr("unknown push flags"));
}

TEST(JobProtocol, AnEndFrameAloneOrForAnotherSequenceIsMalformed) {
  std::vector<CanFrame> a = encode(JobCommand{1, LiftHead{}});
  std::vector<CanFrame> b = encode(JobCommand{2, LiftHead{}});
  MessageDecoder decoder;
  EXPECT_FALSE(decoder.push(a[0]));
  const std::optional<Decoded> d = decoder.push(b[1]);  // end of 2 after data of 1
  ASSERT_TRUE(d);
  EXPECT_THAT(std::get<Malformed>(*d).reason, HasSubstr("end frame without data frames"));
}

TEST(JobProtocol, ForeignFramesAreCountedAndIgnored) {
  MessageDecoder decoder;
  EXPECT_FALSE(decoder.push(*make_can_frame(0x123, false, {1, 2, 3})));
  EXPECT_FALSE(decoder.push(*make_can_frame(0x1fffffff, true, {})));
  EXPECT_FALSE(decoder.push(*make_remote_frame(0x01001000, true, 8)));
  EXPECT_EQ(decoder.foreign_frames(), 3U);
}

TEST(JobProtocol, ARetransmittedMessageDecodesAgain) {
  const std::vector<CanFrame> frames = encode(JobResult{7, {}, {}});
  MessageDecoder decoder;
  int complete = 0;
  for (int copy = 0; copy < 2; ++copy) {
    for (const CanFrame& f : frames) complete += decoder.push(f) ? 1 : 0;
  }
  EXPECT_EQ(complete, 2);
}

// At a high frame loss few copies of a long message cross whole: each copy sent again (the same
// sequence number) fills the frames the copies before it missed. A decoder that dropped what had
// arrived with each incomplete copy needed one copy to cross whole (9 frames at 20 % loss: 13 %).
TEST(JobProtocol, ACopySentAgainFillsTheFramesTheCopiesBeforeItMissed) {
  const JobResult result{7, {.progress_m = 3, .duration_s = 10, .energy_wh = 1}, {}};
  const std::vector<CanFrame> frames = encode(result);
  ASSERT_GE(frames.size(), 4U);
  MessageDecoder decoder;
  // Copy 1 misses frame 1; copy 2, which misses frame 2, completes the message with its frame 1.
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i == 1) continue;
    const std::optional<Decoded> d = decoder.push(frames[i]);
    EXPECT_EQ(d.has_value(), i + 1 == frames.size()) << i;
    if (d) {
      EXPECT_THAT(std::get<Malformed>(*d).reason, HasSubstr("result 7: frame 1 of"));
    }
  }
  std::optional<Decoded> whole;
  for (std::size_t i = 0; i < frames.size() && !whole; ++i) {
    if (i != 2) whole = decoder.push(frames[i]);
  }
  ASSERT_TRUE(whole);
  ASSERT_TRUE(std::holds_alternative<Message>(*whole)) << std::get<Malformed>(*whole).reason;
  EXPECT_EQ(std::get<Message>(*whole), Message{result});
  // A copy whose end frame is lost completes when a later frame fills the last gap.
  MessageDecoder late;
  for (std::size_t i = 0; i + 1 < frames.size(); ++i) {
    if (i != 0) {
      EXPECT_FALSE(late.push(frames[i]));
    }
  }
  EXPECT_TRUE(late.push(frames.back()));  // malformed: frame 0 missing; kept
  const std::optional<Decoded> filled = late.push(frames[0]);
  ASSERT_TRUE(filled);
  EXPECT_EQ(std::get<Message>(*filled), Message{result});
}

// Issue 29: a drive that ends at a manhole it detected reports what the robot saw of it. The
// odometry is the report's progress_m (and the status's odometry_m), as before.
JobReport observed_drive() {
  JobReport r;
  r.progress_m = 12.345678901234567;  // the wheels' measure, slip and all
  r.duration_s = 41.15;
  r.energy_wh = 2.0 / 3.0;
  r.observation = ManholeSignature{
      .slots = {{0, 0, 0.3}, {87.25, -0.0412, 0.25}, {181.5, 0.1 / 3, 0.2999999999999999}},
      .shaft_diameter_m = 1.0000000000000002};
  return r;
}

void put_f64(CanFrame& frame, double value) {
  const auto bits = std::bit_cast<std::uint64_t>(value);
  for (std::size_t i = 0; i < 8; ++i) frame.data[i] = static_cast<std::uint8_t>(bits >> (8 * i));
}

TEST(JobProtocol, AResultCarriesTheManholeObservationBitForBit) {
  const RobotStatus status{99.5, 512.25, 1800, false, false};
  JobReport blocked = observed_drive();
  blocked.error = RobotError{RobotErrorKind::kBlockage, "obstacle in P5 at 4.00 m"};
  ManholeSignature many;
  for (std::size_t i = 0; i < kMaxObservedSlots; ++i) {
    many.slots.push_back({3.5 * static_cast<double>(i), 0.01 * static_cast<double>(i), 0.3});
  }
  many.shaft_diameter_m = 4;
  JobReport crowded = observed_drive();
  crowded.observation = many;
  for (const JobResult& result : {JobResult{1, observed_drive(), status},
                                  JobResult{2, blocked, status}, JobResult{3, crowded, {}}}) {
    const std::vector<CanFrame> frames = encode(result);
    // The 6-byte header, 6 numbers, the reason, 3 frames a slot (slots[0]'s direction, always 0,
    // is not sent, the shaft is), the end frame.
    const std::size_t reason = result.report.error ? 3 : 0;
    const std::size_t slots = result.report.observation->slots.size();
    EXPECT_EQ(frames.size(), 1 + 6 + reason + 3 * slots + 1);
    EXPECT_EQ(frames[0].dlc, 6);
    EXPECT_EQ(frames[0].data[4] | (frames[0].data[5] << 8),
              static_cast<int>(result.report.observation->slots.size()));
    const Message back = round_trip(result);
    EXPECT_EQ(back, Message{result});
    // Bit for bit: a run over the bus equals one in process.
    EXPECT_EQ(encode(back), frames);
  }
}

TEST(JobProtocol, AResultWithoutAnObservationKeepsTheEarlierLayout) {
  JobReport plain = observed_drive();
  plain.observation.reset();
  const std::vector<CanFrame> frames = encode(JobResult{4, plain, {}});
  ASSERT_EQ(frames.size(), 8U);  // header, 6 numbers, end: as before issue 29
  EXPECT_EQ(frames[0].dlc, 4);
  const Message back = round_trip(JobResult{4, plain, {}});
  EXPECT_FALSE(std::get<JobResult>(back).report.observation.has_value());
}

TEST(JobProtocol, AMalformedObservationIsNamed) {
  JobReport r = observed_drive();
  std::vector<CanFrame> good = encode(JobResult{5, r, {}});
  good.pop_back();  // decode_message takes the data frames
  // Frames 0 header, 1-6 numbers, 7 shaft, 8-9 slot 1 (step, diameter), 10-12 slot 2, 13-15 slot 3.
  ASSERT_EQ(good.size(), 16U);
  const auto reason_of = [](const std::vector<CanFrame>& frames) {
    const Decoded d = decode_message(MessageType::kResult, 5, frames);
    const auto* bad = std::get_if<Malformed>(&d);
    return bad != nullptr ? bad->reason : std::string("decoded");
  };
  EXPECT_EQ(reason_of(good), "decoded");
  const auto with = [&](std::size_t frame, double value) {
    std::vector<CanFrame> f = good;
    put_f64(f[frame], value);
    return reason_of(f);
  };
  const auto slots = [&](std::uint16_t n) {
    std::vector<CanFrame> f = good;
    f[0].data[4] = static_cast<std::uint8_t>(n & 0xffU);
    f[0].data[5] = static_cast<std::uint8_t>(n >> 8U);
    return reason_of(f);
  };
  EXPECT_THAT(slots(0), HasSubstr("result 5: an observation of 0 slots"));
  EXPECT_THAT(slots(101), HasSubstr("an observation of 101 slots (at most 100)"));
  EXPECT_THAT(slots(4), HasSubstr("frame 16 missing"));
  EXPECT_THAT(slots(2), HasSubstr("16 frames, expected 13"));
  EXPECT_THAT(with(7, 0), HasSubstr("observation: shaft diameter 0 is not > 0"));
  EXPECT_THAT(with(9, std::numeric_limits<double>::quiet_NaN()),
              HasSubstr("observation: slot 1: diameter nan is not > 0"));
  EXPECT_THAT(with(10, 400), HasSubstr("observation: slot 2: direction 400 is not in [0, 360)"));
  EXPECT_THAT(with(13, 10), HasSubstr("observation: slot 3: directions must be counter-clockwise"));
  EXPECT_THAT(with(14, std::numeric_limits<double>::infinity()),
              HasSubstr("observation: slot 3: the step is not a number"));
  std::vector<CanFrame> long_header = good;
  long_header[0].dlc = 7;
  EXPECT_THAT(reason_of(long_header), HasSubstr("frame 0 has 7 bytes, expected 4"));
  // An observation's frames lost on the way: the copy sent again fills them, as for any result.
  const std::vector<CanFrame> frames = encode(JobResult{5, r, {}});
  MessageDecoder decoder;
  std::optional<Decoded> first;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i != 8 && i != 14) first = decoder.push(frames[i]);
  }
  ASSERT_TRUE(first);
  EXPECT_THAT(std::get<Malformed>(*first).reason, HasSubstr("result 5: frame 8 of 16 missing"));
  EXPECT_FALSE(decoder.push(frames[8]));
  const std::optional<Decoded> whole = decoder.push(frames[14]);
  ASSERT_TRUE(whole);
  EXPECT_EQ(std::get<Message>(*whole), (Message{JobResult{5, r, {}}}));
}

// Issue 29: a turn reports the angle the robot's joints measured (JobReport::turn_measured_deg),
// bit for bit, in a RESULT whose header has 5 bytes (byte 4: a measured turn), the angle after the
// reason. A wrong marker, an angle out of [0, 360) and a missing frame are named.
TEST(JobProtocol, AResultCarriesTheMeasuredTurn) {
  JobReport turned;
  turned.duration_s = 20;
  turned.energy_wh = 0.5;
  turned.turn_measured_deg = 271.30000000000001;
  JobReport failed = turned;
  failed.error = RobotError{RobotErrorCause::kFault, "motor 3 over current"};
  for (const JobResult& result : {JobResult{6, turned, {}}, JobResult{7, failed, {}}}) {
    const std::vector<CanFrame> frames = encode(result);
    const std::size_t reason = result.report.error ? 3 : 0;
    EXPECT_EQ(frames.size(), 1 + 6 + reason + 1 + 1);
    EXPECT_EQ(frames[0].dlc, 5);
    EXPECT_EQ(frames[0].data[4], 1);
    const Message back = round_trip(result);
    EXPECT_EQ(back, Message{result});
    EXPECT_EQ(encode(back), frames);
  }
  std::vector<CanFrame> good = encode(JobResult{6, turned, {}});
  good.pop_back();
  const auto reason_of = [](const std::vector<CanFrame>& frames) {
    const Decoded d = decode_message(MessageType::kResult, 6, frames);
    const auto* bad = std::get_if<Malformed>(&d);
    return bad != nullptr ? bad->reason : std::string("decoded");
  };
  EXPECT_EQ(reason_of(good), "decoded");
  std::vector<CanFrame> marker = good;
  marker[0].data[4] = 2;
  EXPECT_THAT(reason_of(marker), HasSubstr("result 6: frame 0: unknown measurement 2"));
  for (const double bad : {360.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    std::vector<CanFrame> f = good;
    put_f64(f[7], bad);
    EXPECT_THAT(reason_of(f), HasSubstr("a measured turn of")) << bad;
  }
  std::vector<CanFrame> missing = good;
  missing.pop_back();
  EXPECT_THAT(reason_of(missing), HasSubstr("frame 7 missing"));
}

// A drive through water says so in its RESULT: bit 2 of the header's flags byte, beside the status
// flags (which the STATUS message carries without it); every other layout is unchanged.
TEST(JobProtocol, AResultCarriesWaterBesideTheStatusFlags) {
  JobReport wet;
  wet.progress_m = 4.5;
  wet.in_water = true;
  JobReport seen = wet;
  seen.observation = ManholeSignature{.slots = {{0, 0, 0.3}, {180, 0, 0.3}}, .shaft_diameter_m = 1};
  RobotStatus lifted;
  lifted.head_lifted = true;
  for (const JobResult& result : {JobResult{8, wet, {}}, JobResult{9, seen, lifted}}) {
    const std::vector<CanFrame> frames = encode(result);
    EXPECT_EQ(frames[0].data[1], result.status.head_lifted ? 0x05 : 0x04);
    EXPECT_EQ(round_trip(result), Message{result});
    JobResult dry = result;
    dry.report.in_water = false;
    const std::vector<CanFrame> dry_frames = encode(dry);
    EXPECT_EQ(dry_frames[0].data[1], result.status.head_lifted ? 0x01 : 0x00);
    EXPECT_EQ(round_trip(dry), Message{dry});
  }
  std::vector<CanFrame> unknown = encode(JobResult{8, wet, {}});
  unknown[0].data[1] = 0x08;
  const Decoded d = decode_message(MessageType::kResult, 8, unknown);
  ASSERT_TRUE(std::holds_alternative<Malformed>(d));
  EXPECT_THAT(std::get<Malformed>(d).reason, HasSubstr("unknown status flags"));
}

TEST(JobProtocol, Crc32IsTheZlibOne) {
  const std::string text = "123456789";
  EXPECT_EQ(crc32(std::vector<std::uint8_t>(text.begin(), text.end())), 0xCBF43926U);
}

}  // namespace
}  // namespace sewerplan::hal
