// SPDX-License-Identifier: MIT
// What the action controller does when the filter and the tracking disagree (relocalisation.h).
#include "relocalisation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <sstream>
#include <variant>

#include "job_arithmetic.h"

namespace sewerplan::executor::detail {

void Relocalisation::settle(Arrival arrival) {
  using Kind = localisation::Verification::Kind;
  const localisation::Verification& v = arrival.verification;
  if (v.kind == Kind::kSignatureDiffers) {
    // The manhole the plan expected, with a mouth fewer: its pipe cannot be reached from here.
    if (missing_mouth(arrival, map_, localising_.options().noise)) mismatch_ = std::move(arrival);
    return;
  }
  if (!v.believed) {
    localising_.reset(tracker_.position(), tracker_.heading_end());
    return;
  }
  tracker_.set_pose(v.believed->position, v.believed->heading_end.value_or(tracker_.heading_end()));
  mismatch_ = std::move(arrival);
}

std::optional<Replan> Relocalisation::relocalise(const domain::PlanReplay& replay,
                                                 std::optional<Job>& go_on,
                                                 const fusion::RobotAction& action) {
  using Kind = localisation::Verification::Kind;
  const Arrival arrival = std::move(*mismatch_);
  mismatch_.reset();
  const localisation::Verification& v = arrival.verification;
  if (v.kind == Kind::kSignatureDiffers) {
    sync_progress(replay.progress());
    const Slot mouth = *missing_mouth(arrival, map_, localising_.options().noise);
    return close_mouth(arrival.expected->manhole, mouth,
                       "no mouth of " + map_.pipe(mouth.pipe).name + " seen: " + v.reason,
                       std::nullopt);
  }
  const auto* in = std::get_if<domain::InPipe>(&v.believed->position);
  if ((v.kind == Kind::kUnmappedJunction || v.believed->at_unmapped_junction) && in != nullptr) {
    std::string why = "a manhole the map lacks: " + v.reason;
    const domain::InPipe here = *in;
    if (std::optional<TurnInManhole> through =
            straight_through(arrival, map_, here.pipe, localising_.options(), mission().profile)) {
      const Job stopped = last_job_;
      const double done_m = last_progress_m_;
      const std::optional<Failure> failed = host_.run_job(*through, action);
      if (!failed) {
        go_on = rest_of(stopped, done_m);
        if (!arrival.forward) {
          // Through rear first: the front now leads into the pipe beyond, the way the robot was
          // backing, so it goes on forward (a backing robot closed the pipe at a junction it had
          // passed on the way in, and was shut in between it and the blockage it backed from).
          tracker_.set_pose(tracker_.position(),
                            static_cast<std::uint8_t>(1 - tracker_.heading_end()));
          if (go_on) go_on = reversed(*go_on);
        }
        // A drive to a manhole goes on to it whatever the odometry says is left.
        if (go_on && !ends_at_manhole(*go_on) && distance_left_m(*go_on) <= 0) go_on.reset();
        return std::nullopt;
      }
      if (failed->cause == hal::RobotErrorCause::kNotAtStart) {
        // Refused: the robot is at no manhole, and what it stopped at was a false detection.
        if (std::optional<localisation::Hypothesis> best = localising_.not_at_manhole();
            best && best->pose.heading_end) {
          sync_progress(replay.progress());
          return Replan{std::nullopt, "relocalised: the robot refused to pass it (" +
                                          failed->detail + "): " + settle_on(*best)};
        }
      }
      const auto cannot_move = [&] {
        using Cause = hal::RobotErrorCause;
        const std::optional<Cause> c = failed->cause;
        return c == Cause::kFault || c == Cause::kBatteryEmpty || c == Cause::kEmergencyStop ||
               c == Cause::kLink || c == Cause::kOtherMalfunction;
      };
      if (failed->kind == Failure::Kind::kStuck && cannot_move()) {
        // The robot cannot move (recovery could not reboot it through): no closure explains that.
        sync_progress(replay.progress());
        return Replan{failed, ""};
      }
      why += "; passing it failed: " + failed->detail;
    }
    sync_progress(replay.progress());
    // Just beyond the robot, the way it was driving: at the junction itself, the plan took the
    // robot on through it (a backing robot cannot pass a manhole), and the robot, refusing to
    // drive into the junction's shaft, called for recovery.
    double offset_m = here.offset_m;
    if (const std::optional<std::uint8_t> facing = v.believed->heading_end) {
      const std::uint8_t towards =
          arrival.forward ? *facing : static_cast<std::uint8_t>(1 - *facing);
      offset_m = std::clamp(offset_m + (towards == 1 ? 1 : -1) * kBlockageAhead_m, 0.0,
                            map_.pipe(here.pipe).length_m);
    }
    return Replan{Failure{.kind = Failure::Kind::kBlockage,
                          .pipe = here.pipe,
                          .offset_m = offset_m,
                          .detail = why},
                  ""};
  }
  move_refuted_failure(v.believed->position);
  sync_progress(replay.progress());
  return Replan{std::nullopt, "relocalised: " + v.reason};
}

void Relocalisation::failure_reported(const std::optional<Failure>& failure) {
  placed_.reset();
  if (failure && (failure->kind == Failure::Kind::kBlockage ||
                  failure->kind == Failure::Kind::kDangerInPipe)) {
    placed_ = Placed{.kind = failure->kind, .at = {failure->pipe, failure->offset_m}};
  }
}

void Relocalisation::drove_since_failure(const Job& job, double progress_m) {
  if (!placed_) return;
  std::visit(
      [&](const auto& j) {
        using J = std::decay_t<decltype(j)>;
        if constexpr (std::is_same_v<J, DriveForward>) {
          placed_->driven_m += progress_m;
        } else if constexpr (std::is_same_v<J, DriveBackward>) {
          placed_->driven_m -= progress_m;
        } else if constexpr (std::is_same_v<J, Scan> || std::is_same_v<J, Push>) {
          placed_->driven_m += j.backward ? -progress_m : progress_m;
        }
        if constexpr (std::is_same_v<J, DriveForward> || std::is_same_v<J, DriveBackward> ||
                      std::is_same_v<J, Scan> || std::is_same_v<J, Push>) {
          placed_->travelled_m += std::abs(progress_m);
        } else if constexpr (std::is_same_v<J, TurnInManhole> ||
                             std::is_same_v<J, EnterPipeFromManhole>) {
          placed_.reset();  // through a manhole: no longer one stretch of pipe
        }
      },
      job);
}

void Relocalisation::move_refuted_failure(const domain::RobotPosition& believed) {
  const auto* at = std::get_if<domain::AtSlot>(&believed);
  if (!placed_ || at == nullptr) return;
  const Slot& mouth = map_.slot(at->manhole, at->slot);
  const double length = map_.pipe(mouth.pipe).length_m;
  const double from_mouth = std::abs(placed_->driven_m);
  // In the pipe it was placed in, the tracking had the pipe right; beyond the mouth's pipe's
  // length, the robot drove through a manhole on the way (the filter's affair, not this); and
  // only one way from the failure (recovery's few centimetres aside): a robot that went back and
  // forth may have passed a manhole unseen, and its net distance says nothing of one pipe.
  if (mouth.pipe == placed_->at.pipe || from_mouth > length ||
      placed_->travelled_m > from_mouth + kOneWaySlackM) {
    return;
  }
  // Inside the pipe: a closure at its very mouth leaves the way in open (close_mouth()).
  const double margin = std::min(10 * kBlockageAhead_m, length / 2);
  const double inside = std::clamp(from_mouth, margin, length - margin);
  const Blockage truly{mouth.pipe, mouth.pipe_end == 0 ? inside : length - inside};
  const std::string why = "the robot, driving on from it, arrived at " +
                          map_.manhole(at->manhole).name + " out of " + map_.pipe(mouth.pipe).name;
  (void)replanner_.move_learnt(placed_->kind, placed_->at, truly, why);
  placed_.reset();  // planned again from here without a failure: failure_reported() clears it
}

bool Relocalisation::settle_elsewhere() {
  const auto* in = std::get_if<domain::InPipe>(&tracker_.position());
  if (in == nullptr) return false;
  const std::optional<localisation::Hypothesis> best = believed_elsewhere(in->pipe);
  if (!best) return false;
  (void)settle_on(*best);
  drove_in_behind(last_job_);
  return true;
}

void Relocalisation::drove_in_behind(const Job& job) {
  // Into this pipe through the mouth behind the robot, the way the drive went: what was learnt
  // blocked on the way is gone.
  const auto& here = std::get<domain::InPipe>(tracker_.position());
  const double direction = tracker_.direction_of(job);
  if (direction != 0) {
    const double entered_at = direction > 0 ? 0.0 : map_.pipe(here.pipe).length_m;
    (void)replanner_.drove_through(here.pipe, entered_at, here.offset_m);
  }
}

std::optional<std::string> Relocalisation::back_up_to_tell_apart() {
  const auto* in = std::get_if<domain::InPipe>(&tracker_.position());
  if (in == nullptr || tell_apart_tries_ >= kMaxTellApart) return std::nullopt;
  const localisation::Estimate belief = localising_.estimate();
  if (belief.lost()) return std::nullopt;
  const localisation::Hypothesis* other = nullptr;
  for (const localisation::Hypothesis& h : belief.hypotheses) {
    const auto* there = std::get_if<domain::InPipe>(&h.pose.position);
    if (h.probability < kTellApartFloor) continue;
    if (there == nullptr || there->pipe != in->pipe) {
      other = &h;
      break;
    }
  }
  if (other == nullptr) return std::nullopt;
  ++tell_apart_tries_;
  const std::string alternative = localisation::describe(other->pose, map_);
  const std::string tracked = tracker_.describe();
  // Away from the failure placed in this pipe, else back the way the last drive went (else away
  // from the end the robot faces); not the way of a step back off a danger (the meshed
  // 1,000-manhole network, seed 6, run 16: the robot drove back into the danger it had just
  // backed off).
  const double last = tracker_.direction_of(way_job_);
  std::uint8_t back_to = last > 0   ? 0
                         : last < 0 ? 1
                                    : static_cast<std::uint8_t>(1 - tracker_.heading_end());
  if (placed_ && placed_->at.pipe == in->pipe && placed_->at.offset_m != in->offset_m) {
    back_to = placed_->at.offset_m > in->offset_m ? 0 : 1;
  }
  const double end_m = back_to == 0 ? 0.0 : map_.pipe(in->pipe).length_m;
  const double distance = std::abs(end_m - in->offset_m);
  const double speed = mission().profile.speed_mps;
  const Job back =
      back_to == tracker_.heading_end()
          ? Job{DriveForward{.speed_mps = speed, .distance_m = distance, .to_manhole = true}}
          : Job{DriveBackward{.speed_mps = speed, .distance_m = distance, .to_manhole = true}};
  const hal::JobReport r = execute_job(back);
  // Settled on by execute_job; planned again from there below, with a closure the arrival shows
  // was placed in the wrong pipe moved into the right one.
  if (mismatch_ && mismatch_->verification.believed) {
    move_refuted_failure(mismatch_->verification.believed->position);
  }
  mismatch_.reset();
  if (halted() || !r.ok()) return std::nullopt;
  sync_progress(replanner_.progress());
  std::ostringstream why;
  why << "no exit from " << tracked << ", but the robot may be " << alternative
      << " (p=" << std::fixed << std::setprecision(2) << other->probability
      << "): backed up to tell, now " << tracker_.describe();
  return why.str();
}

std::optional<std::string> Relocalisation::refused_at_no_manhole(const Failure& failure,
                                                                 const Job& job) {
  if (failure.cause != hal::RobotErrorCause::kNotAtStart ||
      !std::holds_alternative<TurnInManhole>(job) ||
      !std::holds_alternative<domain::AtSlot>(tracker_.position())) {
    return std::nullopt;
  }
  const std::optional<localisation::Hypothesis> best = localising_.not_at_manhole();
  if (!best || !best->pose.heading_end) return std::nullopt;
  return "relocalised: the robot refused a turn (" + failure.detail + "): " + settle_on(*best);
}

std::optional<Replan> Relocalisation::refused_into_no_mouth(const Failure& failure,
                                                            const fusion::RobotAction& action) {
  const auto* pass = std::get_if<fusion::PassManhole>(&action);
  const auto* at = std::get_if<domain::AtSlot>(&tracker_.position());
  if (failure.cause != hal::RobotErrorCause::kNoMouth || pass == nullptr || at == nullptr ||
      at->manhole != pass->manhole || at->slot == pass->to_slot) {
    return std::nullopt;
  }
  const Slot& mouth = map_.slot(pass->manhole, pass->to_slot);
  return close_mouth(pass->manhole, mouth,
                     "no mouth of " + map_.pipe(mouth.pipe).name + " in " +
                         map_.manhole(pass->manhole).name + ": " + failure.detail,
                     failure.cause);
}

Replan Relocalisation::close_mouth(ManholeId manhole, const Slot& mouth, std::string detail,
                                   std::optional<hal::RobotErrorCause> cause) {
  close_passages_into(manhole, mouth);
  // Just inside the pipe from this manhole: at its very end, the way in would stay open.
  const double length = map_.pipe(mouth.pipe).length_m;
  const double inside = std::min(10 * kBlockageAhead_m, length / 2);
  return Replan{Failure{.kind = Failure::Kind::kBlockage,
                        .pipe = mouth.pipe,
                        .offset_m = mouth.pipe_end == 0 ? inside : length - inside,
                        .detail = std::move(detail),
                        .cause = cause},
                ""};
}

void Relocalisation::place_by_belief(Failure& failure, const Job& job) {
  if (failure.kind != Failure::Kind::kBlockage && failure.kind != Failure::Kind::kDangerInPipe)
    return;
  std::optional<localisation::Hypothesis> best = believed_elsewhere(failure.pipe);
  if (!best && at_far_end(failure, job)) best = likely_elsewhere(failure.pipe, kPastEndShare);
  if (!best) return;
  failure.detail += "; " + settle_on(*best);
  const auto& in = std::get<domain::InPipe>(best->pose.position);
  const double length = map_.pipe(in.pipe).length_m;
  const double direction = tracker_.direction_of(job);
  failure.pipe = in.pipe;
  failure.offset_m = std::clamp(in.offset_m + direction * kBlockageAhead_m, 0.0, length);
  if (const std::optional<double> met = learnt_behind(in.pipe, in.offset_m, direction)) {
    // The robot drove into this pipe unseen this job, through its whole length behind the place
    // settled on: a blockage or danger learnt there, just behind, stopped it, whatever the
    // odometry says.
    const double at = std::clamp(*met - direction * kBlockageAhead_m, 0.0, length);
    tracker_.set_pose(domain::InPipe{in.pipe, at}, *best->pose.heading_end);
    failure.offset_m = *met;
    std::ostringstream why;
    why << "; it met what was learnt at " << std::fixed << std::setprecision(2) << *met << " m in "
        << map_.pipe(in.pipe).name << " again, from the other side";
    failure.detail += why.str();
  }
  // A blockage learnt on the way in under the belief before was placed where the robot was not
  // (ISYBAU sample, realistic world, run 83: one obstacle closed 1.13 m into a pipe, then met
  // again, rear first, at 1.20 m by the relocalised robot, which was shut in between the two).
  // After the place is settled (above), so that a fault met again stays.
  drove_in_behind(job);
}

std::optional<double> Relocalisation::learnt_behind(PipeId pipe, double offset_m,
                                                    double direction) const {
  if (direction == 0) return std::nullopt;
  const double entered_at = direction > 0 ? 0.0 : map_.pipe(pipe).length_m;
  std::optional<double> first;
  const auto consider = [&](const Blockage& b) {
    if (b.pipe != pipe || (b.offset_m - offset_m) * direction >= 0) return;
    // Within the odometry's reach of the place (not a fault far back it may never have passed),
    // and not a closure at the mouth it came in by (a mouth the world lacks, closed).
    if (std::abs(b.offset_m - offset_m) > kMetAgainM || std::abs(b.offset_m - entered_at) < kAtEndM)
      return;
    // Of those behind, the one nearest the end the robot came in by is the one it met.
    if (!first || (b.offset_m - *first) * direction < 0) first = b.offset_m;
  };
  const Learnt& learnt = replanner_.learnt();
  for (const Blockage& b : learnt.blockages) consider(b);
  for (const Blockage& b : learnt.danger_spots) consider(b);
  return first;
}

std::optional<localisation::Hypothesis> Relocalisation::believed_elsewhere(PipeId tracked) const {
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

std::optional<localisation::Hypothesis> Relocalisation::likely_elsewhere(PipeId tracked,
                                                                         double share) const {
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

bool Relocalisation::at_far_end(const Failure& failure, const Job& job) const {
  const double direction = tracker_.direction_of(job);
  if (direction == 0) return false;
  const double end = direction > 0 ? map_.pipe(failure.pipe).length_m : 0.0;
  return std::abs(failure.offset_m - end) <= kAtEndM;
}

std::string Relocalisation::settle_on(const localisation::Hypothesis& believed) {
  std::string tracked = tracker_.describe();
  tracker_.set_pose(believed.pose.position, *believed.pose.heading_end);
  std::ostringstream why;
  why << "the robot is " << localisation::describe(believed.pose, map_) << " (p=" << std::fixed
      << std::setprecision(2) << believed.probability << "), not " << tracked;
  return why.str();
}

void Relocalisation::close_passages_into(ManholeId manhole, const Slot& mouth) {
  const Pipe& pipe = map_.pipe(mouth.pipe);
  const SlotIndex gone = pipe.ends[mouth.pipe_end].slot;
  Learnt closed;
  for (std::uint16_t s = 0; s < map_.manhole(manhole).slot_count; ++s) {
    if (s != gone.value()) closed.closed_passages.push_back({manhole, gone, SlotIndex{s}});
  }
  // Each passage names slots the map has: learn() cannot refuse them.
  (void)replanner_.learn(closed);
}
}  // namespace sewerplan::executor::detail
