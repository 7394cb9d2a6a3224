// SPDX-License-Identifier: MIT
// SocketCanBus: a CanBus (can_bus.h) on a Linux SocketCAN interface ("can0", "vcan0").
//
// Opens a raw CAN socket (PF_CAN, SOCK_RAW, CAN_RAW) bound to one interface, with error frames
// enabled so that a bus-off reaches the controller as a kBusError. Kernels without CAN support
// (no PF_CAN) fail at open with a clear kBusError; so does an unknown interface. Reads wait with
// poll(), at most the timeout asked.
//
//   Result<std::unique_ptr<SocketCanBus>> bus = SocketCanBus::open("can0");
//   // "socketcan:can0: this kernel has no CAN support (socket(PF_CAN): Address family not
//   //  supported by protocol)" on a kernel without CAN
//
// Thread safety: A SocketCanBus is not thread-safe: one thread uses it.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "sewerplan/core/result.h"
#include "sewerplan/hal/can/can_bus.h"
#include "sewerplan/hal/can/slcan.h"

namespace sewerplan::hal {

class SocketCanBus final : public CanBus {
 public:
  static Result<std::unique_ptr<SocketCanBus>> open(const std::string& interface);

  Result<void> send(const CanFrame& frame) override;
  Result<std::optional<CanFrame>> receive(double timeout_s) override;
  // The kernel restarts a bus-off controller itself (ip link set can0 type can restart-ms N).
  Result<void> recover() override { return {}; }
  std::string name() const override { return "socketcan:" + interface_; }

 private:
  SocketCanBus(FileDescriptor socket, std::string interface);
  FileDescriptor socket_;
  std::string interface_;
};

}  // namespace sewerplan::hal
