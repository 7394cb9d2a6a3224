// SPDX-License-Identifier: MIT
// A simulated CAN node (hal/can/sim_node.h) serving a SimRobot on its own thread, with the
// controller's end of the bus: over SLCAN through a pseudo-terminal, or an in-memory pair.
// Header-only: the test support library does not link hal.
#pragma once

#include <atomic>
#include <memory>
#include <thread>
#include <utility>

#include <gtest/gtest.h>

#include "sewerplan/hal/can/can_bus.h"
#include "sewerplan/hal/can/sim_node.h"
#include "sewerplan/hal/can/slcan.h"
#include "sewerplan/hal/sim_robot.h"

namespace sewerplan::testing {

enum class Transport { kSlcanPty, kMemory };

class CanNodeThread {
 public:
  // `map` must outlive this; it is the robot's world (a true world, hal/world_errors.h, with the
  // sensing of `sim_options`, or the map itself).
  CanNodeThread(const SewerMap& map, const RobotProfile& profile, hal::SimPose start,
                hal::FaultScenario faults, hal::BusFaults bus_faults, Transport transport,
                double heartbeat_s = 0.5, hal::SimOptions sim_options = {})
      : robot_(map, profile, start, std::move(faults), std::move(sim_options)) {
    hal::SimNodeOptions options{.heartbeat_s = heartbeat_s, .faults = std::move(bus_faults)};
    if (transport == Transport::kSlcanPty) {
      Result<hal::Pty> pty = hal::open_pty();
      if (!pty.has_value()) {
        ADD_FAILURE() << pty.error().message;
        return;
      }
      auto device = std::make_unique<hal::SlcanDeviceBus>(std::move(pty->master), pty->slave_path);
      keep_open_ = std::move(pty->slave);
      Result<std::unique_ptr<hal::SlcanBus>> host = hal::SlcanBus::open(pty->slave_path, {});
      if (!host.has_value()) {
        ADD_FAILURE() << host.error().message;
        return;
      }
      node_ = std::make_unique<hal::SimNode>(*device, robot_, options, device.get());
      node_bus_ = std::move(device);
      controller_bus_ = std::move(*host);
    } else {
      auto [a, b] = hal::make_memory_can_pair();
      node_ = std::make_unique<hal::SimNode>(*b, robot_, options, b.get());
      node_bus_ = std::move(b);
      controller_bus_ = std::move(a);
    }
    thread_ = std::thread([this] { static_cast<void>(node_->serve(stop_)); });
  }
  CanNodeThread(const CanNodeThread&) = delete;
  CanNodeThread& operator=(const CanNodeThread&) = delete;
  ~CanNodeThread() { stop(); }

  // Stops the node; afterwards robot() and node() may be read.
  void stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  bool ok() const { return controller_bus_ != nullptr; }
  hal::CanBus& controller_bus() { return *controller_bus_; }
  const hal::SimRobot& robot() const { return robot_; }
  const hal::SimNode& node() const { return *node_; }

 private:
  hal::SimRobot robot_;
  hal::FileDescriptor keep_open_;
  std::unique_ptr<hal::CanBus> node_bus_;
  std::unique_ptr<hal::CanBus> controller_bus_;
  std::unique_ptr<hal::SimNode> node_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace sewerplan::testing
