// SPDX-License-Identifier: MIT
// Relocalisation: what the action controller does when the localisation filter and the tracking
// disagree about where the robot is.
//
// Private to executor. The controller tracks the robot by the plan and the jobs' reports
// (DeadReckoning); Localising feeds the same jobs to the topological filter and checks every
// arrival at a manhole (localising.h). Relocalisation acts on what those two say together: an
// arrival that does not match moves the tracking to the filter's most likely place (settle()) and
// makes the run loop plan again from there after the job (relocalise()), passing straight through
// a manhole the map lacks or closing the mouth a manhole was seen without; a failure the robot
// met in a pipe the filter believes it is not in is placed where it believes it (place_by_belief(),
// refused_at_no_manhole()); a turn refused into a mouth the manhole lacks closes that mouth
// (refused_into_no_mouth()); a robot with no exit from the tracked place but another likely place
// backs up to the manhole behind to tell them apart (back_up_to_tell_apart()). What it changes it
// tells the Replanner (drove_through, learn) and, through its host, the run loop (docs/
// localisation.md, "In the action controller").
//
//   Relocalisation relocalisation(map, replanner, tracker, localising, halt, host);
//   relocalisation.job_sent(job, report.progress_m);   // every job the robot ran
//   if (!arrival.verification.matches()) relocalisation.settle(std::move(arrival));
//   if (relocalisation.has_mismatch()) replan = relocalisation.relocalise(replay, go_on, action);
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <utility>

#include "sewerplan/core/job.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/robot_state.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/executor/replanner.h"
#include "sewerplan/fusion/robot_action.h"
#include "sewerplan/hal/robot.h"
#include "sewerplan/localisation/topological_filter.h"

#include "dead_reckoning.h"
#include "localising.h"

namespace sewerplan::executor::detail {

// Why the run loop plans again: a failure for the Replanner, or (without one) the reason of a plan
// from where the robot is.
struct Replan {
  std::optional<Failure> failure;
  std::string reason;
};

// What relocalisation needs from the run loop: a job sent, logged and tracked (its arrival checked
// and settled on: Relocalisation::settle()); the same with the recovery table's stages, as a job of
// `action` (StagedRecovery::run_job: a malfunction rebooted through), empty when it was done; the
// Replanner told the progress from where the tracking has the robot.
struct RelocalisationHost {
  std::function<hal::JobReport(const Job&)> execute_job;
  std::function<std::optional<Failure>(const Job&, const fusion::RobotAction& action)> run_job;
  std::function<void(domain::MissionProgress)> sync_progress;
};

class Relocalisation {
 public:
  // All must outlive this object; `halt` is the run's halt flag (no further job once it is set).
  Relocalisation(const SewerMap& map, Replanner& replanner, DeadReckoning& tracker,
                 Localising& localising, const std::atomic<bool>& halt, RelocalisationHost host)
      : map_(map),
        replanner_(replanner),
        tracker_(tracker),
        localising_(localising),
        halt_(halt),
        host_(std::move(host)) {}

  // The robot ran `job` and drove `progress_m` of it: the rest of a job stopped by a manhole the
  // map lacks goes on from there (relocalise()); a drive back goes the way it came.
  void job_sent(const Job& job, double progress_m, bool ok) {
    // A job straight after a failed one, the other way, is recovery's step back (backing off a
    // danger, backing up to retry), not the way the robot came.
    const bool steps_back =
        !last_ok_ && tracker_.direction_of(job) * tracker_.direction_of(last_job_) < 0;
    if (!steps_back) way_job_ = job;
    last_ok_ = ok;
    last_job_ = job;
    last_progress_m_ = progress_m;
    drove_since_failure(job, progress_m);
  }

  // The run loop reports `failure` to the Replanner (or, empty, plans again for another reason):
  // a blockage or danger in a pipe is remembered with where it was placed, and the robot's drives
  // from there are counted, until it passes or turns through a manhole. When the next arrival
  // relocalises the robot to a mouth of another pipe, the failure was in that pipe, as far from
  // the mouth as the robot drove (Replanner::move_learnt).
  void failure_reported(const std::optional<Failure>& failure);

  // An arrival that does not match the plan's manhole: the controller settles on the filter's
  // most likely place at once (so that what observes the job sees it there), and the plan is
  // made again after the job (relocalise()). At the manhole the odometry expected but unlike its
  // map (signature-differs): a discrepancy of the map, the plan goes on. Lost: the filter starts
  // again from the tracking's place.
  void settle(Arrival arrival);

  // Whether an arrival was settled on since the last relocalise() (or clear_mismatch()): the plan
  // is to be made again from there.
  bool has_mismatch() const { return mismatch_.has_value(); }
  // The run loop plans again for another reason (a failure): the settled arrival needs no plan of
  // its own.
  void clear_mismatch() { mismatch_.reset(); }

  // The plan again from where the robot was found to be (settle()). A manhole the map lacks, in
  // the pipe a drive was driving: the robot passes straight through when a mouth goes on,
  // and `go_on` is the rest of the job it stopped (empty when it was done); else the pipe is closed
  // there, as a blockage (docs/localisation.md). The pass is a job of `action` (the one the
  // stopped job was of), with its recovery: a malfunction during it is rebooted through, and one
  // recovery cannot clear ends the mission as it would in any job, not as a closed pipe (AIS,
  // realistic world, seed 42, run 118: a transient malfunction while backing out through a
  // junction closed the robot's way home). Precondition: has_mismatch().
  std::optional<Replan> relocalise(const domain::PlanReplay& replay, std::optional<Job>& go_on,
                                   const fusion::RobotAction& action);

  // A drive to a manhole that saw none within its bound: where the filter believes the robot in
  // another pipe (it drove through the manhole unseen), the tracking moves there, and the plan is
  // made again from there (StagedRecovery). Retrying drove the robot on, 2 m at a time, away from
  // the manhole it missed, and the pipe beyond was then closed as blocked, often the robot's way
  // home.
  bool settle_elsewhere();

  // No exit is reachable from where the tracking has the robot (in a pipe), but the filter holds
  // another place for it, in another pipe, at kTellApartFloor or more (a manhole driven
  // through unseen, or a pipe longer than mapped: on the meshed network, seed 2, run 20, a robot
  // past a manhole it missed met an obstacle, the tracked pipe was closed at its end, and the
  // beacon came on with an exit a few metres behind it). The robot drives back the way it came, to
  // the manhole behind; the arrival there is checked, and the tracking settles on what the filter
  // finds. The reason to plan again, or empty: no other place, not in a pipe, tried
  // kMaxTellApart times already, or the drive back failed.
  std::optional<std::string> back_up_to_tell_apart();

  // A turn the robot refused as not at its start (hal::RobotErrorCause::kNotAtStart) where the
  // tracking has it at a manhole: it is at none, and the stop the filter weighed was a false
  // detection. The tracking moves to the filter's most likely place in a pipe and the plan is made
  // again from there; the reason, or empty when the filter has no such place (the failure stands:
  // the robot is held). Before, the controller rebooted the robot three times and called it stuck
  // (AIS, world errors: a false detection 0.6 m short of M2, taken for M2 at p=0.86).
  std::optional<std::string> refused_at_no_manhole(const Failure& failure, const Job& job);

  // A turn the robot refused into a mouth the manhole does not have
  // (hal::RobotErrorCause::kNoMouth, on `action`, a pass of the manhole where the tracking has the
  // robot at its arrival mouth): the way through that mouth does not exist in the sewer (a lateral
  // the map has and the sewer lacks, a manhole of another type). Every passage into that mouth is
  // closed as learnt, and its pipe just inside it, as when an arrival showed the mouth missing
  // (relocalise()); the plan is made again from where the robot stands, and the failure's detail
  // begins "no mouth of P in M". Empty for any other failure (it stands). Before, the refusal was a
  // job no robot could run (invalid-job): the robot was held and the beacon called `stuck` (the
  // official ISYBAU sample, docs/campaign.md, run 8); earlier still it was relocalised into its
  // pipe, where it was not.
  std::optional<Replan> refused_into_no_mouth(const Failure& failure,
                                              const fusion::RobotAction& action);

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
  void place_by_belief(Failure& failure, const Job& job);

 private:
  // The robot, settled in its pipe, drove in through the mouth behind it during `job`: the
  // blockages learnt on that stretch are gone (Replanner::drove_through).
  void drove_in_behind(const Job& job);
  // The filter's place for the robot when it believes it in another pipe than `tracked` (a
  // manhole driven through unseen, with no arrival since to settle on): the most likely place holds
  // a majority, and at least twice what every place in the tracked pipe holds together.
  std::optional<localisation::Hypothesis> believed_elsewhere(PipeId tracked) const;
  // The filter's most likely place in a pipe other than `tracked` (not at a junction), when it
  // holds at least `share`.
  std::optional<localisation::Hypothesis> likely_elsewhere(PipeId tracked, double share) const;
  // Whether `failure` (in a pipe) is placed at the end of its pipe that `job` drove towards: the
  // place it stopped, not where the robot is now (a danger's recovery backs off first).
  bool at_far_end(const Failure& failure, const Job& job) const;
  // Moves the tracking to `believed`; what it was, for the record.
  std::string settle_on(const localisation::Hypothesis& believed);
  // A blockage or danger spot learnt in `pipe` behind `offset_m` for a robot driving `direction`
  // (+1: towards the pipe's ends[1]): the first a robot that came in at the end behind it met.
  // The belief can settle a robot that drove through a manhole unseen beyond what it met before
  // (the meshed 1,000-manhole network, seed 4, run 19: a danger learnt at 14.59 m, met again from
  // the other end, the odometry short by 1.3 m: shut in between the two, the beacon came on).
  // Only within kMetAgainM of the place (the odometry's error over a few pipes), and not at the
  // pipe's end it came in by.
  std::optional<double> learnt_behind(PipeId pipe, double offset_m, double direction) const;
  static constexpr double kMetAgainM = 2.0;
  // Every passage of `manhole` into or out of the mouth `mouth` that the robot did not see, closed
  // as learnt: the blockage inside its pipe leaves the mouth itself a place to turn through, and a
  // turn into a mouth the sewer lacks is a job the robot cannot run (on the official ISYBAU sample
  // the plan turned into it, and the robot, refusing the job three times, called for recovery).
  void close_passages_into(ManholeId manhole, const Slot& mouth);
  // close_passages_into(), and the mouth's pipe closed just inside it: the failure to plan again
  // with, `detail` its words, `cause` the robot's (empty when the controller found it itself).
  Replan close_mouth(ManholeId manhole, const Slot& mouth, std::string detail,
                     std::optional<hal::RobotErrorCause> cause);

  const Mission& mission() const { return replanner_.mission(); }
  bool halted() const { return halt_.load(); }
  hal::JobReport execute_job(const Job& job) { return host_.execute_job(job); }
  void sync_progress(domain::MissionProgress progress) { host_.sync_progress(std::move(progress)); }

  const SewerMap& map_;
  Replanner& replanner_;
  DeadReckoning& tracker_;
  Localising& localising_;
  const std::atomic<bool>& halt_;
  RelocalisationHost host_;
  // An arrival that did not match the plan's manhole, handled after the job (relocalise()).
  std::optional<Arrival> mismatch_;
  // The last job sent and how far it drove (the rest of a job stopped by a manhole the map lacks).
  Job last_job_ = Stop{};
  bool last_ok_ = true;
  // The last job that was not recovery's step back (job_sent()): its direction is the way the
  // robot came, for back_up_to_tell_apart().
  Job way_job_ = Stop{};
  double last_progress_m_ = 0;
  // failure_reported(): the last failure placed in a pipe, and the robot's drives since (front
  // first positive), while it stays in one pipe by its own account.
  struct Placed {
    Failure::Kind kind = Failure::Kind::kBlockage;  // or kDangerInPipe
    Blockage at;
    double driven_m = 0;     // net, front first positive
    double travelled_m = 0;  // every metre, either way
  };
  // move_refuted_failure(): the drives since the failure went one way, but for this much.
  static constexpr double kOneWaySlackM = 0.5;
  std::optional<Placed> placed_;
  void drove_since_failure(const Job& job, double progress_m);
  // The arrival `believed` (a mouth) refutes where the remembered failure was placed: it moves
  // into the mouth's pipe; the words for the plan's reason, or empty.
  void move_refuted_failure(const domain::RobotPosition& believed);
  // How often the robot backed up to tell its places apart (back_up_to_tell_apart()).
  static constexpr int kMaxTellApart = 3;
  // The least probability of another place that back_up_to_tell_apart() goes to look at. Not the
  // filter's ambiguity_probability (0.05): the other choice is the beacon, with the robot left in
  // the sewer, so even an unlikely place is worth a drive back (the meshed 1,000-manhole network,
  // seed 6, run 16: a danger met 1.8 m past a manhole driven through unseen, the filter holding
  // that place at p=0.011 and the robot's, short of the manhole, shut in by a blockage behind it).
  static constexpr double kTellApartFloor = 0.001;
  // place_by_belief(): a place beyond the tracked pipe's end is taken when the filter holds it at
  // this share or more, the robot being at that end (within kAtEndM).
  static constexpr double kPastEndShare = 0.25;
  static constexpr double kAtEndM = 0.1;
  int tell_apart_tries_ = 0;
};

}  // namespace sewerplan::executor::detail
