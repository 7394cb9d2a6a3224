// SPDX-License-Identifier: MIT
#include "sewerplan/hal/can/socketcan.h"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "can_text.h"
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

namespace sewerplan::hal {
namespace {

Error socket_error(const std::string& name, const std::string& what, int error) {
  return Error{ErrorCode::kBusError, name + ": " + what + ": " + std::strerror(error)};
}

}  // namespace

SocketCanBus::SocketCanBus(FileDescriptor socket, std::string interface)
    : socket_(std::move(socket)), interface_(std::move(interface)) {}

Result<std::unique_ptr<SocketCanBus>> SocketCanBus::open(const std::string& interface) {
  const std::string name = "socketcan:" + interface;
  if (interface.empty() || interface.size() >= IFNAMSIZ) {
    return Error{ErrorCode::kInvalidArgument, name + ": an interface name has 1 to " +
                                                  std::to_string(IFNAMSIZ - 1) + " characters"};
  }
  FileDescriptor s(::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC | SOCK_NONBLOCK, CAN_RAW));
  if (!s.valid()) {
    const int error = errno;
    if (error == EAFNOSUPPORT || error == EPROTONOSUPPORT) {
      return Error{
          ErrorCode::kBusError,
          name + ": this kernel has no CAN support (socket(PF_CAN): " + std::strerror(error) + ")"};
    }
    return socket_error(name, "socket(PF_CAN)", error);
  }
  const unsigned index = ::if_nametoindex(interface.c_str());
  if (index == 0) {
    return Error{ErrorCode::kBusError, name +
                                           ": no such network interface (is it up? ip link set " +
                                           interface + " up type can bitrate 500000)"};
  }
  const can_err_mask_t errors = CAN_ERR_BUSOFF | CAN_ERR_CRTL | CAN_ERR_RESTARTED;
  if (::setsockopt(s.get(), SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &errors, sizeof(errors)) != 0) {
    return socket_error(name, "cannot enable error frames", errno);
  }
  sockaddr_can address{};
  address.can_family = AF_CAN;
  address.can_ifindex = static_cast<int>(index);
  if (::bind(s.get(), reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {  // NOLINT
    return socket_error(name, "cannot bind to the interface", errno);
  }
  return std::unique_ptr<SocketCanBus>(new SocketCanBus(std::move(s), interface));  // NOLINT
}

Result<void> SocketCanBus::send(const CanFrame& frame) {
  can_frame raw{};
  raw.can_id = frame.id;
  if (frame.extended) raw.can_id |= CAN_EFF_FLAG;
  if (frame.remote) raw.can_id |= CAN_RTR_FLAG;
  raw.can_dlc = frame.dlc;
  std::copy(frame.data.begin(), frame.data.end(), raw.data);
  for (;;) {
    const ssize_t n = ::write(socket_.get(), &raw, sizeof(raw));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == ENOBUFS || errno == EAGAIN)) {
      return socket_error(name(), "transmit queue full", errno);
    }
    if (n != static_cast<ssize_t>(sizeof(raw))) return socket_error(name(), "write failed", errno);
    return {};
  }
}

Result<std::optional<CanFrame>> SocketCanBus::receive(double timeout_s) {
  pollfd p{socket_.get(), POLLIN, 0};
  const int ms = static_cast<int>(std::clamp(timeout_s, 0.0, 3600.0) * 1000 + 0.5);
  int ready = 0;
  do {
    ready = ::poll(&p, 1, ms);
  } while (ready < 0 && errno == EINTR);
  if (ready < 0) return socket_error(name(), "poll failed", errno);
  if (ready == 0) return std::optional<CanFrame>();
  can_frame raw{};
  const ssize_t n = ::read(socket_.get(), &raw, sizeof(raw));
  if (n < 0 && (errno == EAGAIN || errno == EINTR)) return std::optional<CanFrame>();
  if (n != static_cast<ssize_t>(sizeof(raw))) return socket_error(name(), "read failed", errno);
  if ((raw.can_id & CAN_ERR_FLAG) != 0) {
    const bool bus_off = (raw.can_id & CAN_ERR_BUSOFF) != 0;
    return Error{ErrorCode::kBusError,
                 name() + (bus_off ? ": bus-off"
                                   : ": controller error frame 0x" +
                                         hex_text(raw.can_id & CAN_ERR_MASK, 8))};
  }
  CanFrame frame;
  frame.extended = (raw.can_id & CAN_EFF_FLAG) != 0;
  frame.remote = (raw.can_id & CAN_RTR_FLAG) != 0;
  frame.id = raw.can_id & (frame.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
  frame.dlc = std::min<std::uint8_t>(raw.can_dlc, 8);
  if (!frame.remote) std::copy(raw.data, raw.data + frame.dlc, frame.data.begin());
  return std::optional<CanFrame>(frame);
}

}  // namespace sewerplan::hal
