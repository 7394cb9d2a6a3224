// SPDX-License-Identifier: MIT
// The action controller: plans, actions, jobs, recovery and replanning (executor.h).
#include "sewerplan/executor/executor.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>

#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/executor/event_json.h"
#include "sewerplan/fusion/action_text.h"
#include "sewerplan/fusion/jobs.h"
#include "sewerplan/fusion/robot_action.h"

#include "dead_reckoning.h"
#include "job_arithmetic.h"
#include "localising.h"
#include "staged_recovery.h"

namespace sewerplan::executor {
namespace {

std::vector<std::string> task_names(const Mission& mission, const std::vector<TaskId>& tasks) {
  std::vector<std::string> names;
  for (TaskId t : tasks) names.push_back(mission.task(t).name);
  return names;
}

}  // namespace

std::ostream& operator<<(std::ostream& os, const MissionReport& r) {
  os << std::fixed << std::setprecision(1);
  switch (r.outcome) {
    case MissionReport::Outcome::kEnded:
      os << "mission ended at ";
      break;
    case MissionReport::Outcome::kBeacon:
      switch (r.beacon) {
        case hal::BeaconState::kNone:
        case hal::BeaconState::kConfirmed:
          os << "beacon on: ";
          break;
        case hal::BeaconState::kUnconfirmed:
          os << "beacon requested, unconfirmed (the robot did not answer): ";
          break;
        case hal::BeaconState::kNotSent:
          os << "beacon NOT on (the request could not be sent): ";
          break;
      }
      break;
    case MissionReport::Outcome::kHalted:
      os << "halted ";
      break;
  }
  os << r.end << '\n';
  os << "tasks done: " << r.tasks_done.size();
  for (std::size_t i = 0; i < r.tasks_done.size(); ++i) {
    os << (i == 0 ? " (" : ", ") << r.tasks_done[i] << (i + 1 == r.tasks_done.size() ? ")" : "");
  }
  os << "\ntasks dropped: " << r.dropped.size() << '\n';
  for (const auto& [task, reason] : r.dropped) os << "  - " << task << ": " << reason << '\n';
  os << "time " << r.time_s << " s, energy " << r.energy_wh << " Wh, " << r.jobs << " jobs, "
     << r.recoveries << " errors cleared by recovery, " << r.replans << " replans";
  if (!r.planning_times_s.empty()) {
    os << std::setprecision(1) << " (planning";
    for (double t : r.planning_times_s) os << ' ' << t * 1000 << " ms";
    os << ')';
  }
  os << "\nbattery reserve " << (r.battery_reserve_kept ? "kept" : "NOT kept");
  if (r.exit_on_reserve) os << " (the way out was on the reserve: no exit above it)";
  os << '\n';
  for (const std::string& e : r.log_errors) os << "log not written: " << e << '\n';
  return os;
}

Executor::Executor(const SewerMap& map, Replanner& replanner, hal::Robot& robot,
                   ExecutorOptions options)
    : map_(map), replanner_(replanner), robot_(robot), options_(options) {}

void Executor::subscribe(EventObserver observer) { observers_.push_back(std::move(observer)); }

void Executor::subscribe_plans(PlanObserver observer) {
  plan_observers_.push_back(std::move(observer));
}

void Executor::subscribe_jobs(JobObserver observer) {
  job_observers_.push_back(std::move(observer));
}

void Executor::subscribe_log(LogFile& log) {
  logs_.push_back(&log);
  observers_.push_back([&log](const Event& event) { log.append(to_json_line(event) + '\n'); });
}

void Executor::halt() {
  halt_.store(true);
  robot_.emergency_stop();
}

class Executor::Run {
 public:
  explicit Run(Executor& e)
      : map_(e.map_),
        replanner_(e.replanner_),
        robot_(e.robot_),
        options_(e.options_),
        observers_(e.observers_),
        plan_observers_(e.plan_observers_),
        job_observers_(e.job_observers_),
        logs_(e.logs_),
        halt_(e.halt_),
        tracker_(e.map_, e.replanner_.progress().position, e.replanner_.heading_end()),
        localising_(e.map_, e.options_.odometry_sd_fraction, e.replanner_.learnt().junctions),
        recovery_(
            e.map_, e.options_.recovery, e.replanner_.mission().profile.speed_mps, tracker_,
            {.execute_job = [this](const Job& job) { return execute_job(job); },
             .reboot = [this] { return reboot(); },
             .recovered_report =
                 [this](const Job& job, const hal::JobReport& heard) {
                   return recovered_report(job, heard);
                 },
             .log_recovery = [this](RecoveryPhase phase, bool ok) { log_recovery(phase, ok); },
             .settle_elsewhere = [this] { return settle_elsewhere(); }}),
        done_(e.replanner_.progress().done) {}

  MissionReport go() {
    localising_.reset(tracker_.position(), tracker_.heading_end());
    if (halted()) return finish(MissionReport::Outcome::kHalted, "");
    std::optional<PlanResponse> first = plan_unless_halted(std::nullopt, "start");
    if (!first) return finish(MissionReport::Outcome::kHalted, "");
    PlanResponse response = std::move(*first);
    log_plan(false, response);
    std::optional<Failure> last_failure;
    for (;;) {
      report_.decision = response.decision;
      if (halted()) return finish(MissionReport::Outcome::kHalted, "");
      if (response.decision == PlanResponse::Decision::kCallForRecovery) {
        // No exit from where the tracking has the robot; the beacon only when none is reachable
        // in the belief: where the filter holds another place, the robot first backs up to the
        // manhole behind, whose arrival tells the places apart.
        if (std::optional<std::string> why = back_up_to_tell_apart()) {
          if (halted()) return finish(MissionReport::Outcome::kHalted, "");
          ++report_.replans;
          last_failure.reset();
          std::optional<PlanResponse> next = plan_unless_halted(std::nullopt, *why);
          if (!next) return finish(MissionReport::Outcome::kHalted, "");
          response = std::move(*next);
          log_plan(true, response);
          continue;
        }
      }
      if (!has_plan(response.decision)) {
        report_.beacon_cause = beacon_cause(response.decision, last_failure);
        return finish(MissionReport::Outcome::kBeacon, response.reason);
      }
      if (auto invalid = check(response)) {
        report_.beacon_cause = MissionReport::BeaconCause::kLimit;
        return finish(MissionReport::Outcome::kBeacon, "the plan is not valid: " + *invalid);
      }
      std::optional<Replan> replan = execute(response);
      if (halted()) return finish(MissionReport::Outcome::kHalted, "");
      if (!replan) {
        confirm_final_task();
        return finish(MissionReport::Outcome::kEnded, response.end);
      }
      if (report_.replans >= options_.max_replans) {
        report_.beacon_cause = MissionReport::BeaconCause::kLimit;
        return finish(MissionReport::Outcome::kBeacon,
                      "gave up after " + std::to_string(report_.replans) + " replans");
      }
      ++report_.replans;
      last_failure = replan->failure;
      if (replan->failure) log_failure(*replan->failure);
      std::optional<PlanResponse> next = plan_unless_halted(replan->failure, replan->reason);
      if (!next) return finish(MissionReport::Outcome::kHalted, "");
      response = std::move(*next);
      log_plan(true, response);
    }
  }

 private:
  struct Replan {
    std::optional<Failure> failure;
    std::string reason;
  };

  double now() const { return robot_.status().elapsed_s; }

  // The Replanner's answer to `failure` (or a plan for `reason`), cancelled by a halt: the halt
  // flag is the cancel of the planner's StopCondition, so a halt while a plan is computed takes
  // effect within the planner's next check, not after the plan. Empty when halted.
  std::optional<PlanResponse> plan_unless_halted(const std::optional<Failure>& failure,
                                                 const std::string& reason) {
    Result<PlanResponse> r = replanner_.plan_cancellable(failure, reason, halt_);
    if (!r.has_value() || halted()) return std::nullopt;
    return std::move(*r);
  }

  bool halted() const { return halt_.load(); }

  template <class What>
  void emit(What what) {
    const Event event{now(), std::move(what)};
    for (const EventObserver& observer : observers_) observer(event);
  }

  // Why the Replanner's answer switches the beacon on: a proof that no exit can be reached, or a
  // robot that cannot move, by what stopped it: the cause the robot typed on the last failure
  // (hal::RobotErrorCause; its words are for people and decide nothing).
  static MissionReport::BeaconCause beacon_cause(PlanResponse::Decision decision,
                                                 const std::optional<Failure>& failure) {
    using Cause = MissionReport::BeaconCause;
    if (decision == PlanResponse::Decision::kCallForRecovery) return Cause::kNoExit;
    if (decision != PlanResponse::Decision::kStuck) return Cause::kLimit;
    if (!failure || !failure->cause) return Cause::kStuck;
    switch (*failure->cause) {
      case hal::RobotErrorCause::kLink:
        return Cause::kLink;
      case hal::RobotErrorCause::kFault:
      case hal::RobotErrorCause::kBatteryEmpty:
      case hal::RobotErrorCause::kOtherMalfunction:
        return Cause::kMalfunction;
      case hal::RobotErrorCause::kObstacle:
      case hal::RobotErrorCause::kBlindEnd:
      case hal::RobotErrorCause::kNoManholeSeen:
      case hal::RobotErrorCause::kOtherBlockage:
      case hal::RobotErrorCause::kDangerSpot:
      case hal::RobotErrorCause::kDangerousPassage:
      case hal::RobotErrorCause::kOtherDanger:
      case hal::RobotErrorCause::kInvalidJob:
      case hal::RobotErrorCause::kEmergencyStop:
        break;  // held where it is: a danger, a job it cannot run, a stop
    }
    return Cause::kStuck;
  }
  const Mission& mission() const { return replanner_.mission(); }

  // The progress planning starts from: the dropped tasks count as done.
  domain::MissionProgress planning_start() const {
    domain::MissionProgress start = replanner_.progress();
    for (const auto& d : replanner_.dropped()) start.done[d.task.index()] = true;
    return start;
  }

  std::optional<std::string> check(const PlanResponse& response) const {
    const auto report = domain::validate_plan(response.plan, map_, mission(), planning_start());
    if (report.valid) return std::nullopt;
    return report.error;
  }

  void log_plan(bool replan, const PlanResponse& r) {
    for (const HazardUpdate& u : r.hazard_updates) log_hazard(u);
    std::vector<std::string> dropped;
    for (const auto& d : r.newly_dropped) {
      dropped.push_back(mission().task(d.task).name);
      emit(TaskDroppedEvent{mission().task(d.task).name, d.reason});
    }
    report_.planning_times_s.push_back(r.planning_time_s);
    emit(PlanEvent{.replan = replan,
                   .reason = r.reason,
                   .planning_ms = r.planning_time_s * 1000,
                   .decision = r.decision,
                   .goals = task_names(mission(), r.goals),
                   .dropped = std::move(dropped),
                   .end = r.end,
                   .steps = r.plan.steps.size(),
                   .cost_s = r.cost_s,
                   .rung = r.rung,
                   .strand_probability = r.strand_probability});
    for (const PlanObserver& observer : plan_observers_) observer(r);
    if (r.decision == PlanResponse::Decision::kExitOnReserve) {
      report_.exit_on_reserve = true;
      const RobotProfile& p = mission().profile;
      emit(ReserveEvent{.end = r.end,
                        .energy_wh = r.energy_wh,
                        .left_wh = robot_.status().battery_wh,
                        .reserve_wh = p.battery_wh * replanner_.reserve_fraction()});
    }
  }

  // What the Replanner is told: a blocked pipe, a closed passage, or a robot that cannot move.
  void log_failure(const Failure& f) {
    FailureEvent event{.kind = f.kind, .detail = f.detail};
    if (f.kind == Failure::Kind::kBlockage || f.kind == Failure::Kind::kDangerInPipe) {
      event.where = FailureEvent::InPipe{map_.pipe(f.pipe).name, f.offset_m};
    } else if (f.kind == Failure::Kind::kDangerousPassage) {
      event.where = FailureEvent::Passage{map_.manhole(f.manhole).name,
                                          static_cast<int>(to_paper_number(f.from)),
                                          static_cast<int>(to_paper_number(f.to))};
    }
    emit(std::move(event));
  }

  // Runs the plan; empty when it was carried out to its end.
  std::optional<Replan> execute(const PlanResponse& response) {
    domain::PlanReplay replay(map_, mission(), planning_start());
    const auto& actions = response.fused.actions;
    for (std::size_t i = 0; i < actions.size(); ++i) {
      if (halted()) return Replan{std::nullopt, "halted"};
      if (auto low = battery_low(actions, i)) return Replan{std::nullopt, *low};
      const fusion::RobotAction& action = actions[i];
      emit(ActionEvent{.step = domain::format_step(response.plan.steps[fusion::plan_step(action)],
                                                   map_, mission()),
                       .kind = std::string(fusion::action_kind(action)),
                       .duration_s = fusion::duration_s(action),
                       .parameters = fusion::describe(action, map_, mission())});
      for (const Job& job : fusion::expand(action, mission().profile)) {
        // A job stopped by a manhole the map lacks goes on beyond it, once the robot has passed.
        for (std::optional<Job> next = job; next;) {
          std::optional<Failure> failure = recovery_.run_job(*next, action);
          if (failure) {
            if (std::optional<std::string> settled = refused_at_no_manhole(*failure, *next)) {
              mismatch_.reset();
              sync_progress(replay.progress());
              return Replan{std::nullopt, *settled};
            }
            place_by_belief(*failure, *next);
          }
          next.reset();
          if (failure || halted()) {
            mismatch_.reset();
            sync_progress(replay.progress());
            return Replan{failure, failure ? "" : "halted"};
          }
          if (mismatch_) {
            if (std::optional<Replan> replan = relocalise(replay, next)) return replan;
          }
        }
      }
      const domain::PlanStep& step = response.plan.steps[fusion::plan_step(action)];
      const std::vector<bool> before = replay.done();
      if (!replay.apply(step).has_value()) {
        return Replan{Failure{.kind = Failure::Kind::kStuck, .detail = "plan and robot disagree"},
                      ""};
      }
      if (!agrees(tracker_.position(), replay.position())) {
        // The robot is not where the plan puts it: plan again from where it really is, rather than
        // carry on (or report the mission ended at an exit) on the plan's word; the step's tasks
        // are not done (a go-to 1 m short is not at its place, a scan stopped short did not
        // inspect the whole pipe).
        sync_progress(replay.progress());
        return Replan{std::nullopt, "the robot is " + tracker_.describe() + ", the plan has it " +
                                        domain::describe(replay.position(), map_)};
      }
      for (TaskId t : mission().task_ids()) {
        if (!before[t.index()] && replay.done()[t.index()]) {
          report_.tasks_done.push_back(mission().task(t).name);
          done_[t.index()] = true;
          emit(TaskDoneEvent{mission().task(t).name});
        }
      }
      tracker_.set_position(replay.position());
      sync_progress(replay.progress());
    }
    return std::nullopt;
  }

  // An arrival that does not match the plan's manhole: the controller settles on the filter's
  // most likely place at once (so that what observes the job sees it there), and the plan is
  // made again after the job (relocalise()). At the manhole the odometry expected but unlike its
  // map (signature-differs): a discrepancy of the map, the plan goes on. Lost: the filter starts
  // again from the tracking's place.
  void settle(detail::Arrival arrival) {
    using Kind = localisation::Verification::Kind;
    const localisation::Verification& v = arrival.verification;
    if (v.kind == Kind::kSignatureDiffers) {
      // The manhole the plan expected, with a mouth fewer: its pipe cannot be reached from here.
      if (detail::missing_mouth(arrival, map_, localising_.options().noise))
        mismatch_ = std::move(arrival);
      return;
    }
    if (!v.believed) {
      localising_.reset(tracker_.position(), tracker_.heading_end());
      return;
    }
    tracker_.set_pose(v.believed->position,
                      v.believed->heading_end.value_or(tracker_.heading_end()));
    mismatch_ = std::move(arrival);
  }

  // The filter's place for the robot when it believes it in another pipe than `tracked` (a
  // manhole driven through unseen, with no arrival since to settle on): the most likely place holds
  // a majority, and at least twice what every place in the tracked pipe holds together.
  std::optional<localisation::Hypothesis> believed_elsewhere(PipeId tracked) const {
    std::optional<localisation::Hypothesis> best = likely_elsewhere(tracked, 0.5);
    if (!best) return std::nullopt;
    double tracked_p = 0;
    for (const localisation::Hypothesis& h : localising_.estimate().hypotheses) {
      const auto* there = std::get_if<domain::InPipe>(&h.pose.position);
      if (there != nullptr && there->pipe == tracked) tracked_p += h.probability;
    }
    if (best->probability < 2 * tracked_p) return std::nullopt;
    return best;
  }

  // The filter's most likely place in a pipe other than `tracked` (not at a junction), when it
  // holds at least `share`.
  std::optional<localisation::Hypothesis> likely_elsewhere(PipeId tracked, double share) const {
    const localisation::Estimate belief = localising_.estimate();
    for (const localisation::Hypothesis& h : belief.hypotheses) {
      const auto* in = std::get_if<domain::InPipe>(&h.pose.position);
      if (in == nullptr || h.pose.at_unmapped_junction || in->pipe == tracked ||
          !h.pose.heading_end) {
        continue;
      }
      if (h.probability >= share) return h;
      break;  // most likely first
    }
    return std::nullopt;
  }

  // Whether `failure` (in a pipe) is placed at the end of its pipe that `job` drove towards: the
  // place it stopped, not where the robot is now (a danger's recovery backs off first).
  bool at_far_end(const Failure& failure, const Job& job) const {
    const double direction = tracker_.direction_of(job);
    if (direction == 0) return false;
    const double end = direction > 0 ? map_.pipe(failure.pipe).length_m : 0.0;
    return std::abs(failure.offset_m - end) <= kAtEndM;
  }

  // Moves the tracking to `believed`; what it was, for the record.
  std::string settle_on(const localisation::Hypothesis& believed) {
    std::string tracked = tracker_.describe();
    tracker_.set_pose(believed.pose.position, *believed.pose.heading_end);
    std::ostringstream why;
    why << "the robot is " << localisation::describe(believed.pose, map_) << " (p=" << std::fixed
        << std::setprecision(2) << believed.probability << "), not " << tracked;
    return why.str();
  }

  // A drive to a manhole that saw none within its bound: where the filter believes the robot in
  // another pipe (it drove through the manhole unseen), the tracking moves there, and the plan is
  // made again from there (StagedRecovery). Retrying drove the robot on, 2 m at a time, away from
  // the manhole it missed, and the pipe beyond was then closed as blocked, often the robot's way
  // home.
  bool settle_elsewhere() {
    const auto* in = std::get_if<domain::InPipe>(&tracker_.position());
    if (in == nullptr) return false;
    const std::optional<localisation::Hypothesis> best = believed_elsewhere(in->pipe);
    if (!best) return false;
    (void)settle_on(*best);
    // Into this pipe through the mouth behind the robot, the way the drive went: what was learnt
    // blocked on the way is gone.
    const auto& here = std::get<domain::InPipe>(tracker_.position());
    const double direction = tracker_.direction_of(last_job_);
    if (direction != 0) {
      const double entered_at = direction > 0 ? 0.0 : map_.pipe(here.pipe).length_m;
      (void)replanner_.drove_through(here.pipe, entered_at, here.offset_m);
    }
    return true;
  }

  // No exit is reachable from where the tracking has the robot (in a pipe), but the filter holds
  // another place for it, in another pipe, at ambiguity_probability or more (a manhole driven
  // through unseen, or a pipe longer than mapped: on the meshed network, seed 2, run 20, a robot
  // past a manhole it missed met an obstacle, the tracked pipe was closed at its end, and the
  // beacon came on with an exit a few metres behind it). The robot drives back the way it came, to
  // the manhole behind; the arrival there is checked, and the tracking settles on what the filter
  // finds. The reason to plan again, or empty: no other place, not in a pipe, tried
  // kMaxTellApart times already, or the drive back failed.
  std::optional<std::string> back_up_to_tell_apart() {
    const auto* in = std::get_if<domain::InPipe>(&tracker_.position());
    if (in == nullptr || tell_apart_tries_ >= kMaxTellApart) return std::nullopt;
    const localisation::Estimate belief = localising_.estimate();
    if (belief.lost()) return std::nullopt;
    const localisation::Hypothesis* other = nullptr;
    for (const localisation::Hypothesis& h : belief.hypotheses) {
      const auto* there = std::get_if<domain::InPipe>(&h.pose.position);
      if (h.probability < localising_.options().ambiguity_probability) continue;
      if (there == nullptr || there->pipe != in->pipe) {
        other = &h;
        break;
      }
    }
    if (other == nullptr) return std::nullopt;
    ++tell_apart_tries_;
    const std::string alternative = localisation::describe(other->pose, map_);
    const std::string tracked = tracker_.describe();
    // Back the way the last drive went (else away from the end the robot faces).
    const double last = tracker_.direction_of(last_job_);
    const std::uint8_t back_to = last > 0   ? 0
                                 : last < 0 ? 1
                                            : static_cast<std::uint8_t>(1 - tracker_.heading_end());
    const double distance =
        back_to == 0 ? in->offset_m : map_.pipe(in->pipe).length_m - in->offset_m;
    const double speed = mission().profile.speed_mps;
    const Job back =
        back_to == tracker_.heading_end()
            ? Job{DriveForward{.speed_mps = speed, .distance_m = distance, .to_manhole = true}}
            : Job{DriveBackward{.speed_mps = speed, .distance_m = distance, .to_manhole = true}};
    const hal::JobReport r = execute_job(back);
    mismatch_.reset();  // settled on by execute_job; planned again from there below
    if (halted() || !r.ok()) return std::nullopt;
    sync_progress(replanner_.progress());
    std::ostringstream why;
    why << "no exit from " << tracked << ", but the robot may be " << alternative
        << " (p=" << std::fixed << std::setprecision(2) << other->probability
        << "): backed up to tell, now " << tracker_.describe();
    return why.str();
  }

  // A turn the robot refused (hal::RobotErrorCause::kInvalidJob) where the tracking has it at a
  // manhole: it is at none, and the stop the filter weighed was a false detection. The tracking
  // moves to the filter's most likely place in a pipe and the plan is made again from there; the
  // reason, or empty when the filter has no such place (the failure stands: the robot is held).
  // Before, the controller rebooted the robot three times and called it stuck (AIS, world errors:
  // a false detection 0.6 m short of M2, taken for M2 at p=0.86).
  std::optional<std::string> refused_at_no_manhole(const Failure& failure, const Job& job) {
    if (failure.cause != hal::RobotErrorCause::kInvalidJob ||
        !std::holds_alternative<TurnInManhole>(job) ||
        !std::holds_alternative<domain::AtSlot>(tracker_.position())) {
      return std::nullopt;
    }
    const std::optional<localisation::Hypothesis> best = localising_.not_at_manhole();
    if (!best || !best->pose.heading_end) return std::nullopt;
    return "relocalised: the robot refused a turn (" + failure.detail + "): " + settle_on(*best);
  }

  // A blockage or danger met in a pipe other than the one the tracking has the robot in, by the
  // filter's belief (believed_elsewhere): the controller settles there and closes that pipe, not
  // the tracked one. Closing the tracked pipe cut the robot's own way back and ended missions with
  // the beacon on.
  //
  // Where the drive stopped at the far end of the tracked pipe (it went past the map's length
  // without an arrival), the robot is in that pipe longer than mapped or in the pipe beyond a
  // manhole it missed, and the filter may hold both alike: then a place beyond, held at
  // kPastEndShare or more, is taken. Closed at the tracked pipe's end, the blockage shut the way
  // back through that manhole, the robot's way out if it was beyond (AIS, the realistic world,
  // seed 3, run 16: P1 at p=0.53 against P12's end at 0.47; P12 was closed at M2, and the beacon
  // came on); closed beyond, the way back stays open under both, and the next arrival tells them
  // apart.
  void place_by_belief(Failure& failure, const Job& job) {
    if (failure.kind != Failure::Kind::kBlockage && failure.kind != Failure::Kind::kDangerInPipe)
      return;
    std::optional<localisation::Hypothesis> best = believed_elsewhere(failure.pipe);
    if (!best && at_far_end(failure, job)) best = likely_elsewhere(failure.pipe, kPastEndShare);
    if (!best) return;
    failure.detail += "; " + settle_on(*best);
    const auto& in = std::get<domain::InPipe>(best->pose.position);
    const double length = map_.pipe(in.pipe).length_m;
    failure.pipe = in.pipe;
    failure.offset_m = std::clamp(
        in.offset_m + tracker_.direction_of(job) * detail::kBlockageAhead_m, 0.0, length);
  }

  // Every passage of `manhole` into or out of the mouth `mouth` that the robot did not see, closed
  // as learnt: the blockage inside its pipe leaves the mouth itself a place to turn through, and a
  // turn into a mouth the sewer lacks is a job the robot cannot run (on the official ISYBAU sample
  // the plan turned into it, and the robot, refusing the job three times, called for recovery).
  void close_passages_into(ManholeId manhole, const Slot& mouth) {
    const Pipe& pipe = map_.pipe(mouth.pipe);
    const SlotIndex gone = pipe.ends[mouth.pipe_end].slot;
    Learnt closed;
    for (std::uint16_t s = 0; s < map_.manhole(manhole).slot_count; ++s) {
      if (s != gone.value()) closed.closed_passages.push_back({manhole, gone, SlotIndex{s}});
    }
    // Each passage names slots the map has: learn() cannot refuse them.
    (void)replanner_.learn(closed);
  }

  // The plan again from where the robot was found to be (settle()). A manhole the map lacks, in
  // the pipe a drive was driving: the robot passes straight through when a mouth goes on,
  // and `go_on` is the rest of the job it stopped (empty when it was done); else the pipe is closed
  // there, as a blockage (docs/localisation.md).
  std::optional<Replan> relocalise(const domain::PlanReplay& replay, std::optional<Job>& go_on) {
    using Kind = localisation::Verification::Kind;
    const detail::Arrival arrival = std::move(*mismatch_);
    mismatch_.reset();
    const localisation::Verification& v = arrival.verification;
    if (v.kind == Kind::kSignatureDiffers) {
      sync_progress(replay.progress());
      const Slot mouth = *detail::missing_mouth(arrival, map_, localising_.options().noise);
      close_passages_into(arrival.expected->manhole, mouth);
      // Just inside the pipe from this manhole: at its very end, the way in would stay open.
      const double length = map_.pipe(mouth.pipe).length_m;
      const double inside = std::min(10 * detail::kBlockageAhead_m, length / 2);
      return Replan{
          Failure{.kind = Failure::Kind::kBlockage,
                  .pipe = mouth.pipe,
                  .offset_m = mouth.pipe_end == 0 ? inside : length - inside,
                  .detail = "no mouth of " + map_.pipe(mouth.pipe).name + " seen: " + v.reason},
          ""};
    }
    const auto* in = std::get_if<domain::InPipe>(&v.believed->position);
    if ((v.kind == Kind::kUnmappedJunction || v.believed->at_unmapped_junction) && in != nullptr) {
      std::string why = "a manhole the map lacks: " + v.reason;
      const domain::InPipe here = *in;
      if (std::optional<TurnInManhole> through = detail::straight_through(
              arrival, map_, here.pipe, localising_.options(), mission().profile)) {
        const Job stopped = last_job_;
        const double done_m = last_progress_m_;
        const hal::JobReport r = execute_job(*through);
        if (r.ok()) {
          go_on = detail::rest_of(stopped, done_m);
          if (!arrival.forward) {
            // Through rear first: the front now leads into the pipe beyond, the way the robot was
            // backing, so it goes on forward (a backing robot closed the pipe at a junction it had
            // passed on the way in, and was shut in between it and the blockage it backed from).
            tracker_.set_pose(tracker_.position(),
                              static_cast<std::uint8_t>(1 - tracker_.heading_end()));
            if (go_on) go_on = detail::reversed(*go_on);
          }
          // A drive to a manhole goes on to it whatever the odometry says is left.
          if (go_on && !detail::ends_at_manhole(*go_on) && detail::distance_left_m(*go_on) <= 0)
            go_on.reset();
          return std::nullopt;
        }
        if (r.error->cause == hal::RobotErrorCause::kInvalidJob) {
          // Refused: the robot is at no manhole, and what it stopped at was a false detection.
          if (std::optional<localisation::Hypothesis> best = localising_.not_at_manhole();
              best && best->pose.heading_end) {
            sync_progress(replay.progress());
            return Replan{std::nullopt, "relocalised: the robot refused to pass it (" +
                                            r.error->reason + "): " + settle_on(*best)};
          }
        }
        why += "; passing it failed: " + r.error->reason;
      }
      sync_progress(replay.progress());
      // Just beyond the robot, the way it was driving: at the junction itself, the plan took the
      // robot on through it (a backing robot cannot pass a manhole), and the robot, refusing to
      // drive into the junction's shaft, called for recovery.
      double offset_m = here.offset_m;
      if (const std::optional<std::uint8_t> facing = v.believed->heading_end) {
        const std::uint8_t towards =
            arrival.forward ? *facing : static_cast<std::uint8_t>(1 - *facing);
        offset_m = std::clamp(offset_m + (towards == 1 ? 1 : -1) * detail::kBlockageAhead_m, 0.0,
                              map_.pipe(here.pipe).length_m);
      }
      return Replan{Failure{.kind = Failure::Kind::kBlockage,
                            .pipe = here.pipe,
                            .offset_m = offset_m,
                            .detail = why},
                    ""};
    }
    sync_progress(replay.progress());
    return Replan{std::nullopt, "relocalised: " + v.reason};
  }

  ArrivalEvent arrival_event(const detail::Arrival& a) const {
    const localisation::Verification& v = a.verification;
    ArrivalEvent e{.expected = a.expected ? domain::describe(*a.expected, map_) : "",
                   .check = std::string(localisation::to_string(v.kind)),
                   .probability = v.probability,
                   .reason = v.reason};
    if (v.believed) {
      e.believed = localisation::describe(*v.believed, map_);
      if (!v.believed->at_unmapped_junction) {
        if (std::optional<ManholeId> m = domain::manhole_of(v.believed->position)) {
          e.manhole = map_.manhole(*m).name;
        }
      }
    }
    if (a.observation) e.observed = detail::signature_text(*a.observation);
    return e;
  }

  // The final go-to that no plan step names (to a manhole, or to a whole pipe: the plan ends
  // there) is done when the plan has been carried out and the robot, by its own reports, is there.
  void confirm_final_task() {
    const std::optional<TaskId> t = mission().final_task_id();
    if (!t || done_[t->index()] || !at(mission().task(*t).place)) return;
    const std::string& name = mission().task(*t).name;
    report_.tasks_done.push_back(name);
    done_[t->index()] = true;
    emit(TaskDoneEvent{name});
  }

  // Whether the robot's reports put it at `place`: in the manhole or at one of its mouths; in the
  // pipe or at one of its mouths; within 1 mm of a point in a pipe.
  bool at(const Place& place) const {
    const domain::RobotPosition& here = tracker_.position();
    if (const auto* m = std::get_if<ManholeId>(&place)) return domain::manhole_of(here) == *m;
    const auto& spot = std::get<PipeSpot>(place);
    if (spot.offset_m) return agrees(here, domain::InPipe{spot.pipe, *spot.offset_m});
    if (const auto* in = std::get_if<domain::InPipe>(&here)) return in->pipe == spot.pipe;
    if (const auto* slot = std::get_if<domain::AtSlot>(&here)) {
      return map_.slot(slot->manhole, slot->slot).pipe == spot.pipe;
    }
    return false;
  }

  // Whether the position the robot's reports give agrees with the plan's. At a pipe's mouth
  // agrees with right at that pipe's end (a drive onto the end arrives at the mouth); in the pipe
  // right at its end does not agree with at the mouth.
  bool agrees(const domain::RobotPosition& tracked, const domain::RobotPosition& planned) const {
    constexpr double kToleranceM = 1e-3;
    if (tracked == planned) return true;
    const auto* in_planned = std::get_if<domain::InPipe>(&planned);
    if (in_planned == nullptr) return false;
    if (const auto* in = std::get_if<domain::InPipe>(&tracked)) {
      return in->pipe == in_planned->pipe &&
             std::abs(in->offset_m - in_planned->offset_m) <= kToleranceM;
    }
    if (const auto* at = std::get_if<domain::AtSlot>(&tracked)) {
      const Slot& slot = map_.slot(at->manhole, at->slot);
      return slot.pipe == in_planned->pipe &&
             std::abs(domain::end_offset_m(map_.pipe(slot.pipe), slot.pipe_end) -
                      in_planned->offset_m) <= kToleranceM;
    }
    return false;
  }

  // A replan reason when the plan left needs more energy than the battery has above the reserve.
  std::optional<std::string> battery_low(const std::vector<fusion::RobotAction>& actions,
                                         std::size_t from) const {
    if (from == 0) return std::nullopt;  // a fresh plan fits what the robot reported
    double seconds = 0;
    for (std::size_t i = from; i < actions.size(); ++i) seconds += fusion::duration_s(actions[i]);
    const RobotProfile& p = mission().profile;
    const double needed = p.energy_wh(seconds);
    const double available =
        robot_.status().battery_wh - p.battery_wh * mission().battery_reserve_fraction;
    if (needed <= available + 1e-9) return std::nullopt;
    std::ostringstream out;
    out << std::fixed << std::setprecision(1) << "battery low: the plan left needs " << needed
        << " Wh, " << available << " Wh are left"
        << (replanner_.on_reserve() ? " (on the reserve)" : " above the reserve");
    return out.str();
  }

  // The replay counts dropped tasks as done; the Replanner hears what the robot has really done.
  void sync_progress(domain::MissionProgress progress) {
    progress.done = done_;
    progress.position = tracker_.position();
    progress.energy_used_wh = mission().profile.battery_wh - robot_.status().battery_wh;
    // The tracker's places are on the map; a report the Replanner rejects keeps its last one.
    (void)replanner_.update(progress, tracker_.heading_end());
  }

  // Once a halt is requested, recovery goes on to no further job, reboot or event: what it then
  // makes of the run is not used (the run loop checks halted() after every job).
  static hal::JobReport halted_report() {
    return {.error = hal::RobotError{hal::RobotErrorKind::kMalfunction, "halted"}};
  }

  hal::JobReport execute_job(const Job& job) {
    if (halted()) return halted_report();
    const domain::RobotPosition before = tracker_.position();
    const double direction = tracker_.direction_of(job);
    const hal::JobReport r = robot_.execute(job);
    last_job_ = job;
    last_progress_m_ = r.progress_m;
    ++report_.jobs;
    tracker_.advance(job, r);
    emit(JobEvent{.job = detail::job_text(job), .progress_m = r.progress_m, .ok = r.ok()});
    if (!r.ok()) {
      emit(ErrorEvent{
          .kind = r.error->kind, .reason = r.error->reason, .where = tracker_.describe()});
    }
    if (std::optional<detail::Arrival> a =
            localising_.follow(job, r, before, tracker_.position(), tracker_.heading_end())) {
      if (a->worth_logging()) emit(arrival_event(*a));
      if (!a->verification.matches()) {
        settle(std::move(*a));
      } else if (a->expected && !std::holds_alternative<domain::AtSlot>(tracker_.position())) {
        tracker_.set_position(*a->expected);  // the far end, sooner than the map says
      }
    }
    observe_pass(r, before, direction);
    notify_job_observers(job, r, before, direction);
    return r;
  }

  // The pipe and offset of a position in a pipe or at a pipe's mouth.
  std::optional<std::pair<PipeId, double>> pipe_offset(const domain::RobotPosition& p) const {
    if (const auto* in = std::get_if<domain::InPipe>(&p)) return std::pair{in->pipe, in->offset_m};
    if (const auto* at = std::get_if<domain::AtSlot>(&p)) {
      const Slot& slot = map_.slot(at->manhole, at->slot);
      return std::pair{slot.pipe, domain::end_offset_m(map_.pipe(slot.pipe), slot.pipe_end)};
    }
    return std::nullopt;
  }

  // A drive (or push, or scan) from `before` to where the robot is now in the same pipe: the
  // hazards it drove past were not blocked, each update logged. A job the robot finished passed
  // every hazard on its way (Replanner::observe_pass); one it did not finish (stopped by a
  // blockage, a danger, a malfunction) passed those behind the stop, but for one within the
  // blockage match distance of it, which may be what stopped it (Replanner::observe_stop). Only
  // finished jobs counted once, and a hazard passed before a stop the robot never drove back
  // over was never counted passed: what it learnt over-counted blockages against passes.
  void observe_pass(const hal::JobReport& report, const domain::RobotPosition& before,
                    double direction) {
    if (direction == 0) return;
    const auto from = pipe_offset(before);
    const auto to = pipe_offset(tracker_.position());
    if (!from || !to || from->first != to->first) return;
    // A drive it finished went through every blockage learnt on its way (drove_through).
    if (report.ok()) (void)replanner_.drove_through(from->first, from->second, to->second);
    Result<std::vector<HazardUpdate>> updates =
        report.ok() ? replanner_.observe_pass(from->first, from->second, to->second)
                    : replanner_.observe_stop(from->first, from->second, to->second);
    if (!updates.has_value()) return;  // the tracker's places are on the map
    for (const HazardUpdate& u : *updates) log_hazard(u);
  }

  void log_hazard(const HazardUpdate& u) {
    emit(HazardEvent{.pipe = map_.pipe(u.belief.pipe).name,
                     .offset_m = u.belief.offset_m,
                     .reason = u.belief.reason,
                     .observed = u.belief.blocked ? HazardEvent::Observed::kBlocked
                                                  : HazardEvent::Observed::kPassed,
                     .probability_before = u.probability_before,
                     .probability = u.belief.probability,
                     .passes = u.belief.passes});
  }

  // The job observers see `job` with where the robot was before it and where the controller
  // has it now (after manhole verification settled it).
  void notify_job_observers(const Job& job, const hal::JobReport& report,
                            const domain::RobotPosition& before, double direction) {
    if (job_observers_.empty()) return;
    const JobSeen seen{job, report, before, tracker_.position(), direction};
    for (const JobObserver& observer : job_observers_) observer(seen);
  }

  Result<void> reboot() {
    if (halted()) return Error{ErrorCode::kCancelled, "halted"};
    return robot_.reboot();
  }

  // The robot's own report of `job`, whose report `heard` the link lost (hal::Robot::
  // recovered_report), logged as the job's; the tracking moves on from what was heard to it. A
  // turn or a drive the robot finished, tracked where the controller last heard of it, was sent
  // again from there and refused as a malfunction: two reboots later a healthy robot was stuck.
  std::optional<hal::JobReport> recovered_report(const Job& job, const hal::JobReport& heard) {
    std::optional<hal::JobReport> own = robot_.recovered_report();
    if (!own) return std::nullopt;
    hal::JobReport rest = *own;
    rest.progress_m = std::max(0.0, own->progress_m - std::max(0.0, heard.progress_m));
    const domain::RobotPosition before = tracker_.position();
    const double direction = tracker_.direction_of(job);
    tracker_.advance(job, rest);
    // The link lost part of the job: the filter starts again from the tracking's place.
    localising_.reset(tracker_.position(), tracker_.heading_end());
    notify_job_observers(job, rest, before, direction);
    emit(JobEvent{.job = detail::job_text(job), .progress_m = own->progress_m, .ok = own->ok()});
    if (!own->ok()) {
      emit(ErrorEvent{
          .kind = own->error->kind, .reason = own->error->reason, .where = tracker_.describe()});
    }
    observe_pass(rest, before, direction);
    return own;
  }

  void log_recovery(RecoveryPhase phase, bool ok) {
    if (!halted()) emit(RecoveryEvent{phase, ok});
  }

  // `end` of a halt is where the robot stopped.
  MissionReport finish(MissionReport::Outcome outcome, std::string end) {
    if (outcome == MissionReport::Outcome::kHalted) end = tracker_.describe();
    if (outcome == MissionReport::Outcome::kBeacon) {
      report_.beacon = robot_.activate_beacon();
      emit(BeaconEvent{end, report_.beacon});
    }
    // What the filter remembered of the pipes joins what the robot learnt, for the next mission
    // (Learnt::junctions); the filter started from the Replanner's, so it replaces it.
    if (localisation::JunctionMemory memory = localising_.memory(); !memory.empty()) {
      Learnt remembered;
      remembered.junctions = std::move(memory);
      (void)replanner_.learn(remembered);
    }
    const hal::RobotStatus status = robot_.status();
    const RobotProfile& p = mission().profile;
    report_.outcome = outcome;
    report_.recoveries = recovery_.cleared();
    report_.end = end;
    std::vector<bool> accounted = done_;
    for (const auto& d : replanner_.dropped()) {
      report_.dropped.emplace_back(mission().task(d.task).name, d.reason);
      accounted[d.task.index()] = true;
    }
    // Issue 30: a mission that ends with the beacon or a halt leaves tasks neither done nor
    // dropped by a plan; they are not done either, and the report counts them.
    if (outcome != MissionReport::Outcome::kEnded) {
      const std::string why = outcome == MissionReport::Outcome::kBeacon
                                  ? "not done: the robot called for recovery (" + end + ")"
                                  : "not done: the mission was halted";
      for (TaskId t : mission().task_ids()) {
        if (!accounted[t.index()]) report_.dropped.emplace_back(mission().task(t).name, why);
      }
    }
    report_.time_s = status.elapsed_s;
    report_.energy_wh = p.battery_wh - status.battery_wh;
    report_.battery_reserve_kept =
        status.battery_wh + 1e-9 >= p.battery_wh * replanner_.reserve_fraction();
    emit(MissionEndEvent{.outcome = outcome,
                         .end = end,
                         .tasks_done = report_.tasks_done,
                         .energy_wh = report_.energy_wh,
                         .replans = report_.replans,
                         .decision = report_.decision,
                         .beacon_cause = report_.beacon_cause,
                         .beacon = report_.beacon});
    for (const LogFile* log : logs_) {
      if (log->failed_appends() == 0) continue;
      report_.log_errors.push_back(*log->first_error() + " (" +
                                   std::to_string(log->failed_appends()) + " of " +
                                   std::to_string(log->appends()) + " events lost)");
    }
    return report_;
  }

  const SewerMap& map_;
  Replanner& replanner_;
  hal::Robot& robot_;
  const ExecutorOptions& options_;
  const std::vector<EventObserver>& observers_;
  const std::vector<PlanObserver>& plan_observers_;
  const std::vector<JobObserver>& job_observers_;
  const std::vector<LogFile*>& logs_;
  const std::atomic<bool>& halt_;
  detail::DeadReckoning tracker_;
  detail::Localising localising_;
  // An arrival that did not match the plan's manhole, handled after the job (relocalise()).
  std::optional<detail::Arrival> mismatch_;
  // The last job sent and how far it drove (the rest of a job stopped by a manhole the map lacks).
  Job last_job_ = Stop{};
  double last_progress_m_ = 0;
  // How often the robot backed up to tell its places apart (back_up_to_tell_apart()).
  static constexpr int kMaxTellApart = 3;
  // place_by_belief(): a place beyond the tracked pipe's end is taken when the filter holds it at
  // this share or more, the robot being at that end (within kAtEndM).
  static constexpr double kPastEndShare = 0.25;
  static constexpr double kAtEndM = 0.1;
  int tell_apart_tries_ = 0;
  detail::StagedRecovery recovery_;
  std::vector<bool> done_;  // per task: done by the robot (or before the start)
  MissionReport report_;
};

MissionReport Executor::run() { return Run(*this).go(); }

}  // namespace sewerplan::executor
