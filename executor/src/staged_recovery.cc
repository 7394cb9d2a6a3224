// SPDX-License-Identifier: MIT
// The rows of a RecoveryProfile (recovery.h), carried out for one job (staged_recovery.h).
#include "staged_recovery.h"

#include <algorithm>

#include "sewerplan/executor/recovery_clears.h"

#include "job_arithmetic.h"

namespace sewerplan::executor::detail {
namespace {

// Where an obstacle or danger is taken to be: just ahead of where the robot stopped, so that the
// robot's own position stays on its side of the blockage. No more than a millimetre: the robot
// stops short of what it meets, and a task between where it stopped and the thing itself cannot
// be reached from this side (a fault campaign found the robot replanning the same unreachable
// sample a hundred times when the margin was 5 cm).

// A recovery drive that got farther than this got past where the robot was stopped.
constexpr double kMoved_m = 0.001;

// How many reboots one job may take. A reboot that lets the robot work again (the job after it
// runs for a while before the next malfunction, or to its end) shows the fault was transient, so
// the budget bounds reboots in a row that did not help: `max_reboots` of them, and at most
// kRebootsPerJob in all, against a robot that fails after every short stretch. (It was
// `max_reboots` per job in all: one cluster of transient faults used it up and ended a mission
// with tasks left and a full battery.)
class RebootBudget {
 public:
  static constexpr int kRebootsPerJob = 20;
  explicit RebootBudget(const RecoveryProfile& profile)
      : max_in_a_row_(profile.tries(RecoveryPhase::kReboot)) {}

  // True when `failed`, a malfunction, may be rebooted through; counts the reboot.
  bool take(const hal::JobReport& failed) {
    if (total_ > 0 && (failed.duration_s > 0 || failed.progress_m > 0)) in_a_row_ = 0;
    if (in_a_row_ >= max_in_a_row_ || total_ >= kRebootsPerJob) return false;
    ++in_a_row_;
    ++total_;
    return true;
  }

 private:
  int max_in_a_row_;
  int in_a_row_ = 0;
  int total_ = 0;
};

bool is_malfunction(const hal::JobReport& r) {
  return !r.ok() && r.error->kind == hal::RobotErrorKind::kMalfunction;
}

}  // namespace

// What the blockage stages came to.
struct StagedRecovery::Cleared {
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

// What one try of a blockage row came to: the end of recovery (cleared, stuck, another error), on
// to the next row, or neither (the row is tried again while its bound allows).
struct StagedRecovery::Try {
  std::optional<Cleared> cleared;
  bool next_row = false;
  static Try ended(Cleared c) { return Try{std::move(c), false}; }
  static Try next() { return Try{std::nullopt, true}; }
  static Try again() { return Try{std::nullopt, false}; }
};

std::optional<Failure> StagedRecovery::run_job(const Job& job, const fusion::RobotAction& action) {
  Job current = job;
  RebootBudget reboots(profile_);
  hal::JobReport r = host_.execute_job(current);
  for (;;) {
    if (r.ok()) return std::nullopt;
    const hal::RobotErrorKind kind = r.error->kind;
    if (r.error->cause == hal::RobotErrorCause::kInvalidJob ||
        r.error->cause == hal::RobotErrorCause::kNotAtStart) {
      // A job the robot cannot run, or not where it is: a reboot changes neither. The run loop
      // decides (a turn refused at a manhole the robot is not at: it relocalises; a job no robot
      // could run, such as a turn with more waypoints than the CAN protocol carries: held).
      return Failure{
          .kind = Failure::Kind::kStuck, .detail = r.error->reason, .cause = r.error->cause};
    }
    if (r.error->cause == hal::RobotErrorCause::kNoMouth) {
      // A turn into a mouth the manhole does not have: a blockage of that passage that no row
      // clears (backing up, lifting the head or pushing make no mouth). The run loop closes the
      // passages into that mouth and plans again from where the robot stands, at its arrival
      // (Relocalisation::refused_into_no_mouth); held where it cannot.
      return Failure{
          .kind = Failure::Kind::kStuck, .detail = r.error->reason, .cause = r.error->cause};
    }
    if (kind == hal::RobotErrorKind::kMalfunction) {
      if (!reboots.take(r)) {
        return Failure{
            .kind = Failure::Kind::kStuck, .detail = r.error->reason, .cause = r.error->cause};
      }
      const Result<void> rebooted = host_.reboot();
      host_.log_recovery(RecoveryPhase::kReboot, rebooted.has_value());
      if (!rebooted.has_value()) {
        // The robot's words say "reboot failed: why" (hal/robot.h). Its software cannot be
        // restarted: a fault of the robot's, unless what failed is the link to it.
        const bool link = r.error->cause == hal::RobotErrorCause::kLink;
        return Failure{.kind = Failure::Kind::kStuck,
                       .detail = r.error->reason + "; " + rebooted.error().message,
                       .cause = link ? hal::RobotErrorCause::kLink : hal::RobotErrorCause::kFault};
      }
      ++cleared_;
      // The job's own report, when the link lost it: done, or its own error, handled as such;
      // a malfunction of its own is the one just rebooted through, and its rest goes on.
      if (take_recovered(current, r) && !is_malfunction(r)) continue;
      if (auto rest = rest_of(current, r.progress_m)) current = *rest;
      r = host_.execute_job(current);
      continue;
    }
    if (kind == hal::RobotErrorKind::kDanger) return danger(current, action, r);
    // Past the manhole it was driving to, unseen: backing up and retrying would only drive on
    // (2 m further each time, into the pipe beyond). Where the robot is believed elsewhere, the
    // job ends there, and the run loop plans again from that place (the tracking no longer
    // agrees with the plan's).
    if (r.error->cause == hal::RobotErrorCause::kNoManholeSeen && host_.settle_elsewhere &&
        host_.settle_elsewhere()) {
      return std::nullopt;
    }
    auto rest = rest_of(current, r.progress_m);
    if (!rest) return danger(current, action, r);  // blocked in a manhole: as a danger
    Cleared cleared = clear_blockage(*rest);
    switch (cleared.how) {
      case Cleared::How::kDone:
        ++cleared_;
        return std::nullopt;
      case Cleared::How::kOtherError:
        // The obstacle is gone, and the drive met something else on the way (a danger spot
        // beyond it, a malfunction): handled as the drive's own error.
        ++cleared_;
        current = cleared.job;
        r = cleared.report;
        continue;
      case Cleared::How::kStuck:
        // What stopped the recovery's own job (backing up, the head), as the robot typed it.
        return Failure{.kind = Failure::Kind::kStuck,
                       .detail = "recovery left the robot stuck",
                       .cause = cleared.report.error ? std::optional(cleared.report.error->cause)
                                                     : std::nullopt};
      case Cleared::How::kStays:
        break;
    }
    return blocked_here(Failure::Kind::kBlockage, current, *r.error);
  }
}

// A job of the recovery stages, rebooting through transient malfunctions (as the reboot row
// allows); its report's progress is the whole distance driven.
hal::JobReport StagedRecovery::recovery_job(const Job& job) {
  Job current = job;
  hal::JobReport r = host_.execute_job(current);
  double progress_m = r.progress_m;
  RebootBudget reboots(profile_);
  while (!r.ok() && r.error->kind == hal::RobotErrorKind::kMalfunction && reboots.take(r)) {
    const Result<void> rebooted = host_.reboot();
    host_.log_recovery(RecoveryPhase::kReboot, rebooted.has_value());
    if (!rebooted.has_value()) break;
    ++cleared_;
    const double heard_m = r.progress_m;
    if (take_recovered(current, r)) {
      progress_m += r.progress_m - heard_m;
      if (!is_malfunction(r)) break;
    }
    if (auto rest = rest_of(current, r.progress_m)) current = *rest;
    r = host_.execute_job(current);
    progress_m += r.progress_m;
  }
  r.progress_m = progress_m;
  return r;
}

bool StagedRecovery::take_recovered(const Job& job, hal::JobReport& r) {
  std::optional<hal::JobReport> own = host_.recovered_report(job, r);
  if (!own) return false;
  r = std::move(*own);
  return true;
}

// The blockage rows of the profile, in its order, each tried as often as its bound says: one
// loop over the table.
StagedRecovery::Cleared StagedRecovery::clear_blockage(Job rest) {
  for (const RecoveryStage& stage : profile_.stages) {
    if (manoeuvre(stage.phase).error != hal::RobotErrorKind::kBlockage) continue;
    for (int i = 0; i < profile_.tries(stage); ++i) {
      const Try t = try_stage(stage, rest);
      if (t.cleared) return *t.cleared;
      if (t.next_row) break;
    }
  }
  return Cleared{Cleared::How::kStays};
}

// One try of the blockage row `stage` on `rest`, the rest of the drive (shortened when the retry
// got on before it was blocked again).
StagedRecovery::Try StagedRecovery::try_stage(const RecoveryStage& stage, Job& rest) {
  // `back_m`: how far the retry drives back to where the robot met the obstacle. Blocked again
  // further on, it met another obstacle: that one gets recovery of its own.
  auto retry = [&](const Job& job, double back_m) -> Try {
    hal::JobReport r = host_.execute_job(job);
    host_.log_recovery(stage.phase, r.ok());
    if (r.ok()) return Try::ended(Cleared{Cleared::How::kDone, job, r});
    if (r.error->kind != hal::RobotErrorKind::kBlockage || r.progress_m > back_m + 0.01) {
      return Try::ended(Cleared{Cleared::How::kOtherError, job, std::move(r)});
    }
    if (auto left = rest_of(job, r.progress_m)) rest = *left;
    return Try::again();
  };
  switch (stage.phase) {
    case RecoveryPhase::kBackUpAndRetry: {
      const hal::JobReport back = recovery_job(back_off(rest, stage.distance_m));
      if (!back.ok()) {
        if (back.error->kind == hal::RobotErrorKind::kMalfunction) {
          return Try::ended(Cleared{Cleared::How::kStuck, rest, back});
        }
        return Try::next();  // no room to back up: on to the next row
      }
      return retry(lengthened(rest, back.progress_m), back.progress_m);
    }
    case RecoveryPhase::kLiftHeadAndRetry:
      for (const Job& head : {Job{LiftHead{}}, Job{LowerHead{}}}) {
        hal::JobReport moved = recovery_job(head);
        if (!moved.ok()) return Try::ended(Cleared{Cleared::How::kStuck, head, std::move(moved)});
      }
      return retry(rest, 0);
    case RecoveryPhase::kPush: {
      // The same way the drive went: backing, with the rear head (hal/obstacle_clearing.h says
      // from which sides a push works).
      const std::optional<Job> push_job = push_for(rest);
      if (!push_job || !hal::works_from(hal::Clearing::kPush, approach_of(*push_job))) {
        return Try::next();
      }
      hal::JobReport push = host_.execute_job(*push_job);
      host_.log_recovery(RecoveryPhase::kPush, push.ok());
      if (push.ok()) return Try::ended(Cleared{Cleared::How::kDone});
      // A push that got on and was stopped again moved the obstacle it met: what stopped it lies
      // further on (another obstacle, a danger spot). That is the drive's own error, with
      // recovery of its own and its own words and place, as is a malfunction; the rest of the
      // drive is driven, not pushed. (A second obstacle was reported with the first one's text,
      // issue 30.)
      if (push.error->kind != hal::RobotErrorKind::kBlockage || push.progress_m > kMoved_m) {
        return Try::ended(Cleared{Cleared::How::kOtherError, rest, std::move(push)});
      }
      return Try::again();
    }
    case RecoveryPhase::kReboot:
    case RecoveryPhase::kBackOffToSafety:
    case RecoveryPhase::kBackOutOfManhole:
      break;  // not a blockage's
  }
  return Try::next();
}

// DANGER: back off to the last safe position (the danger rows: which one by where the robot is),
// and report the spot or the passage.
std::optional<Failure> StagedRecovery::danger(const Job& job, const fusion::RobotAction& action,
                                              const hal::JobReport& r) {
  if (const auto* pass = std::get_if<fusion::PassManhole>(&action);
      pass && std::holds_alternative<TurnInManhole>(job)) {
    back_out_of_manhole();
    return Failure{.kind = Failure::Kind::kDangerousPassage,
                   .manhole = pass->manhole,
                   .from = pass->from_slot,
                   .to = pass->to_slot,
                   .detail = r.error->reason,
                   .cause = r.error->cause};
  }
  if (!rest_of(job, 0)) {
    return Failure{
        .kind = Failure::Kind::kStuck, .detail = r.error->reason, .cause = r.error->cause};
  }
  std::optional<Failure> failure = blocked_here(Failure::Kind::kDangerInPipe, job, *r.error);
  const RecoveryStage* stage = profile_.stage(RecoveryPhase::kBackOffToSafety);
  if (stage != nullptr && profile_.tries(*stage) > 0) {
    const hal::JobReport back = host_.execute_job(back_off(job, stage->distance_m));
    host_.log_recovery(RecoveryPhase::kBackOffToSafety, back.ok());
  }
  return failure;
}

// After a dangerous passage, back into the pipe the robot came by: at the pipe's mouth the plan
// model only lets it pass the manhole (and a U-turn exceeds every turn limit), so with the
// passage closed it could be trapped at the mouth; in the pipe it can drive back the way it came.
void StagedRecovery::back_out_of_manhole() {
  const RecoveryStage* stage = profile_.stage(RecoveryPhase::kBackOutOfManhole);
  const auto* at = std::get_if<domain::AtSlot>(&tracker_.position());
  if (stage == nullptr || profile_.tries(*stage) == 0 || at == nullptr) return;
  const Slot& slot = map_.slot(at->manhole, at->slot);
  const double distance = std::min(stage->distance_m, map_.pipe(slot.pipe).length_m / 2);
  if (distance <= 0) return;
  // Facing the manhole, the pipe is behind the robot; facing the pipe, ahead.
  const Job back_job = tracker_.heading_end() == slot.pipe_end
                           ? Job{DriveBackward{speed_mps_, distance}}
                           : Job{DriveForward{speed_mps_, distance}};
  const hal::JobReport back = host_.execute_job(back_job);
  host_.log_recovery(RecoveryPhase::kBackOutOfManhole, back.ok());
}

// A blockage or danger just ahead of the robot in its pipe.
Failure StagedRecovery::blocked_here(Failure::Kind kind, const Job& job,
                                     const hal::RobotError& error) const {
  const auto* in = std::get_if<domain::InPipe>(&tracker_.position());
  if (in == nullptr) {
    return Failure{.kind = Failure::Kind::kStuck, .detail = error.reason, .cause = error.cause};
  }
  const double length = map_.pipe(in->pipe).length_m;
  const double ahead = in->offset_m + tracker_.direction_of(job) * kBlockageAhead_m;
  return Failure{.kind = kind,
                 .pipe = in->pipe,
                 .offset_m = std::clamp(ahead, 0.0, length),
                 .detail = error.reason,
                 .cause = error.cause};
}

}  // namespace sewerplan::executor::detail
