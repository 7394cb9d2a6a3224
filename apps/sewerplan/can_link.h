// SPDX-License-Identifier: MIT
// The robot over a CAN bus for `simulate --can` and `simulate --replay`: the bus a spec names
// (slcan:TTY or socketcan:IFACE), or the replay of a candump log, optionally recorded to a
// candump log, with a CanRobot on it that has asked the node for its status.
#pragma once

#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/output_file.h"
#include "sewerplan/core/result.h"
#include "sewerplan/hal/can/can_bus.h"
#include "sewerplan/hal/can/can_robot.h"
#include "sewerplan/hal/can/candump.h"

namespace sewerplan::cli {

struct CanLinkOptions {
  std::string bus;     // "slcan:/dev/ttyUSB0", "socketcan:can0"; empty with replay
  std::string replay;  // a candump log to play back instead of a bus
  std::string log;     // write the traffic here as a candump log
  char bitrate = '6';  // SLCAN S code
};

// Seconds since the epoch, for candump time stamps.
class WallClock final : public Clock {
 public:
  double now_s() const override;
};

class CanLink {
 public:
  // Opens the bus or the log and connects; errors name the bus or the file.
  static Result<std::unique_ptr<CanLink>> open(const CanLinkOptions& options);
  hal::CanRobot& robot() { return *robot_; }
  // "CAN link slcan:/dev/pts/3: 0 retries, 0 timeouts, 0 bad inputs, 0 bus errors".
  void write_summary(std::ostream& out) const;
  // Closes the candump log (--can-log): an error naming it if a frame could not be written.
  Result<void> close_log();

 private:
  CanLink() = default;
  WallClock wall_;
  std::unique_ptr<hal::CanBus> bus_;
  std::optional<LogFile> log_;
  std::optional<hal::RecordingCanBus> recording_;
  std::optional<hal::CanRobot> robot_;
};

}  // namespace sewerplan::cli
