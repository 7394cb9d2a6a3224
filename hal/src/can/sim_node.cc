// SPDX-License-Identifier: MIT
#include "sewerplan/hal/can/sim_node.h"

#include <algorithm>
#include <cmath>

#include "sewerplan/core/overloaded.h"

namespace sewerplan::hal {
namespace {

// What goes on the line for a garbage fault: a truncated frame, a line with a bad digit and noise.
constexpr std::string_view kGarbage = "t12\rT0220Z0008DEADBEEFXY\r\x01\xff\xfe\r";

bool contains(const std::vector<std::uint64_t>& list, std::uint64_t value) {
  return std::find(list.begin(), list.end(), value) != list.end();
}

}  // namespace

SimNode::SimNode(CanBus& bus, SimRobot& robot, SimNodeOptions options, FaultableLine* line)
    : bus_(bus),
      robot_(robot),
      options_(std::move(options)),
      line_(line),
      clock_(options_.clock != nullptr ? options_.clock : &steady_),
      rng_(options_.faults.seed) {}

Result<void> SimNode::serve(const std::atomic<bool>& stop) {
  while (!stop.load()) {
    if (Result<void> r = poll(0.05); !r.has_value()) return r;
  }
  return {};
}

Result<void> SimNode::poll(double timeout_s) {
  heartbeat_if_due();
  if (late_job_) {
    const double left_s = late_job_->due_s - clock_->now_s();
    if (left_s <= 0) {
      const JobCommand command = std::move(late_job_->command);
      late_job_.reset();
      run_job(command);
    } else {
      timeout_s = std::min(timeout_s, left_s);
    }
  }
  Result<std::optional<CanFrame>> in = bus_.receive(timeout_s);
  if (!in.has_value()) {
    // Garbage is dropped; a closed line ends the service.
    if (in.error().code == ErrorCode::kBusError) return in.error();
    ++stats_.malformed;
    return {};
  }
  if (!in->has_value()) return {};
  std::optional<Decoded> decoded = decoder_.push(**in);
  if (!decoded) return {};
  std::visit(Overloaded{
                 [&](const Message& m) { handle(m); },
                 [&](const Malformed& m) { handle_malformed(m); },
             },
             *decoded);
  return {};
}

void SimNode::heartbeat_if_due() {
  if (options_.heartbeat_s <= 0) return;
  const double now_s = clock_->now_s();
  if (now_s - last_heartbeat_s_ < options_.heartbeat_s) return;
  last_heartbeat_s_ = now_s;
  const NodeState state = estop_latched_ ? NodeState::kStopped
                          : late_job_    ? NodeState::kBusy
                                         : NodeState::kIdle;
  const std::uint8_t last = kept_.empty() ? 0 : kept_.back().command.seq;
  for (const CanFrame& f : encode(Heartbeat{true, state, heartbeat_counter_++, last})) {
    static_cast<void>(bus_.send(f));
  }
}

void SimNode::send(const Message& message) {
  const BusFaults& faults = options_.faults;
  for (const CanFrame& frame : encode(message)) {
    const std::uint64_t index = frames_sent_++;
    if (line_ != nullptr && contains(faults.garbage_before, index)) {
      line_->write_garbage(kGarbage);
      ++stats_.garbage_written;
    }
    const bool drop_by_rate = faults.drop_rate > 0 && rng_.bernoulli(faults.drop_rate);
    if (contains(faults.drop_frames, index) || drop_by_rate) {
      ++stats_.frames_dropped;
      continue;
    }
    static_cast<void>(bus_.send(frame));
  }
}

void SimNode::handle(const Message& message) {
  if (!std::holds_alternative<Heartbeat>(message) && sent_by_node(message_type(message))) return;
  if (std::holds_alternative<Heartbeat>(message)) return;  // the controller is alive
  const std::uint64_t request = stats_.requests++;
  const BusFaults& faults = options_.faults;
  if (faults.silence && request >= faults.silence->from_request &&
      request < faults.silence->from_request + faults.silence->requests) {
    ++stats_.ignored;
    return;
  }
  if (faults.bus_off_at && *faults.bus_off_at == request) {
    ++stats_.ignored;
    if (line_ != nullptr) line_->enter_bus_off();
    return;
  }
  std::visit(Overloaded{
                 [&](const JobCommand& m) { handle_job(m); },
                 [&](const Request& m) { handle_request(m); },
                 [&](const EmergencyStop&) {
                   ++stats_.emergency_stops;
                   estop_latched_ = true;
                   late_job_.reset();  // stopped before it started: never run
                   send(EmergencyStopAck{});
                 },
                 [](const auto&) {},
             },
             message);
}

const SimNode::Kept* SimNode::kept(std::uint8_t seq) const {
  const auto it = std::find_if(kept_.rbegin(), kept_.rend(),
                               [seq](const Kept& k) { return k.command.seq == seq; });
  return it == kept_.rend() ? nullptr : &*it;
}

void SimNode::answer(const Kept& job, bool result_only) {
  const bool losing = contains(losing_, job.number);
  for (std::size_t i = result_only ? job.answer.size() - 1 : 0; i < job.answer.size(); ++i) {
    const Message& m = job.answer[i];
    if (losing && !std::holds_alternative<JobAck>(m)) {
      // Sent, and lost on the way: counted as node frames, so that drop=N keeps its meaning.
      const std::size_t frames = encode(m).size();
      frames_sent_ += frames;
      stats_.frames_dropped += frames;
      continue;
    }
    send(m);
  }
}

void SimNode::handle_job(const JobCommand& command) {
  if (const Kept* k = kept(command.seq); k != nullptr && k->command == command) {
    ++stats_.repeats;
    answer(*k, false);
    return;
  }
  // The late job sent again: its answers are still held back.
  if (late_job_ && late_job_->command == command) return;
  if (estop_latched_) {
    send(JobAck{command.seq, AckCode::kRefused, 0});
    return;
  }
  const BusFaults& faults = options_.faults;
  if (faults.late_ack && faults.late_ack->job == stats_.jobs_run && !late_ack_used_) {
    late_ack_used_ = true;  // once: a job sent after the held one was dropped is not held
    // Held back while the node goes on serving (heartbeats busy, the adapter answering): a node
    // that slept here fell silent altogether, which is a lost link, not a late acknowledgement.
    late_job_ = LateJob{command, clock_->now_s() + faults.late_ack->delay_s};
    return;
  }
  late_job_.reset();  // a newer job replaces one still held back
  run_job(command);
}

void SimNode::run_job(const JobCommand& command) {
  const std::uint64_t number = stats_.jobs_run++;
  const JobReport report = robot_.execute(command.job);
  // A number used again (after a wrap) names the new job.
  std::erase_if(kept_, [&](const Kept& k) { return k.command.seq == command.seq; });
  kept_.push_back(
      Kept{command,
           {JobAck{command.seq, AckCode::kAccepted, 0}, JobProgress{command.seq, report.progress_m},
            JobResult{command.seq, report, robot_.status()}},
           number});
  if (kept_.size() > kKeptJobs) kept_.erase(kept_.begin());
  if (contains(options_.faults.lose_results, number)) losing_.push_back(number);
  answer(kept_.back(), false);
}

void SimNode::handle_request(const Request& request) {
  switch (request.kind) {
    case RequestKind::kStatus:
      send(StatusReply{request.seq, robot_.status()});
      return;
    case RequestKind::kResult:
      if (const Kept* k = kept(request.seq)) {
        ++stats_.repeats;
        answer(*k, true);
        return;
      }
      // A job held back by a late-ack fault is still to run: its result comes when it has.
      if (late_job_ && late_job_->command.seq == request.seq) return;
      send(JobAck{request.seq, AckCode::kUnknown, 0});
      return;
    case RequestKind::kReboot: {
      if (last_reboot_ && last_reboot_->seq == request.seq) {
        ++stats_.repeats;
        send(*last_reboot_);
        return;
      }
      late_job_.reset();  // a restarted node has forgotten it
      losing_.clear();    // the link that lost results came back with the reboot
      const Result<void> rebooted = robot_.reboot();
      if (rebooted.has_value()) estop_latched_ = false;
      last_reboot_ = RebootResult{
          request.seq,
          rebooted.has_value() ? std::nullopt : std::optional(rebooted.error().message),
          robot_.status()};
      send(*last_reboot_);
      return;
    }
    case RequestKind::kBeacon:
      static_cast<void>(robot_.activate_beacon());  // the STATUS says whether it is on
      send(StatusReply{request.seq, robot_.status()});
      return;
  }
}

void SimNode::handle_malformed(const Malformed& malformed) {
  ++stats_.malformed;
  if (malformed.type != MessageType::kJob) return;
  send(JobAck{malformed.seq, malformed.incomplete ? AckCode::kIncomplete : AckCode::kCorrupt, 0});
}

}  // namespace sewerplan::hal
