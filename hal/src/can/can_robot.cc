// SPDX-License-Identifier: MIT
#include "sewerplan/hal/can/can_robot.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include "sewerplan/core/check.h"

namespace sewerplan::hal {
namespace {

// A peer that floods the bus cannot keep a wait going for ever.
constexpr std::size_t kMaxFramesPerWait = 100000;

std::string seconds_text(double s) {
  std::ostringstream os;
  os << s << " s";
  return os.str();
}

}  // namespace

CanRobot::CanRobot(CanBus& bus, CanRobotOptions options)
    : bus_(bus), options_(options), clock_(options.clock != nullptr ? options.clock : &steady_) {
  SEWER_CHECK(options_.attempts >= 1 && options_.max_resends >= 0,
              "CanRobot: attempts must be >= 1, max_resends >= 0");
  SEWER_CHECK(options_.ack_timeout_s > 0 && options_.link_timeout_s > 0 &&
                  options_.job_timeout_s > 0 && options_.heartbeat_s > 0,
              "CanRobot: timeouts must be > 0");
}

Result<void> CanRobot::send(const Message& message) {
  for (const CanFrame& frame : encode(message)) {
    if (Result<void> sent = bus_.send(frame); !sent.has_value()) {
      ++stats_.bus_errors;
      return sent;
    }
  }
  ++messages_sent_;
  return {};
}

void CanRobot::heartbeat_if_due() {
  const double now_s = clock_->now_s();
  if (now_s - last_heartbeat_s_ < options_.heartbeat_s) return;
  last_heartbeat_s_ = now_s;
  static_cast<void>(send(Heartbeat{false, NodeState::kIdle, heartbeat_counter_++, seq_}));
}

std::optional<Message> CanRobot::await(double timeout_s,
                                       const std::function<Verdict(const Message&)>& judge,
                                       std::string& problem, bool& bus_failed, bool stoppable) {
  const double start_s = clock_->now_s();
  double window_start_s = start_s;
  double waited_s = 0;  // wall time spent in empty receives: bounds the wait under any Clock
  std::size_t bad = 0;
  std::size_t frames = 0;
  // Counts one garbled line or malformed message; false once there are more than a retry can
  // repair: a line this noisy is broken.
  const auto tolerate_bad_input = [&](std::string what) {
    ++stats_.bad_input;
    last_bad_input_ = what;
    problem = std::move(what);
    if (++bad <= options_.max_bad_input) return true;
    problem = std::to_string(bad) + " bad inputs, the last: " + problem;
    bus_failed = true;
    return false;
  };
  for (;;) {
    if (stoppable && stop_requested_.load()) {
      problem = "emergency stop";
      bus_failed = true;
      return std::nullopt;
    }
    const double now_s = clock_->now_s();
    if (now_s - start_s >= options_.job_timeout_s) {
      problem = "no end within the job timeout of " + seconds_text(options_.job_timeout_s);
      ++stats_.timeouts;
      return std::nullopt;
    }
    const double left_s = std::min(timeout_s - (now_s - window_start_s), timeout_s - waited_s);
    if (left_s <= 0) {
      problem = "no answer within " + seconds_text(timeout_s);
      ++stats_.timeouts;
      return std::nullopt;
    }
    heartbeat_if_due();
    const double slice_s = std::min(left_s, options_.heartbeat_s);
    Result<std::optional<CanFrame>> in = bus_.receive(slice_s);
    if (!in.has_value()) {
      if (in.error().code == ErrorCode::kBusError) {
        ++stats_.bus_errors;
        bus_failed = true;
        problem = in.error().message;
        return std::nullopt;
      }
      if (!tolerate_bad_input(in.error().message)) return std::nullopt;
      continue;
    }
    if (!in->has_value()) {
      waited_s += slice_s;
      continue;
    }
    if (++frames > kMaxFramesPerWait) {
      problem = "flooded with " + std::to_string(frames) + " frames without an answer";
      return std::nullopt;
    }
    if (const std::optional<FrameId> id = frame_id(**in);
        id && awaited_seq_ && id->seq == *awaited_seq_ && sent_by_node(id->type) &&
        id->type != MessageType::kNodeHeartbeat && id->type != MessageType::kEmergencyStopAck) {
      heard_ = true;  // a frame of the answer, whole or not
    }
    std::optional<Decoded> decoded = decoder_.push(**in);
    if (!decoded) continue;
    if (const auto* bad_message = std::get_if<Malformed>(&*decoded)) {
      if (!tolerate_bad_input("malformed " + bad_message->reason)) return std::nullopt;
      // The answer arrived damaged: ask again now (the decoder keeps what arrived) rather than
      // wait out the timeout.
      if (awaited_seq_ && bad_message->seq == *awaited_seq_ && sent_by_node(bad_message->type)) {
        return std::nullopt;
      }
      continue;
    }
    Message& message = std::get<Message>(*decoded);
    if (!sent_by_node(message_type(message))) continue;  // another controller's, or an echo
    switch (judge(message)) {
      case Verdict::kTake:
        return std::move(message);
      case Verdict::kAlive:
        window_start_s = clock_->now_s();
        waited_s = 0;
        break;
      case Verdict::kIgnore:
        if (!std::holds_alternative<Heartbeat>(message)) ++stats_.stale_messages;
        break;
    }
  }
}

std::optional<Message> CanRobot::exchange(const Request& request, double timeout_s,
                                          const std::function<Verdict(const Message&)>& judge,
                                          std::string& problem, bool stoppable) {
  awaited_seq_ = request.seq;
  // Sends that nothing of an answer came back to count against `attempts`; those whose answer
  // arrived damaged against max_resends as well.
  int unanswered = 0;
  int sends = 0;
  std::optional<Message> answer;
  while (!answer && unanswered < options_.attempts &&
         sends < options_.attempts + options_.max_resends) {
    if (sends++ > 0) ++stats_.retries;
    if (Result<void> sent = send(request); !sent.has_value()) {
      problem = sent.error().message;
      break;
    }
    bool bus_failed = false;
    heard_ = false;
    answer = await(timeout_s, judge, problem, bus_failed, stoppable);
    if (bus_failed) break;
    if (!answer && !heard_) ++unanswered;
  }
  awaited_seq_.reset();
  if (!answer && unanswered == options_.attempts) {
    problem += " (" + std::to_string(sends) + " attempts)";
  }
  return answer;
}

JobReport CanRobot::link_failure(const std::string& what, double progress_m) {
  ++stats_.link_failures;
  ++stats_.emergency_stops;
  static_cast<void>(send(EmergencyStop{StopReason::kProtocolError}));
  JobReport report;
  report.progress_m = progress_m;
  std::string reason = "CAN link: " + what;
  // A timeout after dropped input: the input may say more than the timeout.
  if (!last_bad_input_.empty() && what.find(last_bad_input_) == std::string::npos) {
    reason += "; dropped before: " + last_bad_input_;
  }
  report.error = RobotError{RobotErrorCause::kLink, std::move(reason)};
  return report;
}

JobReport CanRobot::stopped(double progress_m) {
  ++stats_.emergency_stops;
  static_cast<void>(send(EmergencyStop{StopReason::kController}));
  JobReport report;
  report.progress_m = progress_m;
  report.error = RobotError{RobotErrorCause::kEmergencyStop, "emergency stop"};
  return report;
}

template <class Reply>
std::optional<Reply> CanRobot::ask(RequestKind kind, double timeout_s, std::string& problem,
                                   bool stoppable) {
  const std::uint8_t seq = next_seq();
  std::optional<Message> answer = exchange(
      Request{kind, seq}, timeout_s,
      [seq](const Message& m) {
        const auto* r = std::get_if<Reply>(&m);
        return r != nullptr && r->seq == seq ? Verdict::kTake : Verdict::kIgnore;
      },
      problem, stoppable);
  if (!answer) return std::nullopt;
  return std::get<Reply>(*answer);
}

Result<void> CanRobot::connect() {
  std::string problem;
  std::optional<StatusReply> answer =
      ask<StatusReply>(RequestKind::kStatus, options_.ack_timeout_s, problem);
  if (!answer) {
    return Error{ErrorCode::kCanTimeout, bus_.name() + ": no node answered: " + problem};
  }
  status_ = answer->status;
  return {};
}

JobReport CanRobot::execute(const Job& job) {
  if (const auto* turn = std::get_if<TurnInManhole>(&job);
      turn != nullptr && turn->waypoints.size() > (kMaxDataFrames - 5) / 4) {
    JobReport report;
    report.error = RobotError{RobotErrorCause::kInvalidJob,
                              "invalid job: " + std::to_string(turn->waypoints.size()) +
                                  " waypoints, the CAN protocol carries at most " +
                                  std::to_string((kMaxDataFrames - 5) / 4)};
    return report;
  }
  if (stop_requested_.load()) return stopped(0);
  const std::uint8_t seq = next_seq();
  const std::string name = "job " + std::to_string(seq);
  last_bad_input_.clear();
  recovered_.reset();
  // Sent, and its result never came: the node may have run it, all or part. The next reboot asks.
  const auto lost = [&](const std::string& what, double progress_m) {
    lost_job_ = seq;
    awaited_seq_.reset();
    return link_failure(what, progress_m);
  };
  awaited_seq_ = seq;
  std::string problem;
  std::optional<JobResult> result;
  bool accepted = false;
  for (int attempt = 0; attempt < options_.attempts && !accepted && !result; ++attempt) {
    if (attempt > 0) ++stats_.retries;
    if (Result<void> sent = send(JobCommand{seq, job}); !sent.has_value()) {
      return lost("cannot send " + name + ": " + sent.error().message, 0);
    }
    bool bus_failed = false;
    std::optional<Message> answer = await(
        options_.ack_timeout_s,
        [seq](const Message& m) {
          const auto* ack = std::get_if<JobAck>(&m);
          const auto* r = std::get_if<JobResult>(&m);
          const bool ours = (ack != nullptr && ack->seq == seq) || (r != nullptr && r->seq == seq);
          return ours ? Verdict::kTake : Verdict::kIgnore;
        },
        problem, bus_failed, true);
    if (bus_failed) return stop_requested_.load() ? stopped(0) : lost(problem, 0);
    if (!answer) continue;
    if (auto* r = std::get_if<JobResult>(&*answer)) {
      result = std::move(*r);  // the acknowledgement was lost, the result was not
      break;
    }
    const JobAck& ack = std::get<JobAck>(*answer);
    switch (ack.code) {
      case AckCode::kAccepted:
        accepted = true;
        break;
      case AckCode::kIncomplete:
        problem = "the node missed frame " + std::to_string(ack.detail) + " of " + name;
        break;
      case AckCode::kCorrupt:
        problem = "the node could not read " + name;
        break;
      case AckCode::kUnknown:  // the answer to a result request of an earlier wait: send again
        problem = "the node does not know " + name;
        break;
      case AckCode::kRefused: {
        JobReport report;
        report.error = RobotError{RobotErrorCause::kEmergencyStop,
                                  "the node refused " + name + ": stopped until a reboot"};
        return report;
      }
    }
  }
  // Without an acknowledgement the node may still be running the job, late: wait for its result
  // as for an accepted job (asking again with RESULT_REQUEST), so that a late acknowledgement
  // changes nothing. Declaring the link failed at once ended missions while the node drove on.
  const std::string no_ack = accepted || result
                                 ? std::string()
                                 : "no acknowledgement of " + name + ": " + problem + " (" +
                                       std::to_string(options_.attempts) + " attempts)";
  double progress_m = 0;
  // As exchange(): waits that heard nothing of the result count against `attempts`, and waits
  // that heard a damaged one against max_resends too.
  int unanswered = 0;
  for (int wait = 0;
       !result && unanswered < options_.attempts && wait < options_.attempts + options_.max_resends;
       ++wait) {
    if (wait > 0) {
      ++stats_.retries;
      if (Result<void> sent = send(Request{RequestKind::kResult, seq}); !sent.has_value()) {
        return lost("cannot ask for the result of " + name + ": " + sent.error().message,
                    progress_m);
      }
    }
    bool bus_failed = false;
    heard_ = false;
    std::optional<Message> answer = await(
        options_.link_timeout_s,
        [seq, &progress_m](const Message& m) {
          if (const auto* r = std::get_if<JobResult>(&m); r != nullptr && r->seq == seq) {
            return Verdict::kTake;
          }
          // The node does not know the job (it never arrived): no result will come.
          if (const auto* a = std::get_if<JobAck>(&m);
              a != nullptr && a->seq == seq && a->code == AckCode::kUnknown) {
            return Verdict::kTake;
          }
          if (const auto* p = std::get_if<JobProgress>(&m); p != nullptr && p->seq == seq) {
            progress_m = p->progress_m;
            return Verdict::kAlive;
          }
          if (const auto* h = std::get_if<Heartbeat>(&m);
              h != nullptr && h->state == NodeState::kBusy) {
            return Verdict::kAlive;
          }
          return Verdict::kIgnore;
        },
        problem, bus_failed, true);
    if (bus_failed) {
      return stop_requested_.load() ? stopped(progress_m) : lost(problem, progress_m);
    }
    if (answer && std::holds_alternative<JobAck>(*answer)) {
      const std::string unknown = "the node does not know " + name;
      return lost(no_ack.empty() ? unknown : no_ack + "; " + unknown, progress_m);
    }
    if (answer) {
      result = std::move(std::get<JobResult>(*answer));
    } else if (!heard_) {
      ++unanswered;
    }
  }
  awaited_seq_.reset();
  if (!result) {
    if (!no_ack.empty()) return lost(no_ack, progress_m);
    return lost("no result of " + name + ": " + problem + " (" + std::to_string(options_.attempts) +
                    " attempts)",
                progress_m);
  }
  lost_job_.reset();
  status_ = result->status;
  return result->report;
}

Result<void> CanRobot::reboot() {
  stop_requested_.store(false);
  if (Result<void> recovered = bus_.recover(); !recovered.has_value()) {
    return Error{ErrorCode::kBusError, "reboot failed: " + recovered.error().message};
  }
  std::string problem;
  // Stoppable: a halt during a reboot used to wait for every attempt's timeout (6 s by default).
  std::optional<RebootResult> answer =
      ask<RebootResult>(RequestKind::kReboot, options_.link_timeout_s, problem, true);
  if (!answer && stop_requested_.load()) {
    ++stats_.emergency_stops;
    static_cast<void>(send(EmergencyStop{StopReason::kController}));
    return Error{ErrorCode::kCancelled, "reboot stopped: emergency stop"};
  }
  if (!answer) {
    return Error{ErrorCode::kCanTimeout, "reboot failed: no answer over CAN: " + problem};
  }
  const RebootResult& r = *answer;
  status_ = r.status;
  // The node's words, as the simulated robot's: "reboot failed: ...".
  if (r.failure) return Error{ErrorCode::kIo, *r.failure};
  return settle_lost_job();
}

// The node keeps the results of its last jobs (kKeptJobs) over a reboot: asked for the one the
// link lost, it gives the job's own report, or ACK kUnknown when the job never reached it. Until
// the answer comes nothing else is sent: a job sent from where the controller last heard of the
// robot (a turn it has made, a drive it has finished) would be refused, as a malfunction.
Result<void> CanRobot::settle_lost_job() {
  if (!lost_job_) return {};
  const std::uint8_t seq = *lost_job_;
  const std::string name = "job " + std::to_string(seq);
  std::string problem;
  std::optional<Message> answer = exchange(
      Request{RequestKind::kResult, seq}, options_.link_timeout_s,
      [seq](const Message& m) {
        const auto* r = std::get_if<JobResult>(&m);
        const auto* ack = std::get_if<JobAck>(&m);
        const bool ours = (r != nullptr && r->seq == seq) ||
                          (ack != nullptr && ack->seq == seq && ack->code == AckCode::kUnknown);
        return ours ? Verdict::kTake : Verdict::kIgnore;
      },
      problem, true);
  if (!answer && stop_requested_.load()) {
    ++stats_.emergency_stops;
    static_cast<void>(send(EmergencyStop{StopReason::kController}));
    return Error{ErrorCode::kCancelled, "reboot stopped: emergency stop"};
  }
  if (!answer) {
    return Error{ErrorCode::kCanTimeout,
                 "reboot failed: no answer over CAN to what became of " + name + ": " + problem};
  }
  lost_job_.reset();
  if (const auto* r = std::get_if<JobResult>(&*answer)) {
    recovered_ = r->report;  // the status stays the reboot's, which is newer
  } else {
    JobReport never;
    never.error =
        RobotError{RobotErrorCause::kLink, "CAN link: " + name + " never reached the node"};
    recovered_ = never;
  }
  return {};
}

std::optional<JobReport> CanRobot::recovered_report() {
  std::optional<JobReport> taken = std::move(recovered_);
  recovered_.reset();
  return taken;
}

BeaconState CanRobot::activate_beacon() {
  std::string problem;
  const std::size_t sent_before = messages_sent_;
  const std::size_t bus_errors_before = stats_.bus_errors;
  std::optional<StatusReply> answer =
      ask<StatusReply>(RequestKind::kBeacon, options_.ack_timeout_s, problem);
  if (!answer) {
    // The bus refused the request (a failed send; SLCAN: the adapter's BEL, a closed line).
    const bool refused = messages_sent_ == sent_before || stats_.bus_errors > bus_errors_before;
    return refused ? BeaconState::kNotSent : BeaconState::kUnconfirmed;
  }
  status_ = answer->status;
  return status_.beacon_on ? BeaconState::kConfirmed : BeaconState::kUnconfirmed;
}

}  // namespace sewerplan::hal
