// SPDX-License-Identifier: MIT
// Candump logs: the can-utils format written and read back, errors with file and line, and the
// recording and replay buses.
#include "sewerplan/hal/can/candump.h"

#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/hal/can/job_protocol.h"

namespace sewerplan::hal {
namespace {

using ::testing::HasSubstr;

TEST(Candump, LinesAreTheCanUtilsFormat) {
  EXPECT_EQ(
      candump_line({1700000000.123456, "can0", *make_can_frame(0x123, false, {0xde, 0xad}), 0}),
      "(1700000000.123456) can0 123#DEAD");
  EXPECT_EQ(candump_line({0.5, "vcan1", *make_can_frame(0x1f334455, true, {}), 0}),
            "(0000000000.500000) vcan1 1F334455#");
  EXPECT_EQ(candump_line({2, "can0", *make_remote_frame(0x7ff, false, 3), 0}),
            "(0000000002.000000) can0 7FF#R3");
}

TEST(Candump, WhatIsWrittenReadsBack) {
  std::stringstream log;
  std::vector<CandumpRecord> written;
  for (const CanFrame& f : encode(JobCommand{3, DriveForward{0.3, 12.5}})) {
    written.push_back({1700000000.25, "can0", f, 0});
    log << candump_line(written.back()) << '\n';
  }
  log << "\n(1700000001.000000) can0 123#R\n";
  Result<std::vector<CandumpRecord>> read = read_candump(log, "x.log");
  ASSERT_TRUE(read.has_value()) << read.error().message;
  ASSERT_EQ(read->size(), written.size() + 1);
  for (std::size_t i = 0; i < written.size(); ++i) {
    EXPECT_EQ((*read)[i].frame, written[i].frame);
    EXPECT_DOUBLE_EQ((*read)[i].time_s, written[i].time_s);
    EXPECT_EQ((*read)[i].line, i + 1);
  }
  EXPECT_TRUE(read->back().frame.remote);
}

TEST(Candump, ReaderErrorsNameTheFileAndLine) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"(1.000000) can0 123DEAD", "x.log:2: expected ID#DATA"},
      {"1.000000 can0 123#00", "x.log:2: expected '(SECONDS.MICROS)"},
      {"(1.5) can0 123#00", "x.log:2: bad time"},
      {"(1.000000) can0 12#00", "x.log:2: a CAN identifier has 3"},
      {"(1.000000) can0 123#0", "x.log:2: expected 0 to 8 data bytes"},
      {"(1.000000) can0 123#001122334455667788", "x.log:2: expected 0 to 8"},
      {"(1.000000) can0 123#ZZ", "x.log:2: bad hex data"},
      {"(1.000000) can0 800#00", "x.log:2: CAN identifier 0x800 does not fit 11 bits"},
      {"(1.000000)can0 123#00", "x.log:2: expected ' ' after the time"},
  };
  for (const auto& [line, message] : cases) {
    std::stringstream log("(1.000000) can0 123#00\n" + line + "\n");
    Result<std::vector<CandumpRecord>> read = read_candump(log, "x.log");
    ASSERT_FALSE(read.has_value()) << line;
    EXPECT_THAT(read.error().message, HasSubstr(message)) << line;
  }
  EXPECT_THAT(read_candump_file("/no/such.log").error().message,
              HasSubstr("cannot read /no/such.log: No such file or directory"));
}

TEST(Candump, TheRecorderWritesBothDirections) {
  auto [a, b] = make_memory_can_pair();
  std::ostringstream out;
  ManualClock clock(1700000000);
  RecordingCanBus recording(*a, out, clock);
  ASSERT_TRUE(recording.send(*make_can_frame(0x100, false, {1})).has_value());
  ASSERT_TRUE(b->send(*make_can_frame(0x200, false, {2})).has_value());
  clock.advance(0.5);
  ASSERT_TRUE(recording.receive(1.0)->has_value());
  EXPECT_EQ(out.str(), "(1700000000.000000) can0 100#01\n(1700000000.500000) can0 200#02\n");
}

TEST(Candump, TheReplayServesTheNodeAndChecksTheController) {
  std::vector<CandumpRecord> records;
  for (const CanFrame& f : encode(Request{RequestKind::kStatus, 1}))
    records.push_back({0, "can0", f, 1});
  for (const CanFrame& f : encode(Heartbeat{false, NodeState::kIdle, 0, 0})) {
    records.push_back({0, "can0", f, 2});
  }
  const std::vector<CanFrame> answer = encode(StatusReply{1, {}});
  for (const CanFrame& f : answer) records.push_back({0, "can0", f, 3});
  ReplayCanBus replay(records, "r.log");
  // The controller's heartbeats are not checked; its other frames are.
  EXPECT_TRUE(replay.send(encode(Heartbeat{false, NodeState::kIdle, 9, 9})[0]).has_value());
  const Result<void> wrong = replay.send(encode(Request{RequestKind::kReboot, 1})[0]);
  ASSERT_FALSE(wrong.has_value());
  EXPECT_THAT(wrong.error().message, HasSubstr("replay:r.log:1: the controller sent"));
  EXPECT_TRUE(replay.send(encode(Request{RequestKind::kStatus, 1})[0]).has_value());
  EXPECT_EQ(replay.unsent(), 0U);
  for (const CanFrame& f : answer) EXPECT_EQ(**replay.receive(0), f);
  EXPECT_FALSE(replay.receive(10.0)->has_value());  // the end: at once
}

}  // namespace
}  // namespace sewerplan::hal
