// SPDX-License-Identifier: MIT
// SLCAN: the line codec, and both ends of a line joined by a pseudo-terminal.
#include "sewerplan/hal/can/slcan.h"

#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/hal/can/socketcan.h"

#include <unistd.h>

namespace sewerplan::hal {
namespace {

using ::testing::HasSubstr;

TEST(SlcanCodec, FramesBecomeLinesAndBack) {
  const std::vector<CanFrame> frames{
      *make_can_frame(0x123, false, {0xde, 0xad}),
      *make_can_frame(0x1f334455, true, {1, 2, 3, 4, 5, 6, 7, 8}),
      *make_can_frame(0x7ff, false, {}),
      *make_remote_frame(0x100, false, 4),
      *make_remote_frame(0x10, true, 0),
  };
  EXPECT_EQ(encode_slcan_frame(frames[0]), "t1232DEAD\r");
  EXPECT_EQ(encode_slcan_frame(frames[1]), "T1F33445580102030405060708\r");
  EXPECT_EQ(encode_slcan_frame(frames[3]), "r1004\r");
  for (const CanFrame& f : frames) {
    std::string line = encode_slcan_frame(f);
    line.pop_back();
    Result<CanFrame> back = parse_slcan_frame(line);
    ASSERT_TRUE(back.has_value()) << back.error().message;
    EXPECT_EQ(*back, f) << line;
  }
}

TEST(SlcanCodec, ATimestampAfterTheDataIsDropped) {
  Result<CanFrame> f = parse_slcan_frame("t1232DEAD1A2B");
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(*f, *make_can_frame(0x123, false, {0xde, 0xad}));
}

TEST(SlcanCodec, BadLinesAreNamed) {
  EXPECT_THAT(parse_slcan_frame("x123").error().message, HasSubstr("unknown line type 'x'"));
  EXPECT_THAT(parse_slcan_frame("t12").error().message, HasSubstr("short frame"));
  EXPECT_THAT(parse_slcan_frame("t1239").error().message, HasSubstr("bad length"));
  EXPECT_THAT(parse_slcan_frame("t1232DE").error().message, HasSubstr("does not match the data"));
  EXPECT_THAT(parse_slcan_frame("t8002DEAD").error().message, HasSubstr("does not fit 11 bits"));
  EXPECT_THAT(parse_slcan_frame("t1232DEZZ").error().message, HasSubstr("bad data"));
  EXPECT_THAT(parse_slcan_frame(std::string("t12\x01"
                                            "0",
                                            5))
                  .error()
                  .message,
              HasSubstr("\\x01"));
}

TEST(SlcanSplitter, CutsLinesBellsAndOverlongLinesAcrossPartialReads) {
  SlcanSplitter s;
  s.feed("t12");
  EXPECT_FALSE(s.next());  // a partial read: nothing yet
  s.feed("30\r\a\rz\r" + std::string(200, 'A'));
  auto t = s.next();
  ASSERT_TRUE(t);
  EXPECT_EQ(t->text, "t1230");
  EXPECT_EQ(s.next()->kind, SlcanSplitter::Token::Kind::kBell);
  EXPECT_EQ(s.next()->text, "");  // an acknowledgement
  EXPECT_EQ(s.next()->text, "z");
  EXPECT_FALSE(s.next());
  s.feed("A\r\nt0010\n");
  t = s.next();
  ASSERT_TRUE(t);
  EXPECT_EQ(t->kind, SlcanSplitter::Token::Kind::kOverlong);
  EXPECT_EQ(t->text.size(), kMaxSlcanLine);
  EXPECT_EQ(s.next()->text, "t0010");  // CR LF is one line end
  EXPECT_FALSE(s.next());
}

// A controller's SlcanBus and an adapter's SlcanDeviceBus on the two ends of a pty.
class SlcanPty : public ::testing::Test {
 protected:
  void SetUp() override {
    Result<Pty> pty = open_pty();
    ASSERT_TRUE(pty.has_value()) << pty.error().message;
    path_ = pty->slave_path;
    device_ = std::make_unique<SlcanDeviceBus>(std::move(pty->master), "pty");
    keep_ = std::move(pty->slave);
    Result<std::unique_ptr<SlcanBus>> bus = SlcanBus::open(path_, {});
    ASSERT_TRUE(bus.has_value()) << bus.error().message;
    host_ = std::move(*bus);
    // The adapter sees C, S6, O: the channel is open once it has read them.
    EXPECT_FALSE(device_->receive(0.2)->has_value());
    EXPECT_TRUE(device_->channel_open());
  }
  std::string path_;
  FileDescriptor keep_;
  std::unique_ptr<SlcanDeviceBus> device_;
  std::unique_ptr<SlcanBus> host_;
};

TEST_F(SlcanPty, FramesCrossInBothDirections) {
  const CanFrame a = *make_can_frame(0x01001000, true, {1, 2, 3});
  ASSERT_TRUE(host_->send(a).has_value());
  Result<std::optional<CanFrame>> got = device_->receive(1.0);
  ASSERT_TRUE(got.has_value() && got->has_value());
  EXPECT_EQ(**got, a);
  const CanFrame b = *make_can_frame(0x321, false, {9});
  ASSERT_TRUE(device_->send(b).has_value());
  got = host_->receive(1.0);
  ASSERT_TRUE(got.has_value() && got->has_value());
  EXPECT_EQ(**got, b);
}

TEST_F(SlcanPty, GarbageIsDroppedAndReportedThenTheLineWorksOn) {
  device_->write_garbage("t12\x01\xff\r" + std::string(100, 'Q') + "\r");
  ASSERT_TRUE(device_->send(*make_can_frame(0x100, false, {7})).has_value());
  Result<std::optional<CanFrame>> first = host_->receive(1.0);
  ASSERT_FALSE(first.has_value());
  EXPECT_EQ(first.error().code, ErrorCode::kParse);
  EXPECT_THAT(first.error().message, HasSubstr("garbled line"));
  Result<std::optional<CanFrame>> second = host_->receive(1.0);
  ASSERT_FALSE(second.has_value());
  EXPECT_THAT(second.error().message, HasSubstr("over-long line"));
  Result<std::optional<CanFrame>> third = host_->receive(1.0);
  ASSERT_TRUE(third.has_value() && third->has_value());
  EXPECT_EQ((*third)->id, 0x100U);
  EXPECT_EQ(host_->stats().garbled_lines, 2U);
}

TEST_F(SlcanPty, BusOffIsABusErrorUntilTheChannelIsReopened) {
  device_->enter_bus_off();
  ASSERT_TRUE(host_->send(*make_can_frame(0x100, false, {})).has_value());
  EXPECT_FALSE(device_->receive(0.2)->has_value());  // refused with BEL
  Result<std::optional<CanFrame>> in = host_->receive(1.0);
  ASSERT_FALSE(in.has_value());
  EXPECT_EQ(in.error().code, ErrorCode::kBusError);
  EXPECT_THAT(in.error().message, HasSubstr("BEL"));
  // The adapter answers the recovery's commands on its own thread, as a real one would.
  Result<std::optional<CanFrame>> got = std::optional<CanFrame>();
  std::thread adapter([&] { got = device_->receive(5.0); });
  const Result<void> recovered = host_->recover();
  EXPECT_TRUE(recovered.has_value()) << recovered.error().message;
  EXPECT_TRUE(host_->send(*make_can_frame(0x101, false, {})).has_value());
  adapter.join();
  ASSERT_TRUE(got.has_value() && got->has_value());
  EXPECT_EQ((*got)->id, 0x101U);
}

TEST_F(SlcanPty, AClosedLineIsABusError) {
  device_.reset();
  keep_ = FileDescriptor();
  Result<std::optional<CanFrame>> in = host_->receive(1.0);
  ASSERT_FALSE(in.has_value());
  EXPECT_EQ(in.error().code, ErrorCode::kBusError);
  EXPECT_THAT(in.error().message, HasSubstr("closed"));
}

TEST_F(SlcanPty, AnAdapterThatStopsReadingStallsAWriteInsteadOfHangingIt) {
  const CanFrame f = *make_can_frame(0x1fffffff, true, {1, 2, 3, 4, 5, 6, 7, 8});
  Result<void> sent;
  for (int i = 0; i < 1000000 && sent.has_value(); ++i) sent = host_->send(f);
  ASSERT_FALSE(sent.has_value());
  EXPECT_EQ(sent.error().code, ErrorCode::kBusError);
  EXPECT_THAT(sent.error().message, HasSubstr("write stalled"));
}

TEST(SlcanBus, AMissingTtyIsNamed) {
  Result<std::unique_ptr<SlcanBus>> bus = SlcanBus::open("/dev/no-such-tty", {});
  ASSERT_FALSE(bus.has_value());
  EXPECT_THAT(bus.error().message, HasSubstr("slcan:/dev/no-such-tty: cannot open"));
}

TEST(SocketCanBus, OpensOrSaysWhyNot) {
  // This machine's kernel has no PF_CAN; elsewhere "nosuchcan0" does not exist. Either way the
  // error says what is missing.
  Result<std::unique_ptr<SocketCanBus>> bus = SocketCanBus::open("nosuchcan0");
  ASSERT_FALSE(bus.has_value());
  EXPECT_EQ(bus.error().code, ErrorCode::kBusError);
  EXPECT_THAT(bus.error().message, HasSubstr("socketcan:nosuchcan0: "));
  EXPECT_THAT(bus.error().message,
              ::testing::AnyOf(HasSubstr("this kernel has no CAN support (socket(PF_CAN): "),
                               HasSubstr("no such network interface")));
}

}  // namespace
}  // namespace sewerplan::hal
