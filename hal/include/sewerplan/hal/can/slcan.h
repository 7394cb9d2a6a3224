// SPDX-License-Identifier: MIT
// SLCAN: CAN over a serial line, the ASCII protocol of Lawicel's CANUSB that most USB-CAN adapters
// speak (CANable, USBtin, ...), and a CanBus (can_bus.h) on each end of such a line.
//
// Every command and frame is a line of ASCII ended by CR: "O" opens the channel, "C" closes it,
// "S0".."S8" set the bitrate (S6: 500 kbit/s), "t1232DEAD" is a standard data frame (id 123, dlc
// 2), "T1F3344553AABBCC" an extended one, "r1232"/"R1F3344552" remote requests. The adapter answers
// a command with CR (or "z"/"Z" CR after a frame) and an error with BEL (0x07). Frames from the
// bus arrive as the same t/T/r/R lines, optionally followed by a 4-digit timestamp.
//
// SlcanBus is the controller's end: it opens a tty (or takes a file descriptor), sets raw mode,
// sends C, Sn, O, and turns lines into frames. Garbage, over-long lines and partial reads never
// throw: a garbled line is dropped and reported once as a kParse error, BEL as kBusError.
// SlcanDeviceBus is the adapter's end, for the simulated node (sim_node.h): it answers the
// commands as an adapter does and can inject line faults. Tests connect the two through a
// pseudo-terminal (open_pty).
//
//   Result<std::unique_ptr<SlcanBus>> bus = SlcanBus::open("/dev/ttyACM0", {});
//   if (!bus.has_value()) { std::cerr << bus.error().message; return; }
//   (*bus)->send(frame);
//   Result<std::optional<CanFrame>> in = (*bus)->receive(0.5);
//
// Thread safety: The SLCAN classes are not thread-safe: one thread uses each line and bus.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/result.h"
#include "sewerplan/hal/can/can_bus.h"
#include "sewerplan/hal/can/can_frame.h"

namespace sewerplan::hal {

// --- The line codec (pure functions, fuzzed) ---------------------------------------------------

// The line for `frame`, with its CR: "t1232DEAD\r".
std::string encode_slcan_frame(const CanFrame& frame);
// A t/T/r/R line without its CR; a 4-hex-digit timestamp after the data is accepted and dropped.
Result<CanFrame> parse_slcan_frame(std::string_view line);

// The longest line an SLCAN peer sends: "T" + 8 + 1 + 16 + a timestamp of 4, with room to spare.
inline constexpr std::size_t kMaxSlcanLine = 64;

// Cuts a byte stream into lines (CR or LF ended; empty lines are acknowledgements), BEL bytes, and
// over-long lines, which are dropped up to their end and reported as garbage.
class SlcanSplitter {
 public:
  struct Token {
    enum class Kind { kLine, kBell, kOverlong };
    Kind kind = Kind::kLine;
    std::string text;  // the line without its terminator; for kOverlong its first bytes
  };
  void feed(std::string_view bytes);
  std::optional<Token> next();

 private:
  std::string pending_;
  std::string line_;
  bool overlong_ = false;
  std::size_t scanned_ = 0;
};

// --- File descriptors and pseudo-terminals ---------------------------------------------------

// Owns a POSIX file descriptor and closes it.
class FileDescriptor {
 public:
  FileDescriptor() = default;
  explicit FileDescriptor(int fd) : fd_(fd) {}
  FileDescriptor(FileDescriptor&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  FileDescriptor& operator=(FileDescriptor&& other) noexcept;
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor();
  int get() const { return fd_; }
  bool valid() const { return fd_ >= 0; }

 private:
  int fd_ = -1;
};

// Puts a tty in raw mode (no echo, no line editing, no CR/LF translation, 8 bits).
Result<void> make_raw_tty(int fd, const std::string& name);

// A pseudo-terminal in raw mode on both ends: the simulated node serves the master, the controller
// opens slave_path. `slave` keeps the line open while no controller is connected.
struct Pty {
  FileDescriptor master;
  FileDescriptor slave;
  std::string slave_path;  // "/dev/pts/3"
};
Result<Pty> open_pty();

// --- The two ends of a line ------------------------------------------------------------------

struct SlcanOptions {
  char bitrate = '6';            // the S command's digit: 0 = 10 kbit/s ... 6 = 500k, 8 = 1M
  const Clock* clock = nullptr;  // for receive()'s timeout; empty: a SteadyClock
};

// What went wrong on a line so far.
struct SlcanStats {
  std::size_t frames_in = 0;
  std::size_t frames_out = 0;
  std::size_t garbled_lines = 0;  // dropped: not a frame, or over-long
  std::size_t bells = 0;          // error replies
};

// Reads a file descriptor into a splitter, with a timeout; shared by both ends.
class SlcanLine {
 public:
  SlcanLine(FileDescriptor fd, std::string name, const Clock* clock);
  Result<void> write(std::string_view bytes);
  // The next token within timeout_s; empty on timeout; kBusError when the line closed.
  Result<std::optional<SlcanSplitter::Token>> read(double timeout_s);
  const std::string& name() const { return name_; }

 private:
  FileDescriptor fd_;
  std::string name_;
  SteadyClock steady_;
  const Clock* clock_;
  SlcanSplitter splitter_;
};

// The controller's end: talks to an adapter.
class SlcanBus final : public CanBus {
 public:
  // Opens a tty, sets it raw and opens the CAN channel. Errors name the path.
  static Result<std::unique_ptr<SlcanBus>> open(const std::string& tty_path, SlcanOptions options);
  // Takes over an open descriptor (already raw) and opens the CAN channel.
  static Result<std::unique_ptr<SlcanBus>> adopt(FileDescriptor fd, std::string name,
                                                 SlcanOptions options);
  ~SlcanBus() override;

  Result<void> send(const CanFrame& frame) override;
  Result<std::optional<CanFrame>> receive(double timeout_s) override;
  // Closes and reopens the channel (C, Sn, O): how an adapter leaves bus-off.
  Result<void> recover() override;
  std::string name() const override { return "slcan:" + line_.name(); }
  const SlcanStats& stats() const { return stats_; }

 private:
  SlcanBus(FileDescriptor fd, std::string name, SlcanOptions options);
  Result<void> open_channel();

  SlcanLine line_;
  SlcanOptions options_;
  SlcanStats stats_;
};

// The adapter's end, for a simulated node: answers O/C/S/V/N/F as an adapter does (CR, or BEL
// for an unknown command or a frame while the channel is closed or bus-off) and hands the
// controller's frames to the node.
class SlcanDeviceBus final : public CanBus, public FaultableLine {
 public:
  SlcanDeviceBus(FileDescriptor fd, std::string name, const Clock* clock = nullptr);

  Result<void> send(const CanFrame& frame) override;
  Result<std::optional<CanFrame>> receive(double timeout_s) override;
  std::string name() const override { return "slcan-device:" + line_.name(); }
  void write_garbage(std::string_view bytes) override;
  void enter_bus_off() override { bus_off_ = true; }

  bool channel_open() const { return open_; }
  const SlcanStats& stats() const { return stats_; }

 private:
  // Answers one command line; the frame it carried, if any.
  std::optional<CanFrame> handle(const SlcanSplitter::Token& token);

  SlcanLine line_;
  bool open_ = false;
  bool bus_off_ = false;
  SlcanStats stats_;
};

}  // namespace sewerplan::hal
