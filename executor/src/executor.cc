// SPDX-License-Identifier: MIT
// The action controller: plans, actions, jobs, recovery and replanning (executor.h).
#include "sewerplan/executor/executor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>

#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/fusion/action_text.h"
#include "sewerplan/fusion/jobs.h"
#include "sewerplan/fusion/robot_action.h"

#include "dead_reckoning.h"
#include "job_arithmetic.h"
#include "staged_recovery.h"

namespace sewerplan::executor {
namespace {

std::vector<std::string> task_names(const Mission& mission, const std::vector<TaskId>& tasks) {
  std::vector<std::string> names;
  for (TaskId t : tasks) names.push_back(mission.task(t).name);
  return names;
}

}  // namespace

namespace {

constexpr std::array<std::pair<MissionReport::BeaconCause, std::string_view>, 6> kBeaconCauses{{
    {MissionReport::BeaconCause::kNone, "none"},
    {MissionReport::BeaconCause::kNoExit, "no-exit"},
    {MissionReport::BeaconCause::kStuck, "stuck"},
    {MissionReport::BeaconCause::kMalfunction, "malfunction"},
    {MissionReport::BeaconCause::kLink, "link"},
    {MissionReport::BeaconCause::kLimit, "limit"},
}};

}  // namespace

std::string_view to_string(MissionReport::BeaconCause cause) {
  for (const auto& [c, name] : kBeaconCauses) {
    if (c == cause) return name;
  }
  return "none";
}

std::optional<MissionReport::BeaconCause> parse_beacon_cause(std::string_view name) {
  for (const auto& [c, n] : kBeaconCauses) {
    if (n == name) return c;
  }
  return std::nullopt;
}

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
    os << std::setprecision(1) << " (planning";
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
        recovery_(
            e.map_, e.options_.recovery, e.replanner_.mission().profile.speed_mps, tracker_,
            {.execute_job = [this](const Job& job) { return execute_job(job); },
             .reboot = [this] { return robot_.reboot(); },
             .log_recovery = [this](std::string_view phase, bool ok) { log_recovery(phase, ok); }}),
        done_(e.replanner_.progress().done) {}

  MissionReport go() {
    PlanResponse response = replanner_.plan("start");
    log_plan("plan", response);
    std::optional<Failure> last_failure;
    for (;;) {
      report_.decision = response.decision;
      if (!has_plan(response.decision)) {
        report_.beacon_cause = beacon_cause(response.decision, last_failure);
        return finish(MissionReport::Outcome::kBeacon, response.reason);
      }
      if (auto invalid = check(response)) {
        report_.beacon_cause = MissionReport::BeaconCause::kLimit;
        return finish(MissionReport::Outcome::kBeacon, "the plan is not valid: " + *invalid);
      }
      std::optional<Replan> replan = execute(response);
      if (!replan) return finish(MissionReport::Outcome::kEnded, response.end);
      if (report_.replans >= options_.max_replans) {
        report_.beacon_cause = MissionReport::BeaconCause::kLimit;
        return finish(MissionReport::Outcome::kBeacon,
                      "gave up after " + std::to_string(report_.replans) + " replans");
      }
      ++report_.replans;
      last_failure = replan->failure;
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

  // Why the Replanner's answer switches the beacon on: a proof that no exit can be reached, or a
  // robot that cannot move, by what stopped it (the robot's words in the last failure).
  static MissionReport::BeaconCause beacon_cause(PlanResponse::Decision decision,
                                                 const std::optional<Failure>& failure) {
    using Cause = MissionReport::BeaconCause;
    if (decision == PlanResponse::Decision::kCallForRecovery) return Cause::kNoExit;
    if (decision != PlanResponse::Decision::kStuck) return Cause::kLimit;
    const std::string detail = failure ? failure->detail : "";
    if (detail.find("CAN link") != std::string::npos) return Cause::kLink;
    if (detail.find("malfunction") != std::string::npos ||
        detail.find("reboot failed") != std::string::npos ||
        detail.find("battery empty") != std::string::npos) {
      return Cause::kMalfunction;
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
                {"parameters", fusion::describe(action, map_, mission())}});
      for (const Job& job : jobs_for(action)) {
        if (auto failure = recovery_.run_job(job, action)) {
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
      if (!agrees(tracker_.position(), replay.position())) {
        // The robot is not where the plan puts it: plan again from where it really is, rather than
        // carry on (or report the mission ended at an exit) on the plan's word.
        sync_progress(replay.progress());
        return Replan{std::nullopt, "the robot is " + tracker_.describe() + ", the plan has it " +
                                        domain::describe(replay.position(), map_)};
      }
      tracker_.set_position(replay.position());
      sync_progress(replay.progress());
    }
    return std::nullopt;
  }

  // The jobs for an action. A drive to a manhole of 0 m has none (fusion drops it), but the robot
  // right at the pipe's end, as a pass into the pipe leaves it, must still drive onto the mouth.
  std::vector<Job> jobs_for(const fusion::RobotAction& action) const {
    std::vector<Job> jobs = fusion::expand(action, mission().profile);
    const auto* drive = std::get_if<fusion::DriveToManhole>(&action);
    if (!jobs.empty() || drive == nullptr ||
        !std::holds_alternative<domain::InPipe>(tracker_.position())) {
      return jobs;
    }
    if (drive->direction == fusion::Direction::kForward) {
      jobs.emplace_back(DriveForward{.speed_mps = drive->speed_mps, .distance_m = 0});
    } else {
      jobs.emplace_back(DriveBackward{.speed_mps = drive->speed_mps, .distance_m = 0});
    }
    return jobs;
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
        {"job", detail::job_text(job)}, {"progress_m", r.progress_m}, {"ok", r.ok()}};
    log_.add(now(), "job", std::move(fields));
    if (!r.ok()) {
      log_.add(now(), "error",
               {{"kind", std::string(hal::to_string(r.error->kind))},
                {"reason", r.error->reason},
                {"where", tracker_.describe()}});
    }
    return r;
  }

  void log_recovery(std::string_view phase, bool ok) {
    log_.add(now(), "recovery", {{"phase", std::string(phase)}, {"ok", ok}});
  }

  MissionReport finish(MissionReport::Outcome outcome, const std::string& end) {
    if (outcome == MissionReport::Outcome::kBeacon) {
      robot_.activate_beacon();
      log_.add(now(), "beacon", {{"reason", end}});
    }
    const hal::RobotStatus status = robot_.status();
    const RobotProfile& p = mission().profile;
    report_.outcome = outcome;
    report_.recoveries = recovery_.cleared();
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
         {"replans", static_cast<std::int64_t>(report_.replans)},
         {"decision", std::string(to_string(report_.decision))},
         {"beacon_cause", std::string(to_string(report_.beacon_cause))}});
    return report_;
  }

  const SewerMap& map_;
  Replanner& replanner_;
  hal::Robot& robot_;
  const ExecutorOptions& options_;
  EventLog& log_;
  detail::DeadReckoning tracker_;
  detail::StagedRecovery recovery_;
  std::vector<bool> done_;  // per task: done by the robot (or before the start)
  MissionReport report_;
};

MissionReport Executor::run() { return Run(*this).go(); }

}  // namespace sewerplan::executor
