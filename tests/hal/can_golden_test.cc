// SPDX-License-Identifier: MIT
// Golden frames of the job protocol (docs/can-protocol.md): for every job kind and every error
// code of a RESULT, the exact frames on the bus. A change of the wire (a reordered Job variant, a
// renumbered code) breaks these, not a robot in the field. The frames were written from the
// protocol's document by an encoder of its own (Python, zlib's CRC-32), not by sewerplan's.
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/hal/can/can_frame.h"
#include "sewerplan/hal/can/job_protocol.h"

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
  RobotError error;
  std::string header;  // data frame 0: the outcome code, flags 0, reason length 4
  std::string end;
};

TEST(CanGoldenFrames, EveryErrorKindHasItsFramesOnTheBus) {
  const std::vector<GoldenError> errors{
      {RobotError{RobotErrorKind::kBlockage, "stop"}, "02221000#01000400", "02221FFF#0800AFD18E74"},
      {RobotError{RobotErrorKind::kDanger, "stop"}, "02221000#02000400", "02221FFF#0800D6E53152"},
      {RobotError{RobotErrorKind::kMalfunction, "stop"}, "02221000#03000400",
       "02221FFF#080001F6A44F"},
  };
  for (const GoldenError& g : errors) {
    SCOPED_TRACE(g.header);
    const JobResult result = golden_result(g.error);
    const std::vector<std::string> frames = result_frames(g.header, g.end);
    EXPECT_EQ(texts(encode(result)), frames);
    EXPECT_EQ(decoded(frames), std::optional<Message>(result));
  }
}

}  // namespace
}  // namespace sewerplan::hal
