// SPDX-License-Identifier: MIT
// CanBus: a connection to a CAN bus that sends and receives frames (can_frame.h).
//
// The CAN robot (can_robot.h) and the simulated controller node (sim_node.h) talk through this
// interface only, so they run on any transport: a serial-line SLCAN adapter (slcan.h), a Linux
// SocketCAN interface (socketcan.h), the in-memory pair below (unit tests), a recording decorator
// or a replay of a candump log (candump.h). Failures are Results: kBusError when the bus or the
// adapter failed (bus-off, a closed line, no CAN support), kParse for garbled input that was
// dropped (the bus stays usable). receive() waits at most its timeout and never blocks longer.
//
//   auto [a, b] = make_memory_can_pair();
//   a->send(*make_can_frame(0x123, false, {1, 2}));
//   Result<std::optional<CanFrame>> f = b->receive(0.1);  // the frame, or empty after 0.1 s
//
// Thread safety: A CanBus is not thread-safe unless it says so (MemoryCanBus is: each end may live
// on its own thread).
#pragma once

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

#include "sewerplan/core/result.h"
#include "sewerplan/hal/can/can_frame.h"

namespace sewerplan::hal {

class CanBus {
 public:
  virtual ~CanBus() = default;
  // Queues one frame for transmission.
  virtual Result<void> send(const CanFrame& frame) = 0;
  // The next frame; empty when none arrived within `timeout_s` (>= 0) of wall time.
  virtual Result<std::optional<CanFrame>> receive(double timeout_s) = 0;
  // Restarts the connection after a bus error (for SLCAN: closes and reopens the channel).
  virtual Result<void> recover() { return {}; }
  // "slcan:/dev/pts/3", "socketcan:can0", ...: for messages.
  virtual std::string name() const = 0;
};

// The line under a simulated node's bus, for fault injection (sim_node.h): what a real bus can do
// to the controller that a well-behaved node cannot.
class FaultableLine {
 public:
  virtual ~FaultableLine() = default;
  // Puts bytes on the line that are no frame (noise, a confused adapter).
  virtual void write_garbage(std::string_view bytes) = 0;
  // The node's side goes bus-off: every frame from the controller is refused with an error until
  // the controller recovers the bus (CanBus::recover).
  virtual void enter_bus_off() = 0;
};

// One end of an in-memory bus with two members; thread-safe, for tests. Frames sent at one end are
// received at the other, in order.
class MemoryCanBus final : public CanBus, public FaultableLine {
 public:
  Result<void> send(const CanFrame& frame) override;
  Result<std::optional<CanFrame>> receive(double timeout_s) override;
  Result<void> recover() override;
  std::string name() const override { return name_; }
  // Garbage reaches the other end as one kParse error from receive().
  void write_garbage(std::string_view bytes) override;
  void enter_bus_off() override;

 private:
  friend std::pair<std::unique_ptr<MemoryCanBus>, std::unique_ptr<MemoryCanBus>>
  make_memory_can_pair();
  struct Shared;
  using Item = std::variant<CanFrame, Error>;
  MemoryCanBus(std::shared_ptr<Shared> shared, int side, std::string name);

  // Shared by the two ends, each of which may live on its own thread.
  std::shared_ptr<Shared> shared_;
  int side_;
  std::string name_;
};

std::pair<std::unique_ptr<MemoryCanBus>, std::unique_ptr<MemoryCanBus>> make_memory_can_pair();

}  // namespace sewerplan::hal
