// SPDX-License-Identifier: MIT
// The action controller: plans, actions, jobs, recovery and replanning (executor.h).
#include "sewerplan/executor/executor.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>

#include "sewerplan/core/overloaded.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/fusion/jobs.h"
#include "sewerplan/fusion/robot_action.h"

#include "dead_reckoning.h"

namespace sewerplan::executor {
namespace {

// Where an obstacle or danger is taken to be: just ahead of where the robot stopped, so that the
// robot's own position stays on its side of the blockage. No more than a millimetre: the robot
// stops short of what it meets, and a task between where it stopped and the thing itself cannot
// be reached from this side (a fault campaign found the robot replanning the same unreachable
// sample a hundred times when the margin was 5 cm).
constexpr double kAhead_m = 0.001;

std::string job_text(const Job& job) {
  std::ostringstream out;
  out << job;
  return out.str();
}

// The rest of a drive after `done_m`, or nothing for a job that is not a drive.
std::optional<Job> rest_of(const Job& job, double done_m) {
  return std::visit(
      Overloaded{[&](const DriveForward& j) -> std::optional<Job> {
                   return DriveForward{j.speed_mps, std::max(0.0, j.distance_m - done_m)};
                 },
                 [&](const DriveBackward& j) -> std::optional<Job> {
                   return DriveBackward{j.speed_mps, std::max(0.0, j.distance_m - done_m)};
                 },
                 [&](const Push& j) -> std::optional<Job> {
                   return Push{j.speed_mps, std::max(0.0, j.distance_m - done_m)};
                 },
                 [&](const Scan& j) -> std::optional<Job> {
                   return Scan{j.speed_mps, std::max(0.0, j.distance_m - done_m), j.backward};
                 },
                 [](const auto&) -> std::optional<Job> { return std::nullopt; }},
      job);
}

// The same drive, `extra_m` longer (after backing up that far).
Job lengthened(const Job& job, double extra_m) {
  return std::visit(
      [&](auto j) -> Job {
        if constexpr (requires { j.distance_m; }) j.distance_m += extra_m;
        return j;
      },
      job);
}

// A drive of `distance_m` the other way, at the job's speed.
Job back_off(const Job& job, double distance_m) {
  return std::visit(Overloaded{[&](const DriveBackward& j) -> Job {
                                 return DriveForward{j.speed_mps, distance_m};
                               },
                               [&](const Scan& j) -> Job {
                                 if (j.backward) return DriveForward{j.speed_mps, distance_m};
                                 return DriveBackward{j.speed_mps, distance_m};
                               },
                               [&](const auto& j) -> Job {
                                 if constexpr (requires { j.speed_mps; }) {
                                   return DriveBackward{j.speed_mps, distance_m};
                                 }
                                 return DriveBackward{0.1, distance_m};
                               }},
                    job);
}

std::string action_text(const fusion::RobotAction& action) {
  std::ostringstream out;
  out << action;
  return out.str();
}

// A push over the rest of a forward drive; none for a backward one (the robot pushes with its
// head).
std::optional<Job> push_for(const Job& job) {
  if (const auto* d = std::get_if<DriveForward>(&job)) return Push{d->speed_mps, d->distance_m};
  if (const auto* p = std::get_if<Push>(&job)) return *p;
  if (const auto* s = std::get_if<Scan>(&job); s && !s->backward) {
    return Push{s->speed_mps, s->distance_m};
  }
  return std::nullopt;
}

std::vector<std::string> task_names(const Mission& mission, const std::vector<TaskId>& tasks) {
  std::vector<std::string> names;
  for (TaskId t : tasks) names.push_back(mission.task(t).name);
  return names;
}

}  // namespace

std::ostream& operator<<(std::ostream& os, const MissionReport& r) {
  os << std::fixed << std::setprecision(1);
  os << (r.outcome == MissionReport::Outcome::kEnded ? "mission ended at " : "beacon on: ") << r.end
     << '\n';
  os << "tasks done: " << r.tasks_done.size();
  for (std::size_t i = 0; i < r.tasks_done.size(); ++i) {
    os << (i == 0 ? " (" : ", ") << r.tasks_done[i] << (i + 1 == r.tasks_done.size() ? ")" : "");
  }
  os << "\ntasks dropped: " << r.dropped.size() << '\n';
  for (const auto& [task, reason] : r.dropped) os << "  - " << task << ": " << reason << '\n';
  os << "time " << r.time_s << " s, energy " << r.energy_wh << " Wh, " << r.jobs << " jobs, "
     << r.recoveries << " errors cleared by recovery, " << r.replans << " replans";
  if (!r.planning_times_s.empty()) {
    os << std::setprecision(3) << " (planning";
    for (double t : r.planning_times_s) os << ' ' << t * 1000 << " ms";
    os << ')';
  }
  os << "\nbattery reserve " << (r.battery_reserve_kept ? "kept" : "NOT kept") << '\n';
  return os;
}

Executor::Executor(const SewerMap& map, Replanner& replanner, hal::Robot& robot,
                   ExecutorOptions options, EventLog& log)
    : map_(map), replanner_(replanner), robot_(robot), options_(options), log_(log) {}

class Executor::Run {
 public:
  explicit Run(Executor& e)
      : map_(e.map_),
        replanner_(e.replanner_),
        robot_(e.robot_),
        options_(e.options_),
        log_(e.log_),
        tracker_(e.map_, e.replanner_.progress().position, e.replanner_.heading_end()),
        done_(e.replanner_.progress().done) {}

  MissionReport go() {
    PlanResponse response = replanner_.plan("start");
    log_plan("plan", response);
    for (;;) {
      if (!has_plan(response.decision)) {
        return finish(MissionReport::Outcome::kBeacon, response.reason);
      }
      if (auto invalid = check(response)) {
        return finish(MissionReport::Outcome::kBeacon, "the plan is not valid: " + *invalid);
      }
      std::optional<Replan> replan = execute(response);
      if (!replan) return finish(MissionReport::Outcome::kEnded, response.end);
      if (report_.replans >= options_.max_replans) {
        return finish(MissionReport::Outcome::kBeacon,
                      "gave up after " + std::to_string(report_.replans) + " replans");
      }
      ++report_.replans;
      if (replan->failure) log_failure(*replan->failure);
      response = replan->failure ? replanner_.report_failure(*replan->failure)
                                 : replanner_.plan(replan->reason);
      log_plan("replan", response);
    }
  }

 private:
  struct Replan {
    std::optional<Failure> failure;
    std::string reason;
  };

  double now() const { return robot_.status().elapsed_s; }
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

  void log_plan(const char* type, const PlanResponse& r) {
    std::vector<std::string> dropped;
    for (const auto& d : r.newly_dropped) {
      dropped.push_back(mission().task(d.task).name);
      log_.add(now(), "task_dropped",
               {{"task", mission().task(d.task).name}, {"reason", d.reason}});
    }
    report_.planning_times_s.push_back(r.planning_time_s);
    log_.add(now(), type,
             {{"reason", r.reason},
              {"planning_ms", r.planning_time_s * 1000},
              {"decision", std::string(to_string(r.decision))},
              {"goals", task_names(mission(), r.goals)},
              {"dropped", dropped},
              {"end", r.end},
              {"steps", static_cast<std::int64_t>(r.plan.steps.size())},
              {"cost_s", r.cost_s}});
  }

  // What the Replanner is told: a blocked pipe, a closed passage, or a robot that cannot move.
  void log_failure(const Failure& f) {
    std::vector<std::pair<std::string, EventValue>> fields{
        {"kind", std::string(to_string(f.kind))}};
    if (f.kind == Failure::Kind::kBlockage || f.kind == Failure::Kind::kDangerInPipe) {
      fields.emplace_back("pipe", map_.pipe(f.pipe).name);
      fields.emplace_back("offset_m", f.offset_m);
    } else if (f.kind == Failure::Kind::kDangerousPassage) {
      fields.emplace_back("manhole", map_.manhole(f.manhole).name);
      fields.emplace_back("from_slot", static_cast<std::int64_t>(to_paper_number(f.from)));
      fields.emplace_back("to_slot", static_cast<std::int64_t>(to_paper_number(f.to)));
    }
    fields.emplace_back("detail", f.detail);
    log_.add(now(), "failure", std::move(fields));
  }

  // Runs the plan; empty when it was carried out to its end.
  std::optional<Replan> execute(const PlanResponse& response) {
    domain::PlanReplay replay(map_, mission(), planning_start());
    const auto& actions = response.fused.actions;
    for (std::size_t i = 0; i < actions.size(); ++i) {
      if (auto low = battery_low(actions, i)) return Replan{std::nullopt, *low};
      const fusion::RobotAction& action = actions[i];
      log_.add(now(), "action",
               {{"step", domain::format_step(response.plan.steps[fusion::plan_step(action)], map_,
                                             mission())},
                {"kind", std::string(fusion::action_kind(action))},
                {"duration_s", fusion::duration_s(action)},
                {"parameters", action_text(action)}});
      for (const Job& job : fusion::expand(action, mission().profile)) {
        if (auto failure = run_job(job, action)) {
          sync_progress(replay.progress());
          return Replan{failure, ""};
        }
      }
      const domain::PlanStep& step = response.plan.steps[fusion::plan_step(action)];
      const std::vector<bool> before = replay.done();
      if (!replay.apply(step).has_value()) {
        return Replan{Failure{.kind = Failure::Kind::kStuck, .detail = "plan and robot disagree"},
                      ""};
      }
      for (TaskId t : mission().task_ids()) {
        if (!before[t.index()] && replay.done()[t.index()]) {
          report_.tasks_done.push_back(mission().task(t).name);
          done_[t.index()] = true;
          log_.add(now(), "task_done", {{"task", mission().task(t).name}});
        }
      }
      tracker_.set_position(replay.position());
      sync_progress(replay.progress());
    }
    return std::nullopt;
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
        << " Wh, " << available << " Wh are left above the reserve";
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

  hal::JobReport execute_job(const Job& job) {
    const hal::JobReport r = robot_.execute(job);
    ++report_.jobs;
    tracker_.advance(job, r);
    std::vector<std::pair<std::string, EventValue>> fields{
        {"job", job_text(job)}, {"progress_m", r.progress_m}, {"ok", r.ok()}};
    log_.add(now(), "job", std::move(fields));
    if (!r.ok()) {
      log_.add(now(), "error",
               {{"kind", std::string(hal::to_string(r.error->kind))},
                {"reason", r.error->reason},
                {"where", tracker_.describe()}});
    }
    return r;
  }

  void log_recovery(const std::string& phase, bool ok) {
    log_.add(now(), "recovery", {{"phase", phase}, {"ok", ok}});
  }

  // Runs one job with staged recovery; a failure for the Replanner when recovery fails.
  std::optional<Failure> run_job(const Job& job, const fusion::RobotAction& action) {
    Job current = job;
    int reboots = 0;
    hal::JobReport r = execute_job(current);
    for (;;) {
      if (r.ok()) return std::nullopt;
      const hal::RobotErrorKind kind = r.error->kind;
      if (kind == hal::RobotErrorKind::kMalfunction) {
        if (reboots >= options_.recovery.max_reboots) {
          return Failure{.kind = Failure::Kind::kStuck, .detail = r.error->reason};
        }
        ++reboots;
        const Result<void> rebooted = robot_.reboot();
        log_recovery("reboot", rebooted.has_value());
        if (!rebooted.has_value()) {
          return Failure{
              .kind = Failure::Kind::kStuck,
              .detail = r.error->reason + "; reboot failed: " + rebooted.error().message};
        }
        ++report_.recoveries;
        if (auto rest = rest_of(current, r.progress_m)) current = *rest;
        r = execute_job(current);
        continue;
      }
      if (kind == hal::RobotErrorKind::kDanger) return danger(current, action, r);
      auto rest = rest_of(current, r.progress_m);
      if (!rest) return danger(current, action, r);  // blocked in a manhole: as a danger
      Cleared cleared = clear_blockage(*rest);
      switch (cleared.how) {
        case Cleared::How::kDone:
          ++report_.recoveries;
          return std::nullopt;
        case Cleared::How::kOtherError:
          // The obstacle is gone, and the drive met something else on the way (a danger spot
          // beyond it, a malfunction): handled as the drive's own error.
          ++report_.recoveries;
          current = cleared.job;
          r = cleared.report;
          continue;
        case Cleared::How::kStuck:
          return Failure{.kind = Failure::Kind::kStuck, .detail = "recovery left the robot stuck"};
        case Cleared::How::kStays:
          break;
      }
      return blocked_here(Failure::Kind::kBlockage, current, r.error->reason);
    }
  }

  // A job of the recovery phases, rebooting through transient malfunctions (at most max_reboots
  // times); its report's progress is the whole distance driven.
  hal::JobReport recovery_job(const Job& job) {
    Job current = job;
    hal::JobReport r = execute_job(current);
    double progress_m = r.progress_m;
    for (int reboots = 0; !r.ok() && r.error->kind == hal::RobotErrorKind::kMalfunction &&
                          reboots < options_.recovery.max_reboots;
         ++reboots) {
      const Result<void> rebooted = robot_.reboot();
      log_recovery("reboot", rebooted.has_value());
      if (!rebooted.has_value()) break;
      ++report_.recoveries;
      if (auto rest = rest_of(current, r.progress_m)) current = *rest;
      r = execute_job(current);
      progress_m += r.progress_m;
    }
    r.progress_m = progress_m;
    return r;
  }

  // What the blockage phases came to.
  struct Cleared {
    enum class How {
      kDone,        // cleared, and the drive finished
      kStays,       // the obstacle stays
      kOtherError,  // cleared, and the drive (job) met another error (report) further on
      kStuck,       // backing up or moving the head failed
    };
    How how = How::kStays;
    Job job{};
    hal::JobReport report;
  };

  Cleared clear_blockage(Job rest) {
    const RecoveryConfig& c = options_.recovery;
    // `back_m`: how far the retry drives back to where the robot met the obstacle. Blocked again
    // further on, it met another obstacle: that one gets recovery of its own.
    auto retry = [&](const Job& job, const std::string& phase,
                     double back_m) -> std::optional<Cleared> {
      hal::JobReport r = execute_job(job);
      log_recovery(phase, r.ok());
      if (r.ok()) return Cleared{Cleared::How::kDone, job, r};
      if (r.error->kind != hal::RobotErrorKind::kBlockage || r.progress_m > back_m + 0.01) {
        return Cleared{Cleared::How::kOtherError, job, std::move(r)};
      }
      if (auto left = rest_of(job, r.progress_m)) rest = *left;
      return std::nullopt;
    };
    for (int i = 0; i < c.backup_retries; ++i) {
      const hal::JobReport back = recovery_job(back_off(rest, c.backup_m));
      if (!back.ok()) {
        if (back.error->kind == hal::RobotErrorKind::kMalfunction) return {Cleared::How::kStuck};
        break;  // no room to back up: on to the head
      }
      if (auto done =
              retry(lengthened(rest, back.progress_m), "1: back up and retry", back.progress_m)) {
        return *done;
      }
    }
    for (int i = 0; i < c.lift_retries; ++i) {
      if (!recovery_job(LiftHead{}).ok() || !recovery_job(LowerHead{}).ok()) {
        return Cleared{Cleared::How::kStuck};
      }
      if (auto done = retry(rest, "2: lift the head and retry", 0)) return *done;
    }
    for (int i = 0; c.push_allowed && i < c.push_retries; ++i) {
      const std::optional<Job> push_job = push_for(rest);
      if (!push_job) break;  // the robot pushes with its head only
      hal::JobReport push = execute_job(*push_job);
      log_recovery("3: push", push.ok());
      if (push.ok()) return Cleared{Cleared::How::kDone};
      if (push.error->kind != hal::RobotErrorKind::kBlockage) {
        return Cleared{Cleared::How::kOtherError, *push_job, std::move(push)};
      }
    }
    return Cleared{Cleared::How::kStays};
  }

  // DANGER: back off to the last safe position, and report the spot or the passage.
  std::optional<Failure> danger(const Job& job, const fusion::RobotAction& action,
                                const hal::JobReport& r) {
    if (const auto* pass = std::get_if<fusion::PassManhole>(&action);
        pass && std::holds_alternative<TurnInManhole>(job)) {
      back_out_of_manhole();
      return Failure{.kind = Failure::Kind::kDangerousPassage,
                     .manhole = pass->manhole,
                     .from = pass->from_slot,
                     .to = pass->to_slot,
                     .detail = r.error->reason};
    }
    if (!rest_of(job, 0)) {
      return Failure{.kind = Failure::Kind::kStuck, .detail = r.error->reason};
    }
    std::optional<Failure> failure =
        blocked_here(Failure::Kind::kDangerInPipe, job, r.error->reason);
    const hal::JobReport back = execute_job(back_off(job, options_.recovery.danger_backoff_m));
    log_recovery("back off to safety", back.ok());
    return failure;
  }

  // After a dangerous passage, back into the pipe the robot came by: at the pipe's mouth the plan
  // model only lets it pass the manhole (and a U-turn exceeds every turn limit), so with the
  // passage closed it could be trapped at the mouth; in the pipe it can drive back the way it
  // came.
  void back_out_of_manhole() {
    const auto* at = std::get_if<domain::AtSlot>(&tracker_.position());
    if (at == nullptr) return;
    const Slot& slot = map_.slot(at->manhole, at->slot);
    const double distance =
        std::min(options_.recovery.danger_backoff_m, map_.pipe(slot.pipe).length_m / 2);
    if (distance <= 0) return;
    // Facing the manhole, the pipe is behind the robot; facing the pipe, ahead.
    const double speed = mission().profile.speed_mps;
    const Job back_job = tracker_.heading_end() == slot.pipe_end
                             ? Job{DriveBackward{speed, distance}}
                             : Job{DriveForward{speed, distance}};
    const hal::JobReport back = execute_job(back_job);
    log_recovery("back out of the manhole", back.ok());
  }

  // A blockage or danger just ahead of the robot in its pipe.
  Failure blocked_here(Failure::Kind kind, const Job& job, const std::string& reason) const {
    const auto* in = std::get_if<domain::InPipe>(&tracker_.position());
    if (in == nullptr) return Failure{.kind = Failure::Kind::kStuck, .detail = reason};
    const double length = map_.pipe(in->pipe).length_m;
    const double ahead = in->offset_m + tracker_.direction_of(job) * kAhead_m;
    return Failure{.kind = kind,
                   .pipe = in->pipe,
                   .offset_m = std::clamp(ahead, 0.0, length),
                   .detail = reason};
  }

  MissionReport finish(MissionReport::Outcome outcome, const std::string& end) {
    if (outcome == MissionReport::Outcome::kBeacon) {
      robot_.activate_beacon();
      log_.add(now(), "beacon", {{"reason", end}});
    }
    const hal::RobotStatus status = robot_.status();
    const RobotProfile& p = mission().profile;
    report_.outcome = outcome;
    report_.end = end;
    for (const auto& d : replanner_.dropped()) {
      report_.dropped.emplace_back(mission().task(d.task).name, d.reason);
    }
    report_.time_s = status.elapsed_s;
    report_.energy_wh = p.battery_wh - status.battery_wh;
    report_.battery_reserve_kept =
        status.battery_wh + 1e-9 >= p.battery_wh * mission().battery_reserve_fraction;
    log_.add(
        now(), "mission_end",
        {{"outcome", std::string(outcome == MissionReport::Outcome::kEnded ? "ended" : "beacon")},
         {"end", end},
         {"tasks_done", report_.tasks_done},
         {"energy_wh", report_.energy_wh},
         {"replans", static_cast<std::int64_t>(report_.replans)}});
    return report_;
  }

  const SewerMap& map_;
  Replanner& replanner_;
  hal::Robot& robot_;
  const ExecutorOptions& options_;
  EventLog& log_;
  detail::DeadReckoning tracker_;
  std::vector<bool> done_;  // per task: done by the robot (or before the start)
  MissionReport report_;
};

MissionReport Executor::run() { return Run(*this).go(); }

}  // namespace sewerplan::executor
