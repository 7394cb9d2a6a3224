// SPDX-License-Identifier: MIT
// CanRobot: the robot behind hal::Robot (robot.h) reached over a CAN bus with the job protocol
// (job_protocol.h, docs/can-protocol.md), so that the executor runs the same jobs on the
// simulated robot or on a real one.
//
// execute() sends the job, waits for its acknowledgement (a timeout and a bounded number of
// attempts), follows progress, and returns the node's report: progress, duration and energy are
// the node's, so a run over the bus is as deterministic as the node behind it. Wall time, from
// the injected Clock, is used only for timeouts. Anything that goes wrong on the bus - no answer,
// a lost link, bus-off, garbled or malformed frames beyond what a retry repairs - ends the job as
// a MALFUNCTION whose reason says what happened, after an emergency stop; nothing waits without a
// deadline and nothing throws. reboot() recovers the bus and asks the node to restart, which the
// executor does after a malfunction; activate_beacon() asks the node to switch the beacon on.
// emergency_stop() only raises a flag: the thread in execute() sees it within a heartbeat period
// (0.5 s), sends EMERGENCY_STOP (reason: the controller), and ends the job as a MALFUNCTION
// "emergency stop" with the progress last reported; a job asked for after it is not sent, until a
// reboot() clears the stop (the node latches it likewise). An emergency_stop() during a reboot ends
// its wait for the node's answer likewise (within a heartbeat period, not after every attempt's
// timeout): the reboot fails with kCancelled, and the stop holds until the next reboot.
//
//   Result<std::unique_ptr<SlcanBus>> bus = SlcanBus::open("/dev/ttyUSB0", {});
//   CanRobot robot(**bus, {});
//   if (Result<void> up = robot.connect(); !up.has_value()) ...  // no node answers
//   JobReport r = robot.execute(DriveForward{.speed_mps = 0.3, .distance_m = 12});
//
// Thread safety: A CanRobot is not thread-safe: one thread drives it, as any Robot;
// emergency_stop() may be called from any thread.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "sewerplan/core/clock.h"
#include "sewerplan/hal/can/can_bus.h"
#include "sewerplan/hal/can/job_protocol.h"
#include "sewerplan/hal/robot.h"

namespace sewerplan::hal {

struct CanRobotOptions {
  double ack_timeout_s = 0.5;     // for an acknowledgement, a status or a reboot result
  double link_timeout_s = 2.0;    // the longest silence from the node while a job runs
  double job_timeout_s = 3600.0;  // the longest job
  int attempts = 3;               // sends of a message unanswered before giving up (>= 1)
  // Further sends of a message whose answer arrives damaged (some of its frames heard, not all):
  // the node is there, and each copy it sends again fills the gaps the last one left.
  int max_resends = 16;
  double heartbeat_s = 0.5;        // the controller's heartbeat period while it waits
  std::size_t max_bad_input = 16;  // garbled or malformed frames tolerated in one exchange
  const Clock* clock = nullptr;    // for timeouts; empty: a SteadyClock
};

// What the link has seen, for the report and for tests.
struct CanLinkStats {
  std::size_t retries = 0;          // messages sent again after a timeout or a rejection
  std::size_t timeouts = 0;         // waits that ended without an answer
  std::size_t bad_input = 0;        // garbled lines and malformed messages dropped
  std::size_t stale_messages = 0;   // answers to an older exchange, ignored
  std::size_t bus_errors = 0;       // errors reported by the bus (bus-off, BEL, closed line)
  std::size_t emergency_stops = 0;  // sent after a failed exchange
  std::size_t link_failures = 0;    // jobs ended as a malfunction by the link
};

class CanRobot final : public Robot {
 public:
  // `bus` must outlive the robot.
  explicit CanRobot(CanBus& bus, CanRobotOptions options = {});

  // Asks the node for its status; an error (kCanTimeout, kBusError) when it does not answer.
  Result<void> connect();

  JobReport execute(const Job& job) override;
  // The status that came with the node's last answer.
  RobotStatus status() const override { return status_; }
  // Recovers the bus, restarts the node and, when the last job's result was lost, asks the node
  // for it (RESULT_REQUEST) before anything else is sent: recovered_report() then has it.
  Result<void> reboot() override;
  std::optional<JobReport> recovered_report() override;
  // kConfirmed when the node's STATUS says the beacon is on; kUnconfirmed when the request went
  // out and no answer (or one without the beacon) came; kNotSent when the bus refused it (a send
  // failed, or the bus reported an error: bus-off, a closed line).
  BeaconState activate_beacon() override;
  void emergency_stop() override { stop_requested_.store(true); }

  const CanLinkStats& stats() const { return stats_; }

 private:
  enum class Verdict { kTake, kAlive, kIgnore };
  // Waits for a message that `judge` takes; kAlive answers restart the window of `timeout_s`.
  // Empty with `problem` set when the window passes, and with `bus_failed` set too when the bus
  // fails or bad input piles up beyond max_bad_input (no retry helps then), or when `stoppable`
  // and an emergency stop is requested.
  std::optional<Message> await(double timeout_s,
                               const std::function<Verdict(const Message&)>& judge,
                               std::string& problem, bool& bus_failed, bool stoppable = false);
  Result<void> send(const Message& message);
  // Sends `request` until `judge` takes an answer: at most options_.attempts sends that nothing of
  // an answer came back to, and options_.max_resends more whose answer arrived damaged.
  std::optional<Message> exchange(const Request& request, double timeout_s,
                                  const std::function<Verdict(const Message&)>& judge,
                                  std::string& problem, bool stoppable = false);
  // Sends a request of `kind` with a new sequence number and takes the first `Reply` to it.
  // `stoppable`: emergency_stop() ends the wait (as it ends a job's).
  template <class Reply>
  std::optional<Reply> ask(RequestKind kind, double timeout_s, std::string& problem,
                           bool stoppable = false);
  JobReport link_failure(const std::string& what, double progress_m);
  // Sends EMERGENCY_STOP for emergency_stop() and ends the job.
  JobReport stopped(double progress_m);
  void heartbeat_if_due();
  std::uint8_t next_seq() { return ++seq_; }
  // After a reboot: what became of the job whose result was lost (recovered_), from the node.
  Result<void> settle_lost_job();

  CanBus& bus_;
  CanRobotOptions options_;
  SteadyClock steady_;
  const Clock* clock_;
  MessageDecoder decoder_;
  RobotStatus status_;
  CanLinkStats stats_;
  std::uint8_t seq_ = 0;
  std::uint8_t heartbeat_counter_ = 0;
  std::string last_bad_input_;  // in the current job, for its failure's reason
  double last_heartbeat_s_ = -1e300;
  std::atomic<bool> stop_requested_{false};  // emergency_stop(), until reboot()
  // The exchange a wait belongs to: a frame of a node message with this sequence number counts as
  // its answer heard (heard_), though perhaps not whole; a malformed one ends the wait at once,
  // so that the request goes again without waiting for the timeout.
  std::optional<std::uint8_t> awaited_seq_;
  bool heard_ = false;
  // The sequence number of a job sent whose result never came: settled by the next reboot().
  std::optional<std::uint8_t> lost_job_;
  std::optional<JobReport> recovered_;
  std::size_t messages_sent_ = 0;  // whole, by send()
};

}  // namespace sewerplan::hal
