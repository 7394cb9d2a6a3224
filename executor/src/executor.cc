// SPDX-License-Identifier: MIT
// The action controller: plans, actions, jobs, recovery and replanning (executor.h); what it does
// when the localisation and the tracking disagree is relocalisation.h.
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
#include "relocalisation.h"
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
        relocalisation_(
            e.map_, e.replanner_, tracker_, localising_, e.halt_,
            {.execute_job = [this](const Job& job) { return execute_job(job); },
             .run_job =
                 [this](const Job& job, const fusion::RobotAction& action) {
                   return recovery_.run_job(job, action);
                 },
             .sync_progress =
                 [this](domain::MissionProgress progress) { sync_progress(std::move(progress)); }}),
        recovery_(
            e.map_, e.options_.recovery, e.replanner_.mission().profile.speed_mps, tracker_,
            {.execute_job = [this](const Job& job) { return execute_job(job); },
             .reboot = [this] { return reboot(); },
             .recovered_report =
                 [this](const Job& job, const hal::JobReport& heard) {
                   return recovered_report(job, heard);
                 },
             .log_recovery = [this](RecoveryPhase phase, bool ok) { log_recovery(phase, ok); },
             .settle_elsewhere = [this] { return relocalisation_.settle_elsewhere(); }}),
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
        // in the belief: at a manhole's mouth with no way on through it, the robot backs into the
        // pipe it came out of; where the filter holds another place, it first backs up to the
        // manhole behind, whose arrival tells the places apart.
        std::optional<std::string> why = back_into_pipe();
        if (!why) why = relocalisation_.back_up_to_tell_apart();
        if (why) {
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
      relocalisation_.failure_reported(replan->failure);
      if (replan->failure) log_failure(*replan->failure);
      std::optional<PlanResponse> next = plan_unless_halted(replan->failure, replan->reason);
      if (!next) return finish(MissionReport::Outcome::kHalted, "");
      response = std::move(*next);
      log_plan(true, response);
    }
  }

 private:
  using Replan = detail::Replan;

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
      case hal::RobotErrorCause::kNoMouth:
      case hal::RobotErrorCause::kOtherBlockage:
      case hal::RobotErrorCause::kDangerSpot:
      case hal::RobotErrorCause::kDangerousPassage:
      case hal::RobotErrorCause::kOtherDanger:
      case hal::RobotErrorCause::kInvalidJob:
      case hal::RobotErrorCause::kNotAtStart:
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
            if (std::optional<std::string> settled =
                    relocalisation_.refused_at_no_manhole(*failure, *next)) {
              relocalisation_.clear_mismatch();
              sync_progress(replay.progress());
              return Replan{std::nullopt, *settled};
            }
            if (std::optional<Replan> closed =
                    relocalisation_.refused_into_no_mouth(*failure, action)) {
              relocalisation_.clear_mismatch();
              sync_progress(replay.progress());
              return closed;
            }
            relocalisation_.place_by_belief(*failure, *next);
          }
          next.reset();
          if (failure || halted()) {
            relocalisation_.clear_mismatch();
            sync_progress(replay.progress());
            return Replan{failure, failure ? "" : "halted"};
          }
          if (relocalisation_.has_mismatch()) {
            if (std::optional<Replan> replan = relocalisation_.relocalise(replay, next, action))
              return replan;
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
  // At a mouth of a manhole the plan cannot go on through (every passage from it beyond the
  // robot's limits or closed: a dead end it was driven into unawares, AIS in the realistic world,
  // seeds 24, 26, 38, 44, 61, 71: M7 from P6, whose way on turns 127 degrees), the robot is still
  // at the end of the pipe it came out of, and drives both ways: the plan starts there, backing
  // into that pipe. The reason to plan again, or empty (not at a mouth).
  std::optional<std::string> back_into_pipe() {
    const auto* at = std::get_if<domain::AtSlot>(&tracker_.position());
    if (at == nullptr) return std::nullopt;
    const domain::AtSlot mouth = *at;  // the tracking's place changes below
    const Slot& slot = map_.slot(mouth.manhole, mouth.slot);
    tracker_.set_pose(
        domain::InPipe{slot.pipe, domain::end_offset_m(map_.pipe(slot.pipe), slot.pipe_end)},
        slot.pipe_end);
    sync_progress(replanner_.progress());
    return "no way on through " + map_.manhole(mouth.manhole).name + " from slot " +
           std::to_string(to_paper_number(mouth.slot)) + ": the robot backs into " +
           map_.pipe(slot.pipe).name;
  }

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
    relocalisation_.job_sent(job, r.progress_m, r.ok());
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
        relocalisation_.settle(std::move(*a));
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
  // Settles the tracking where the filter finds the robot, and plans again from there.
  detail::Relocalisation relocalisation_;
  detail::StagedRecovery recovery_;
  std::vector<bool> done_;  // per task: done by the robot (or before the start)
  MissionReport report_;
};

MissionReport Executor::run() { return Run(*this).go(); }

}  // namespace sewerplan::executor
