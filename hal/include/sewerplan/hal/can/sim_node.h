// SPDX-License-Identifier: MIT
// SimNode: the microcontroller side of the job protocol (job_protocol.h), simulated: it serves a
// SimRobot (sim_robot.h) on any CanBus, and can make the bus misbehave.
//
// The node answers the controller (can_robot.h) as docs/can-protocol.md says: it acknowledges a
// job, runs it on the simulated robot, sends progress and the result with the robot's status,
// answers status, result, reboot and beacon requests, latches an emergency stop until a reboot,
// and sends heartbeats. A job or reboot sent again with the same sequence number is answered from
// memory, not run twice; the answers of the last kKeptJobs jobs are kept (over a reboot too), so a
// RESULT_REQUEST for any of them is answered, and one for a job never run gets ACK kUnknown.
// BusFaults inject what a real bus does: lost frames (listed, or at a rate drawn from a seed),
// garbage on the line, silence (requests ignored), bus-off, a late acknowledgement. Faults are
// counted in protocol frames and requests, not in time, so a faulty run is as repeatable as a clean
// one. The node runs on its own thread in tests and in `sewerplan sim-node`.
//
//   SimRobot robot(map, profile, start, faults);
//   Pty pty = *open_pty();
//   SlcanDeviceBus line(std::move(pty.master), pty.slave_path);
//   SimNode node(line, robot, {.faults = *parse_bus_faults("drop=4")}, &line);
//   std::atomic<bool> stop{false};
//   std::thread t([&] { static_cast<void>(node.serve(stop)); });
//
// Thread safety: A SimNode is not thread-safe: it serves on one thread; only `stop` is set from
// another.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/rng.h"
#include "sewerplan/hal/can/can_bus.h"
#include "sewerplan/hal/can/job_protocol.h"
#include "sewerplan/hal/sim_robot.h"

namespace sewerplan::hal {

// Requests are the controller's messages other than heartbeats, counted from 0 as they arrive;
// node frames are the frames the node sends other than heartbeats, counted from 0.
struct Silence {
  std::uint64_t from_request = 0;
  std::uint64_t requests = 1;  // how many requests in a row the node ignores
  friend bool operator==(const Silence&, const Silence&) = default;
};
// The node holds job J's answers back for delay_s (from the node's Clock) while it goes on
// serving: heartbeats (busy), other requests, the adapter's commands. The job runs when the delay
// has passed, unless an emergency stop, a reboot or a newer job comes first.
struct LateAck {
  std::uint64_t job = 0;  // the job (from 0, counting jobs run) whose acknowledgement is late
  double delay_s = 1.0;   // wall time
  friend bool operator==(const LateAck&, const LateAck&) = default;
};

struct BusFaults {
  std::uint64_t seed = 0;
  double drop_rate = 0;                       // each node frame is lost with this probability
  std::vector<std::uint64_t> drop_frames;     // node frames that are lost
  std::vector<std::uint64_t> garbage_before;  // garbage goes on the line before these node frames
  std::optional<Silence> silence;
  std::optional<std::uint64_t> bus_off_at;  // the request at which the node's side goes bus-off
  std::optional<LateAck> late_ack;
  // The answers after the acknowledgement (PROGRESS and RESULT) of these jobs (counted from 0, as
  // jobs run) are lost, every copy, until the node's next reboot: a link that fails while the job
  // runs and comes back with the reboot.
  std::vector<std::uint64_t> lose_results;
  bool empty() const { return *this == BusFaults{}; }
  friend bool operator==(const BusFaults&, const BusFaults&) = default;
};

// "drop=3,7;drop-rate=0.01;seed=5;garbage=2;silence=10+3;bus-off=12;late-ack=4@1.5;lose-result=6"
// (any subset,
// in any order; docs/can.md). The error names the bad item.
Result<BusFaults> parse_bus_faults(std::string_view spec);
std::ostream& operator<<(std::ostream& os, const BusFaults& faults);

struct SimNodeOptions {
  double heartbeat_s = 0.5;  // wall time between the node's heartbeats; 0: none
  BusFaults faults;
  const Clock* clock = nullptr;  // for heartbeats and late acknowledgements; empty: a SteadyClock
};

struct SimNodeStats {
  std::size_t requests = 0;
  std::size_t jobs_run = 0;
  std::size_t repeats = 0;         // jobs, results and reboots answered from memory
  std::size_t malformed = 0;       // messages that could not be read
  std::size_t ignored = 0;         // requests dropped by a silence or a bus-off
  std::size_t frames_dropped = 0;  // node frames lost by fault injection
  std::size_t garbage_written = 0;
  std::size_t emergency_stops = 0;
};

class SimNode {
 public:
  // `bus` and `robot` (and `line`, optional: needed for garbage and bus-off faults) must outlive
  // the node.
  SimNode(CanBus& bus, SimRobot& robot, SimNodeOptions options, FaultableLine* line = nullptr);

  // Handles what arrives within timeout_s; an error when the bus failed for good.
  Result<void> poll(double timeout_s);
  // Serves until `stop` is set; ok when stopped, the bus's error when the line closed.
  Result<void> serve(const std::atomic<bool>& stop);

  const SimNodeStats& stats() const { return stats_; }
  bool stopped() const { return estop_latched_; }

 private:
  void handle(const Message& message);
  void handle_job(const JobCommand& command);
  void run_job(const JobCommand& command);
  void handle_request(const Request& request);
  void handle_malformed(const Malformed& malformed);
  void send(const Message& message);
  void heartbeat_if_due();

  CanBus& bus_;
  SimRobot& robot_;
  SimNodeOptions options_;
  FaultableLine* line_;
  SteadyClock steady_;
  const Clock* clock_;
  Rng rng_;
  MessageDecoder decoder_;
  SimNodeStats stats_;
  std::uint64_t frames_sent_ = 0;
  bool estop_latched_ = false;
  // The last kKeptJobs jobs run, with their answers (ACK, PROGRESS, RESULT), oldest first; kept
  // over a reboot.
  struct Kept {
    JobCommand command;
    std::vector<Message> answer;
    std::uint64_t number = 0;  // counted from 0, as jobs run
  };
  const Kept* kept(std::uint8_t seq) const;
  // Sends the kept answers of a job, but those a lose-result fault loses.
  void answer(const Kept& job, bool result_only);
  std::vector<Kept> kept_;
  std::vector<std::uint64_t> losing_;  // lose-result jobs whose answers are lost until a reboot
  std::optional<RebootResult> last_reboot_;
  // The job whose acknowledgement a late-ack fault holds back, and when it is run and answered.
  struct LateJob {
    JobCommand command;
    double due_s = 0;
  };
  std::optional<LateJob> late_job_;
  bool late_ack_used_ = false;
  std::uint8_t heartbeat_counter_ = 0;
  double last_heartbeat_s_ = -1e300;
};

}  // namespace sewerplan::hal
