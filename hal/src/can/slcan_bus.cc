// SPDX-License-Identifier: MIT
// The two ends of an SLCAN line over a file descriptor, and pseudo-terminals to join them.
#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "sewerplan/hal/can/slcan.h"

#include "can_text.h"
#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

namespace sewerplan::hal {
namespace {

std::string errno_text(int error) { return std::strerror(error); }

Error io_error(const std::string& name, const std::string& what, int error) {
  return Error{ErrorCode::kBusError, name + ": " + what + ": " + errno_text(error)};
}

}  // namespace

FileDescriptor& FileDescriptor::operator=(FileDescriptor&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

FileDescriptor::~FileDescriptor() {
  if (fd_ >= 0) ::close(fd_);
}

Result<void> make_raw_tty(int fd, const std::string& name) {
  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) return io_error(name, "not a terminal (tcgetattr)", errno);
  ::cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  ::cfsetispeed(&tio, B115200);
  ::cfsetospeed(&tio, B115200);
  if (::tcsetattr(fd, TCSANOW, &tio) != 0) return io_error(name, "cannot set raw mode", errno);
  return {};
}

Result<Pty> open_pty() {
  FileDescriptor master(::posix_openpt(O_RDWR | O_NOCTTY));
  if (!master.valid()) return io_error("pty", "posix_openpt", errno);
  if (::grantpt(master.get()) != 0 || ::unlockpt(master.get()) != 0) {
    return io_error("pty", "grantpt/unlockpt", errno);
  }
  std::array<char, 128> path{};
  if (::ptsname_r(master.get(), path.data(), path.size()) != 0) {
    return io_error("pty", "ptsname", errno);
  }
  Pty pty;
  pty.slave_path = path.data();
  pty.slave = FileDescriptor(::open(pty.slave_path.c_str(), O_RDWR | O_NOCTTY));
  if (!pty.slave.valid()) return io_error(pty.slave_path, "cannot open", errno);
  if (Result<void> r = make_raw_tty(pty.slave.get(), pty.slave_path); !r.has_value())
    return r.error();
  if (Result<void> r = make_raw_tty(master.get(), "pty master"); !r.has_value()) return r.error();
  pty.master = std::move(master);
  return pty;
}

// --- SlcanLine ---------------------------------------------------------------------------------

SlcanLine::SlcanLine(FileDescriptor fd, std::string name, const Clock* clock)
    : fd_(std::move(fd)), name_(std::move(name)), clock_(clock != nullptr ? clock : &steady_) {
  // Non-blocking, so that a peer that stops reading stalls a write for at most a second instead
  // of for ever.
  const int flags = ::fcntl(fd_.get(), F_GETFL);
  if (flags >= 0) static_cast<void>(::fcntl(fd_.get(), F_SETFL, flags | O_NONBLOCK));
}

Result<void> SlcanLine::write(std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd_.get(), bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      pollfd p{fd_.get(), POLLOUT, 0};
      if (::poll(&p, 1, 1000) <= 0) return Error{ErrorCode::kBusError, name_ + ": write stalled"};
      continue;
    }
    if (n <= 0) return io_error(name_, "write failed", errno);
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
  return {};
}

Result<std::optional<SlcanSplitter::Token>> SlcanLine::read(double timeout_s) {
  const double deadline_s = clock_->now_s() + std::max(0.0, timeout_s);
  for (;;) {
    if (std::optional<SlcanSplitter::Token> token = splitter_.next()) return token;
    const double left_s = deadline_s - clock_->now_s();
    const int left_ms = left_s <= 0 ? 0 : static_cast<int>(std::min(left_s, 3600.0) * 1000 + 1);
    pollfd p{fd_.get(), POLLIN, 0};
    const int ready = ::poll(&p, 1, left_ms);
    if (ready < 0 && errno == EINTR) continue;
    if (ready < 0) return io_error(name_, "poll failed", errno);
    if (ready == 0) return std::optional<SlcanSplitter::Token>();
    std::array<char, 512> buffer{};
    const ssize_t n = ::read(fd_.get(), buffer.data(), buffer.size());
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    // A pty reads EIO once its other end is closed.
    if (n == 0 || (n < 0 && errno == EIO)) {
      return Error{ErrorCode::kBusError, name_ + ": the line was closed at the other end"};
    }
    if (n < 0) return io_error(name_, "read failed", errno);
    splitter_.feed(std::string_view(buffer.data(), static_cast<std::size_t>(n)));
  }
}

// --- SlcanBus ----------------------------------------------------------------------------------

SlcanBus::SlcanBus(FileDescriptor fd, std::string name, SlcanOptions options)
    : line_(std::move(fd), std::move(name), options.clock), options_(options) {}

Result<std::unique_ptr<SlcanBus>> SlcanBus::open(const std::string& tty_path,
                                                 SlcanOptions options) {
  FileDescriptor fd(::open(tty_path.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC));
  if (!fd.valid()) return io_error("slcan:" + tty_path, "cannot open", errno);
  if (Result<void> raw = make_raw_tty(fd.get(), "slcan:" + tty_path); !raw.has_value()) {
    return raw.error();
  }
  return adopt(std::move(fd), tty_path, options);
}

Result<std::unique_ptr<SlcanBus>> SlcanBus::adopt(FileDescriptor fd, std::string name,
                                                  SlcanOptions options) {
  if (options.bitrate < '0' || options.bitrate > '8') {
    return Error{ErrorCode::kInvalidArgument,
                 "slcan:" + name + ": the bitrate code must be 0..8, not '" +
                     printable(std::string_view(&options.bitrate, 1)) + "'"};
  }
  std::unique_ptr<SlcanBus> bus(new SlcanBus(std::move(fd), std::move(name), options));  // NOLINT
  if (Result<void> opened = bus->open_channel(); !opened.has_value()) return opened.error();
  return bus;
}

SlcanBus::~SlcanBus() { static_cast<void>(line_.write("C\r")); }

Result<void> SlcanBus::open_channel() {
  // Close first: an adapter left open by an earlier program refuses S with BEL.
  return line_.write(std::string("C\rS") + options_.bitrate + "\rO\r");
}

Result<void> SlcanBus::recover() {
  // Close, ask for the version as a marker, and drop everything the adapter sent before the
  // version (error replies to frames refused while bus-off, stale frames): what came before the
  // reset means nothing now.
  if (Result<void> closed = line_.write("C\rV\r"); !closed.has_value()) return closed;
  for (int tokens = 0; tokens < 10000; ++tokens) {
    Result<std::optional<SlcanSplitter::Token>> token = line_.read(1.0);
    if (!token.has_value()) return token.error();
    if (!token->has_value()) {
      return Error{ErrorCode::kBusError, name() + ": the adapter did not answer V within 1 s"};
    }
    const SlcanSplitter::Token& t = **token;
    if (t.kind == SlcanSplitter::Token::Kind::kLine && !t.text.empty() && t.text[0] == 'V') break;
  }
  return open_channel();
}

Result<void> SlcanBus::send(const CanFrame& frame) {
  Result<void> written = line_.write(encode_slcan_frame(frame));
  if (written.has_value()) ++stats_.frames_out;
  return written;
}

Result<std::optional<CanFrame>> SlcanBus::receive(double timeout_s) {
  for (;;) {
    Result<std::optional<SlcanSplitter::Token>> token = line_.read(timeout_s);
    if (!token.has_value()) return token.error();
    if (!token->has_value()) return std::optional<CanFrame>();
    const SlcanSplitter::Token& t = **token;
    switch (t.kind) {
      case SlcanSplitter::Token::Kind::kBell:
        ++stats_.bells;
        return Error{ErrorCode::kBusError,
                     name() + ": the adapter reported an error (BEL): bus-off or a refused frame"};
      case SlcanSplitter::Token::Kind::kOverlong:
        ++stats_.garbled_lines;
        return Error{ErrorCode::kParse,
                     name() + ": dropped an over-long line '" + printable(t.text) + "'"};
      case SlcanSplitter::Token::Kind::kLine:
        break;
    }
    // Acknowledgements of commands and frames: CR, "z", "Z"; version and status replies.
    if (t.text.empty() || t.text == "z" || t.text == "Z" || t.text[0] == 'V' || t.text[0] == 'v' ||
        t.text[0] == 'N' || t.text[0] == 'F') {
      continue;
    }
    Result<CanFrame> frame = parse_slcan_frame(t.text);
    if (!frame.has_value()) {
      ++stats_.garbled_lines;
      return Error{ErrorCode::kParse,
                   name() + ": dropped a garbled line: " + frame.error().message};
    }
    ++stats_.frames_in;
    return std::optional<CanFrame>(*frame);
  }
}

// --- SlcanDeviceBus ----------------------------------------------------------------------------

SlcanDeviceBus::SlcanDeviceBus(FileDescriptor fd, std::string name, const Clock* clock)
    : line_(std::move(fd), std::move(name), clock) {}

Result<void> SlcanDeviceBus::send(const CanFrame& frame) {
  if (!open_ || bus_off_) {
    return Error{ErrorCode::kBusError, name() + (bus_off_ ? ": bus-off" : ": channel closed")};
  }
  Result<void> written = line_.write(encode_slcan_frame(frame));
  if (written.has_value()) ++stats_.frames_out;
  return written;
}

void SlcanDeviceBus::write_garbage(std::string_view bytes) {
  static_cast<void>(line_.write(bytes));
}

Result<std::optional<CanFrame>> SlcanDeviceBus::receive(double timeout_s) {
  for (;;) {
    Result<std::optional<SlcanSplitter::Token>> token = line_.read(timeout_s);
    if (!token.has_value()) return token.error();
    if (!token->has_value()) return std::optional<CanFrame>();
    if (std::optional<CanFrame> frame = handle(**token)) return frame;
  }
}

std::optional<CanFrame> SlcanDeviceBus::handle(const SlcanSplitter::Token& token) {
  const auto reply = [&](std::string_view text) { static_cast<void>(line_.write(text)); };
  if (token.kind != SlcanSplitter::Token::Kind::kLine) {
    ++stats_.garbled_lines;
    reply("\a");
    return std::nullopt;
  }
  const std::string& line = token.text;
  if (line.empty()) return std::nullopt;
  switch (line[0]) {
    case 'O':
      open_ = true;
      reply("\r");
      return std::nullopt;
    case 'C':
      // Closing resets the controller chip: the way out of bus-off.
      open_ = false;
      bus_off_ = false;
      reply("\r");
      return std::nullopt;
    case 'S':
    case 's':
      reply(open_ ? "\a" : "\r");
      return std::nullopt;
    case 'V':
      reply("V1013\r");
      return std::nullopt;
    case 'N':
      reply("NSIM0\r");
      return std::nullopt;
    case 'F':
      reply(bus_off_ ? "F20\r" : "F00\r");
      return std::nullopt;
    default:
      break;
  }
  Result<CanFrame> frame = parse_slcan_frame(line);
  if (!frame.has_value()) {
    ++stats_.garbled_lines;
    reply("\a");
    return std::nullopt;
  }
  if (!open_ || bus_off_) {
    ++stats_.bells;
    reply("\a");
    return std::nullopt;
  }
  ++stats_.frames_in;
  return *frame;
}

}  // namespace sewerplan::hal
