// SPDX-License-Identifier: MIT
#include "sewerplan/hal/sim_robot.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <sstream>
#include <utility>

#include "sewerplan/core/check.h"
#include "sewerplan/core/map_queries.h"
#include "sewerplan/core/overloaded.h"
#include "sewerplan/hal/obstacle_clearing.h"

namespace sewerplan::hal {
namespace {

// Irwin-Hall: twelve uniforms less 6, a normal to within 0.3 % in the body and cut at 6 sigma;
// plain arithmetic, so the same on every platform.
double irwin_hall(Rng& rng, double sigma) {
  if (sigma <= 0) return 0;
  double sum = 0;
  for (int i = 0; i < 12; ++i) sum += rng.uniform01();
  return (sum - 6) * sigma;
}

// A drive that ends this close to a pipe end has reached it (fusion's distances carry rounding).
constexpr double kLengthTolerance_m = 1e-6;

std::string metres(double value_m) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(2) << value_m << " m";
  return os.str();
}

std::string seconds(double value_s) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(1) << value_s << " s";
  return os.str();
}

std::string slot_text(SlotIndex slot) { return "slot " + std::to_string(to_paper_number(slot)); }

bool valid_number(double value) { return std::isfinite(value) && value >= 0; }

// The pipe end a robot at a manhole's slot is at: the pipe and the end's offset.
InPipe pipe_end_pose(const SewerMap& map, ManholeId manhole, SlotIndex slot, bool heading_in) {
  const Slot& s = map.slot(manhole, slot);
  const double offset_m = s.pipe_end == 0 ? 0.0 : map.pipe(s.pipe).length_m;
  // Heading into the pipe points at the other end; heading out points at this one.
  const bool towards_end1 = (s.pipe_end == 0) == heading_in;
  return InPipe{s.pipe, offset_m, towards_end1 ? Heading::kTowardsEnd1 : Heading::kTowardsEnd0};
}

// Whether a push that meets an obstacle of `kind` with `approach` moves it (the one table,
// obstacle_clearing.h).
bool pushed_away(ObstacleKind kind, Approach approach) {
  return cleared_by(kind) == Clearing::kPush && clears_from(kind, approach);
}

}  // namespace

// Where a drive stops and why.
struct SimRobot::Move {
  enum class Why { kDone, kPipeEnd, kObstacle, kDanger };
  double distance_m = 0;
  Why why = Why::kDone;
  double fault_offset_m = 0;  // the obstacle's or danger spot's offset
};

std::ostream& operator<<(std::ostream& os, const SimPose& pose) {
  const auto flags = os.flags();
  const auto precision = os.precision();
  std::visit(Overloaded{
                 [&](const InManhole& p) { os << "in manhole " << p.manhole; },
                 [&](const AtSlot& p) {
                   os << "at manhole " << p.manhole << ' ' << slot_text(p.slot) << " facing the "
                      << (p.facing == Facing::kIntoManhole ? "manhole" : "pipe");
                 },
                 [&](const InPipe& p) {
                   os << "in pipe " << p.pipe << " at " << std::fixed << std::setprecision(2)
                      << p.offset_m << " m towards end "
                      << (p.heading == Heading::kTowardsEnd0 ? 0 : 1);
                 },
             },
             pose);
  os.flags(flags);
  os.precision(precision);
  return os;
}

std::string describe(const SimPose& pose, const SewerMap& map) {
  return std::visit(
      Overloaded{
          [&](const InManhole& p) { return "in manhole " + map.manhole(p.manhole).name; },
          [&](const AtSlot& p) {
            return "at " + map.manhole(p.manhole).name + ' ' + slot_text(p.slot) + " (" +
                   map.pipe(map.slot(p.manhole, p.slot).pipe).name + ") facing the " +
                   (p.facing == Facing::kIntoManhole ? "manhole" : "pipe");
          },
          [&](const InPipe& p) {
            const Pipe& pipe = map.pipe(p.pipe);
            const PipeEnd& end = pipe.ends[p.heading == Heading::kTowardsEnd0 ? 0 : 1];
            return "in " + pipe.name + " at " + metres(p.offset_m) + " towards " +
                   (end.manhole ? map.manhole(*end.manhole).name : std::string("its blind end"));
          },
      },
      pose);
}

SimRobot::SimRobot(const SewerMap& map, RobotProfile profile, SimPose start, FaultScenario faults,
                   SimOptions options)
    : map_(map),
      profile_(std::move(profile)),
      pose_(start),
      faults_(std::move(faults)),
      obstacle_cleared_(faults_.obstacles.size(), false),
      malfunction_struck_(faults_.malfunctions.size(), false),
      options_(std::move(options)),
      sensing_rng_(options_.sensing.seed),
      turn_rng_(options_.sensing.seed ^ 0x243f6a8885a308d3ULL) {
  SEWER_CHECK(validate_profile(profile_).has_value(), "SimRobot: invalid robot profile");
  SEWER_CHECK(validate_faults(faults_, map_).has_value(), "SimRobot: invalid fault scenario");
  std::visit(Overloaded{
                 [&](const InManhole& p) {
                   SEWER_CHECK(p.manhole.index() < map_.manhole_count(), "start: bad manhole");
                 },
                 [&](const AtSlot& p) {
                   SEWER_CHECK(p.manhole.index() < map_.manhole_count() &&
                                   p.slot.value() < map_.manhole(p.manhole).slot_count,
                               "start: bad manhole or slot");
                 },
                 [&](const InPipe& p) {
                   SEWER_CHECK(p.pipe.index() < map_.pipe_count() && p.offset_m >= 0 &&
                                   p.offset_m <= map_.pipe(p.pipe).length_m,
                               "start: bad pipe or offset");
                 },
             },
             pose_);
  status_.battery_wh = faults_.battery_wh.value_or(profile_.battery_wh);
}

std::vector<Obstacle> SimRobot::remaining_obstacles() const {
  std::vector<Obstacle> left;
  for (std::size_t i = 0; i < faults_.obstacles.size(); ++i) {
    if (!obstacle_cleared_[i]) left.push_back(faults_.obstacles[i]);
  }
  return left;
}

JobReport SimRobot::execute(const Job& job) {
  if (stopped_.load()) return finish(failure(RobotErrorCause::kEmergencyStop, "emergency stop"));
  const std::size_t index = jobs_executed_++;
  for (std::size_t i = 0; i < faults_.malfunctions.size(); ++i) {
    if (malfunction_struck_[i]) continue;
    const Malfunction& m = faults_.malfunctions[i];
    const auto* at_job = std::get_if<AtJob>(&m.when);
    const auto* at_time = std::get_if<AtTime>(&m.when);
    if (at_job != nullptr && at_job->index == index) {
      strike(i, "at job " + std::to_string(index));
    } else if (at_time != nullptr && at_time->time_s <= status_.elapsed_s) {
      strike(i, "at " + seconds(at_time->time_s));
    }
  }
  if (fault_) return finish(failure(RobotErrorCause::kFault, fault_->reason));
  if (status_.battery_wh <= 0) {
    return finish(failure(RobotErrorCause::kBatteryEmpty, "battery empty"));
  }
  return finish(run(job));
}

Result<void> SimRobot::reboot() {
  if (fault_ && fault_->kind == MalfunctionKind::kPermanent) {
    // core's ErrorCode has no robot fault yet; kIo: the robot's software cannot be restarted.
    return Error{ErrorCode::kIo, "reboot failed: " + fault_->reason};
  }
  fault_.reset();
  stopped_.store(false);
  const double duration_s =
      std::min(options_.reboot_s, profile_.seconds_for(std::max(0.0, status_.battery_wh)));
  JobReport report;
  report.duration_s = duration_s;
  static_cast<void>(finish(std::move(report)));
  // A malfunction timed while the software restarts meets software that is not running: a
  // transient one is cleared with the rest by this reboot, a permanent one stays. (They struck the
  // next job at once, so that one cluster of transient faults used up the executor's reboots.)
  for (std::size_t i = 0; i < faults_.malfunctions.size(); ++i) {
    const auto* at_time = std::get_if<AtTime>(&faults_.malfunctions[i].when);
    if (malfunction_struck_[i] || at_time == nullptr || at_time->time_s > status_.elapsed_s) {
      continue;
    }
    if (faults_.malfunctions[i].kind == MalfunctionKind::kTransient) {
      malfunction_struck_[i] = true;
    } else {
      strike(i, "at " + seconds(at_time->time_s));
    }
  }
  return {};
}

JobReport SimRobot::run(const Job& job) {
  return std::visit(Overloaded{
                        [&](const DriveForward& j) {
                          return drive(j.speed_mps, j.distance_m, +1, false, j.to_manhole);
                        },
                        [&](const DriveBackward& j) {
                          return drive(j.speed_mps, j.distance_m, -1, false, j.to_manhole);
                        },
                        [&](const Push& j) {
                          return drive(j.speed_mps, j.distance_m, j.backward ? -1 : +1, true);
                        },
                        [&](const Scan& j) {
                          return drive(j.speed_mps, j.distance_m, j.backward ? -1 : +1, false);
                        },
                        [&](const TurnInManhole& j) { return turn(j); },
                        [&](const EnterPipeFromManhole& j) { return enter(j); },
                        [&](const LiftHead&) { return set_head(true); },
                        [&](const LowerHead&) { return set_head(false); },
                        [&](const TakeSample& j) {
                          if (!valid_number(j.duration_s))
                            return invalid("the duration must be >= 0");
                          return stand(j.duration_s);
                        },
                        [&](const Stop&) { return JobReport{}; },
                    },
                    job);
}

JobReport SimRobot::drive(double speed_mps, double distance_m, int direction, bool push,
                          bool to_manhole) {
  if (!(std::isfinite(speed_mps) && speed_mps > 0)) return invalid("the speed must be > 0");
  if (!valid_number(distance_m)) return invalid("the distance must be >= 0");
  // A drive of 0 m does nothing, except in a pipe right at its end, where it is at the mouth.
  if (distance_m == 0 && !std::holds_alternative<InPipe>(pose_)) return JobReport{};
  if (const auto* in = std::get_if<InManhole>(&pose_)) {
    return failure(RobotErrorCause::kNotAtStart, "cannot drive in manhole " +
                                                     map_.manhole(in->manhole).name +
                                                     " at no pipe mouth: enter a pipe first");
  }
  if (const auto* at = std::get_if<AtSlot>(&pose_)) {
    // The way into the pipe is behind the robot when it faces the manhole.
    const int into_pipe = at->facing == Facing::kIntoManhole ? -1 : +1;
    if (direction != into_pipe && !push) {
      // Out of the pipe from the mouth it stands at (the controller believed it short of the end,
      // the pipe being shorter than mapped): the pipe's end stops it at once, as it stops any
      // drive that reaches it, and the robot sees the manhole unless it misses it. Refusing the
      // job left the controller rebooting a robot that had nothing wrong with it.
      JobReport report;
      const SensingModel& sensing = options_.sensing;
      const bool missed = sensing.missed_share > 0 && sensing_rng_.bernoulli(sensing.missed_share);
      if (sensing.observe && !missed) {
        std::vector<SlotIndex> order = signature_slot_order(map_, at->manhole, at->slot);
        report.observation = observe(expected_signature(map_, at->manhole, at->slot), &order);
        sighting_ = Sighting{at->manhole, at->slot, std::move(order)};
      }
      return report;
    }
    if (direction != into_pipe) {
      return failure(RobotErrorCause::kNotAtStart,
                     std::string("cannot drive ") + (direction > 0 ? "forward" : "backward") +
                         " into manhole " + map_.manhole(at->manhole).name + " from the mouth of " +
                         slot_text(at->slot) + ": turn through it");
    }
    const bool front_into_pipe = at->facing == Facing::kIntoPipe;
    const InPipe from = pipe_end_pose(map_, at->manhole, at->slot, front_into_pipe);
    JobReport report = drive_in_pipe(from, speed_mps, distance_m, direction, push, to_manhole);
    report.progress_m = odometry(report.progress_m, from.pipe);
    report.in_water = in_water(report.progress_m, from.pipe);
    return report;
  }
  const InPipe from = std::get<InPipe>(pose_);
  JobReport report = drive_in_pipe(from, speed_mps, distance_m, direction, push, to_manhole);
  report.progress_m = odometry(report.progress_m, from.pipe);
  report.in_water = in_water(report.progress_m, from.pipe);
  return report;
}

SimRobot::Move SimRobot::plan_move(const InPipe& from, double distance_m, int sign,
                                   std::optional<Approach> push) const {
  const Pipe& pipe = map_.pipe(from.pipe);
  const double to_end_m = sign > 0 ? pipe.length_m - from.offset_m : from.offset_m;
  Move move;
  if (distance_m <= to_end_m + kLengthTolerance_m) {
    move.distance_m = std::min(distance_m, to_end_m);
  } else {
    move.distance_m = to_end_m;
    move.why = Move::Why::kPipeEnd;
  }
  if (move.distance_m >= to_end_m - kLengthTolerance_m) move.why = Move::Why::kPipeEnd;
  // The robot stops clearance_m before the nearest obstacle or danger spot ahead; a stop where
  // the drive ends anyway does not fail it.
  const auto consider = [&](PipeId pipe_id, double offset_m, Move::Why why) {
    if (pipe_id != from.pipe) return;
    const double ahead_m = (offset_m - from.offset_m) * sign;
    if (ahead_m <= 0) return;
    double stop_m = ahead_m - options_.clearance_m;
    if (stop_m < kLengthTolerance_m) stop_m = 0;  // already there (a blockage before)
    if (stop_m < move.distance_m - kLengthTolerance_m) move = Move{stop_m, why, offset_m};
  };
  for (std::size_t i = 0; i < faults_.obstacles.size(); ++i) {
    const Obstacle& o = faults_.obstacles[i];
    if (obstacle_cleared_[i] || (push && pushed_away(o.kind, *push))) continue;
    consider(o.pipe, o.offset_m, Move::Why::kObstacle);
  }
  for (const DangerSpot& d : faults_.danger_spots) consider(d.pipe, d.offset_m, Move::Why::kDanger);
  return move;
}

JobReport SimRobot::drive_in_pipe(const InPipe& from, double speed_mps, double distance_m,
                                  int direction, bool push, bool to_manhole) {
  const Pipe& pipe = map_.pipe(from.pipe);
  const int sign = (from.heading == Heading::kTowardsEnd1 ? 1 : -1) * direction;
  // A drive to a manhole goes on past the map's distance, up to a bound, until it sees one; a
  // false detection may stop it sooner.
  const SensingModel& sensing = options_.sensing;
  const double budget_m = to_manhole ? distance_m + beyond_manhole_limit_m(distance_m) : distance_m;
  std::optional<double> false_at_m;
  if (to_manhole && sensing.false_per_km > 0) {
    const double at_m = -std::log(1 - sensing_rng_.uniform01()) * 1000 / sensing.false_per_km;
    const double to_end_m = sign > 0 ? pipe.length_m - from.offset_m : from.offset_m;
    if (at_m < std::min(budget_m, to_end_m)) false_at_m = at_m;
  }
  const Approach approach = direction > 0 ? Approach::kFront : Approach::kRear;
  Move move = plan_move(from, false_at_m.value_or(budget_m), sign,
                        push ? std::optional(approach) : std::nullopt);
  JobReport report;
  std::optional<Interrupt> stop = interrupt_within(move.distance_m / speed_mps);
  report.progress_m = stop ? std::min(move.distance_m, stop->after_s * speed_mps) : move.distance_m;
  report.duration_s = stop ? stop->after_s : move.distance_m / speed_mps;
  if (push) {
    // A push moves every obstacle a push clears from its side (pushed_away) that it reaches.
    for (std::size_t i = 0; i < faults_.obstacles.size(); ++i) {
      const Obstacle& o = faults_.obstacles[i];
      if (o.pipe != from.pipe || !pushed_away(o.kind, approach)) continue;
      const double ahead_m = (o.offset_m - from.offset_m) * sign;
      if (ahead_m > 0 && ahead_m - options_.clearance_m <= report.progress_m) {
        obstacle_cleared_[i] = true;
      }
    }
  }
  const double offset_m = std::clamp(from.offset_m + sign * report.progress_m, 0.0, pipe.length_m);
  pose_ = InPipe{from.pipe, offset_m, from.heading};
  if (stop) return interrupt(*stop, std::move(report));
  switch (move.why) {
    case Move::Why::kDone:
      if (false_at_m) {
        if (sensing.observe) report.observation = false_manhole(from.pipe);
        return report;
      }
      if (to_manhole) {
        report.error =
            RobotError{RobotErrorCause::kNoManholeSeen,
                       "no manhole seen in " + pipe.name + " within " + metres(report.progress_m) +
                           " (the map says " + metres(distance_m) + ")"};
      }
      return report;
    case Move::Why::kPipeEnd: {
      const PipeEnd& end = pipe.ends[sign > 0 ? 1 : 0];
      if (end.manhole) {
        pose_ = AtSlot{*end.manhole, end.slot,
                       direction > 0 ? Facing::kIntoManhole : Facing::kIntoPipe};
        const bool missed =
            sensing.missed_share > 0 && sensing_rng_.bernoulli(sensing.missed_share);
        if (!missed) {
          if (sensing.observe) {
            std::vector<SlotIndex> order = signature_slot_order(map_, *end.manhole, end.slot);
            report.observation = observe(expected_signature(map_, *end.manhole, end.slot), &order);
            sighting_ = Sighting{*end.manhole, end.slot, std::move(order)};
          }
          return report;
        }
        // Not seen: where the manhole lets it drive straight on, a drive to a manhole does,
        // with what is left of its bound; elsewhere the pipe's end stops it, unobserved.
        const double left_m = budget_m - report.progress_m;
        const std::optional<SlotIndex> on = straight_on(*end.manhole, end.slot);
        if (!to_manhole || !on || left_m <= kLengthTolerance_m) return report;
        const InPipe next = pipe_end_pose(map_, *end.manhole, *on, direction > 0);
        JobReport rest = drive_in_pipe(next, speed_mps, left_m, direction, push, false);
        rest.progress_m += report.progress_m;
        rest.duration_s += report.duration_s;
        if (rest.ok() && !rest.observation && !std::holds_alternative<AtSlot>(pose_)) {
          rest.error =
              RobotError{RobotErrorCause::kNoManholeSeen,
                         "no manhole seen in " + pipe.name + " within " + metres(rest.progress_m) +
                             " (the map says " + metres(distance_m) + ")"};
        }
        return rest;
      }
      pose_ = InPipe{from.pipe, sign > 0 ? pipe.length_m : 0.0, from.heading};
      // A drive to a manhole that meets the pipe's blind end (a lateral the world lacks) saw no
      // manhole, however far it went.
      if (!to_manhole && distance_m <= report.progress_m + kLengthTolerance_m) return report;
      report.error = RobotError{RobotErrorCause::kBlindEnd,
                                "blind end of " + pipe.name + " at " + metres(offset_m)};
      return report;
    }
    case Move::Why::kObstacle:
      report.error = RobotError{RobotErrorCause::kObstacle,
                                "obstacle in " + pipe.name + " at " + metres(move.fault_offset_m)};
      return report;
    case Move::Why::kDanger:
      report.error = RobotError{RobotErrorCause::kDangerSpot,
                                "danger in " + pipe.name + " at " + metres(move.fault_offset_m)};
      return report;
  }
  return report;
}

double SimRobot::normal(double sigma) { return irwin_hall(sensing_rng_, sigma); }

// Slip: the error's standard deviation is drift x distance, twice that in a wet pipe and twice
// again in one falling more than 2 % (its ends' inverts); never below 0.
double SimRobot::odometry(double true_m, PipeId pipe) {
  const SensingModel& s = options_.sensing;
  if (s.drift <= 0 || true_m <= 0) return true_m;
  double slip = 1;
  if (pipe.index() < s.wet.size() && s.wet[pipe.index()]) slip *= 2;
  const Pipe& p = map_.pipe(pipe);
  if (p.ends[0].manhole && p.ends[1].manhole) {
    const double fall_m = map_.slot(*p.ends[0].manhole, p.ends[0].slot).invert_z_m -
                          map_.slot(*p.ends[1].manhole, p.ends[1].slot).invert_z_m;
    if (std::abs(fall_m) > 0.02 * p.length_m) slip *= 2;
  }
  return std::max(0.0, true_m + normal(s.drift * slip * true_m));
}

bool SimRobot::in_water(double driven_m, PipeId pipe) const {
  const std::vector<bool>& wet = options_.sensing.wet;
  return driven_m > 0 && pipe.index() < wet.size() && wet[pipe.index()];
}

ManholeSignature SimRobot::observe(ManholeSignature truth, std::vector<SlotIndex>* order) {
  if (!options_.sensing.signature_noise) return truth;
  const SignatureNoise& n = *options_.sensing.signature_noise;
  for (std::size_t i = 0; i < truth.slots.size(); ++i) {
    SlotSighting& s = truth.slots[i];
    if (i > 0) {
      s.relative_deg = std::fmod(s.relative_deg + normal(n.direction_deg) + 720.0, 360.0);
      s.step_m += normal(n.step_m);
    }
    s.diameter_m = std::max(0.01, s.diameter_m + normal(n.diameter_m));
  }
  // The robot lists what it sees counter-clockwise from where it came in.
  std::vector<std::size_t> seen(truth.slots.size());
  std::iota(seen.begin(), seen.end(), std::size_t{0});
  std::stable_sort(seen.begin() + (seen.empty() ? 0 : 1), seen.end(),
                   [&](std::size_t a, std::size_t b) {
                     return truth.slots[a].relative_deg < truth.slots[b].relative_deg;
                   });
  std::vector<SlotSighting> sorted;
  sorted.reserve(seen.size());
  for (std::size_t i : seen) sorted.push_back(truth.slots[i]);
  truth.slots = std::move(sorted);
  if (order != nullptr && order->size() == seen.size()) {
    std::vector<SlotIndex> reordered;
    reordered.reserve(seen.size());
    for (std::size_t i : seen) reordered.push_back((*order)[i]);
    *order = std::move(reordered);
  }
  truth.shaft_diameter_m = std::max(0.1, truth.shaft_diameter_m + normal(n.shaft_m));
  return truth;
}

// What a false detection looks like: a pipe going straight on, the shaft the pipe's own width (a
// joint, a lateral's mouth, a change of profile taken for a manhole).
ManholeSignature SimRobot::false_manhole(PipeId pipe) {
  const double d = map_.pipe(pipe).diameter_m;
  return observe(ManholeSignature{.slots = {{0, 0, d}, {180, 0, d}}, .shaft_diameter_m = d});
}

std::optional<SlotIndex> SimRobot::straight_on(ManholeId manhole, SlotIndex arrival) const {
  const double in_deg = map_.slot(manhole, arrival).azimuth_deg;
  const auto slots = map_.slots(manhole);
  for (std::size_t i = 0; i < slots.size(); ++i) {
    if (i == arrival.index()) continue;
    // A pipe the robot's body does not fit stops it at its mouth: it cannot drive on into a
    // 0.10 m house connection, or brace itself in a pipe wider than its profile's.
    const double size_m = map_.pipe(slots[i].pipe).diameter_m;
    if (size_m < profile_.min_pipe_diameter_m || size_m > profile_.max_pipe_diameter_m) continue;
    const double turn = std::abs(std::fmod(slots[i].azimuth_deg - in_deg + 720.0, 360.0) - 180);
    if (turn <= 15) return SlotIndex{static_cast<std::uint16_t>(i)};
  }
  return std::nullopt;
}

JobReport SimRobot::turn_by_sighting(const TurnInManhole& job) {
  // In a pipe right at its end in a manhole is at that mouth.
  if (const auto* in = std::get_if<InPipe>(&pose_)) {
    const Pipe& pipe = map_.pipe(in->pipe);
    for (std::size_t e = 0; e < 2; ++e) {
      const double end = e == 0 ? 0.0 : pipe.length_m;
      if (pipe.ends[e].manhole && std::abs(in->offset_m - end) <= 1e-6) {
        const bool front_to_this_end = (in->heading == Heading::kTowardsEnd1) == (e == 1);
        pose_ = AtSlot{*pipe.ends[e].manhole, pipe.ends[e].slot,
                       front_to_this_end ? Facing::kIntoManhole : Facing::kIntoPipe};
        break;
      }
    }
  }
  const auto* at = std::get_if<AtSlot>(&pose_);
  if (at == nullptr) {
    return failure(RobotErrorCause::kNotAtStart,
                   "not at a manhole's mouth (" + describe(pose_, map_) + ")");
  }
  const std::vector<SlotIndex> order =
      sighting_ && sighting_->manhole == at->manhole && sighting_->arrival == at->slot
          ? sighting_->order
          : signature_slot_order(map_, at->manhole, at->slot);
  if (job.to_slot == 0) return invalid("a turn from the arrival into the arrival");
  if (job.to_slot >= order.size()) {
    // The sewer has no such mouth here: no way through, whatever the job's numbers.
    return failure(RobotErrorCause::kNoMouth, map_.manhole(at->manhole).name + " has no mouth " +
                                                  std::to_string(job.to_slot + 1) +
                                                  " seen from its arrival (" +
                                                  std::to_string(order.size()) + " seen)");
  }
  TurnInManhole by_number = job;
  by_number.from_slot = at->slot.value();
  by_number.to_slot = order[job.to_slot].value();
  return turn(by_number);
}

JobReport SimRobot::turn(const TurnInManhole& job) {
  if (job.from_slot == kBySighting) return turn_by_sighting(job);
  // In a pipe right at its end in a manhole is at that mouth: a plan may leave a pipe it only just
  // entered with a drive of 0 m, which fusion sends as no job at all.
  if (const auto* in = std::get_if<InPipe>(&pose_)) {
    const Pipe& pipe = map_.pipe(in->pipe);
    for (std::size_t e = 0; e < 2; ++e) {
      const double end = e == 0 ? 0.0 : pipe.length_m;
      if (pipe.ends[e].manhole && std::abs(in->offset_m - end) <= 1e-6 &&
          pipe.ends[e].slot.value() == job.from_slot) {
        // It keeps the way it faces: to back out again it must know which way the pipe is.
        const bool front_to_this_end = (in->heading == Heading::kTowardsEnd1) == (e == 1);
        pose_ = AtSlot{*pipe.ends[e].manhole, pipe.ends[e].slot,
                       front_to_this_end ? Facing::kIntoManhole : Facing::kIntoPipe};
        break;
      }
    }
  }
  const auto* at = std::get_if<AtSlot>(&pose_);
  if (at == nullptr || at->slot.value() != job.from_slot) {
    return failure(RobotErrorCause::kNotAtStart, "not at " + slot_text(SlotIndex{job.from_slot}) +
                                                     " of a manhole (" + describe(pose_, map_) +
                                                     ")");
  }
  const Manhole& manhole = map_.manhole(at->manhole);
  if (job.to_slot >= manhole.slot_count) {
    // The map has a mouth the sewer lacks (a lateral missing, another type of manhole): the way
    // through it does not exist, a blockage of that passage, not a job no robot could run.
    return failure(RobotErrorCause::kNoMouth, manhole.name + " has no passage from " +
                                                  slot_text(SlotIndex{job.from_slot}) + " to " +
                                                  slot_text(SlotIndex{job.to_slot}) + ": it has " +
                                                  std::to_string(manhole.slot_count) + " mouths");
  }
  if (job.to_slot == job.from_slot) {
    return invalid("a turn from " + slot_text(SlotIndex{job.from_slot}) + " into itself");
  }
  if (!valid_number(job.duration_s)) return invalid("the duration must be >= 0");
  const SlotIndex to{job.to_slot};
  for (const DangerousPassage& d : faults_.dangerous_passages) {
    const bool same = d.from_slot == at->slot && d.to_slot == to;
    const bool reverse = d.from_slot == to && d.to_slot == at->slot;
    if (d.manhole == at->manhole && (same || reverse)) {
      return failure(RobotErrorCause::kDangerousPassage, "dangerous passage in " + manhole.name +
                                                             " from " + slot_text(at->slot) +
                                                             " to " + slot_text(to));
    }
  }
  JobReport report = stand(job.duration_s);
  if (!report.ok()) return report;
  if (const std::optional<double> noise = options_.sensing.turn_noise_deg) {
    // The joints measure the heading change between the two mouths (the world's, not the map's).
    const double truly = std::fmod(map_.slot(at->manhole, to).azimuth_deg -
                                       map_.slot(at->manhole, at->slot).azimuth_deg + 720.0,
                                   360.0);
    report.turn_measured_deg = std::fmod(truly + irwin_hall(turn_rng_, *noise) + 720.0, 360.0);
  }
  pose_ = pipe_end_pose(map_, at->manhole, to, true);
  return report;
}

JobReport SimRobot::enter(const EnterPipeFromManhole& job) {
  const auto* in = std::get_if<InManhole>(&pose_);
  if (in == nullptr) {
    return failure(RobotErrorCause::kNotAtStart,
                   "not lowered into a manhole (" + describe(pose_, map_) + ")");
  }
  const Manhole& manhole = map_.manhole(in->manhole);
  if (job.slot >= manhole.slot_count) {
    return invalid(manhole.name + " has no " + slot_text(SlotIndex{job.slot}));
  }
  if (!valid_number(job.duration_s)) return invalid("the duration must be >= 0");
  const ManholeId m = in->manhole;
  JobReport report = stand(job.duration_s);
  if (report.ok()) pose_ = pipe_end_pose(map_, m, SlotIndex{job.slot}, true);
  return report;
}

JobReport SimRobot::set_head(bool lifted) {
  JobReport report = stand(options_.head_move_s);
  if (!report.ok()) return report;
  status_.head_lifted = lifted;
  if (!lifted) return report;
  // A lifted head frees a transient_lift obstacle within reach, at a pipe mouth too.
  std::optional<InPipe> where;
  if (const auto* p = std::get_if<InPipe>(&pose_)) where = *p;
  if (const auto* at = std::get_if<AtSlot>(&pose_)) {
    where = pipe_end_pose(map_, at->manhole, at->slot, true);
  }
  if (!where) return report;
  for (std::size_t i = 0; i < faults_.obstacles.size(); ++i) {
    const Obstacle& o = faults_.obstacles[i];
    if (o.pipe == where->pipe && cleared_by(o.kind) == Clearing::kLiftHead &&
        std::abs(o.offset_m - where->offset_m) <= options_.lift_reach_m + kLengthTolerance_m) {
      obstacle_cleared_[i] = true;
    }
  }
  return report;
}

JobReport SimRobot::stand(double duration_s) {
  JobReport report;
  if (std::optional<Interrupt> stop = interrupt_within(duration_s)) {
    report.duration_s = stop->after_s;
    return interrupt(*stop, std::move(report));
  }
  report.duration_s = duration_s;
  return report;
}

std::optional<SimRobot::Interrupt> SimRobot::interrupt_within(double duration_s) const {
  std::optional<Interrupt> first;
  const double battery_s = profile_.seconds_for(status_.battery_wh);
  if (battery_s < duration_s) first = Interrupt{battery_s, std::nullopt};
  for (std::size_t i = 0; i < faults_.malfunctions.size(); ++i) {
    const auto* at_time = std::get_if<AtTime>(&faults_.malfunctions[i].when);
    if (malfunction_struck_[i] || at_time == nullptr) continue;
    const double after_s = std::max(0.0, at_time->time_s - status_.elapsed_s);
    if (after_s < duration_s && (!first || after_s < first->after_s)) {
      first = Interrupt{after_s, i};
    }
  }
  return first;
}

JobReport SimRobot::interrupt(const Interrupt& stop, JobReport report) {
  if (!stop.malfunction) {
    battery_empty_ = true;
    report.error = RobotError{RobotErrorCause::kBatteryEmpty, "battery empty"};
    return report;
  }
  const auto& at = std::get<AtTime>(faults_.malfunctions[*stop.malfunction].when);
  strike(*stop.malfunction, "at " + seconds(at.time_s));
  report.error = RobotError{RobotErrorCause::kFault, fault_->reason};
  return report;
}

void SimRobot::strike(std::size_t malfunction, const std::string& when) {
  malfunction_struck_[malfunction] = true;
  const MalfunctionKind kind = faults_.malfunctions[malfunction].kind;
  // A permanent fault is not softened by a later transient one.
  if (fault_ && fault_->kind == MalfunctionKind::kPermanent) return;
  fault_ = Fault{kind, std::string(to_string(kind)) + " malfunction " + when};
}

JobReport SimRobot::failure(RobotErrorCause cause, std::string reason) {
  JobReport report;
  report.error = RobotError{cause, std::move(reason)};
  return report;
}

JobReport SimRobot::invalid(const std::string& what) {
  return failure(RobotErrorCause::kInvalidJob, "invalid job: " + what);
}

JobReport SimRobot::finish(JobReport report) {
  report.energy_wh = profile_.energy_wh(report.duration_s);
  status_.battery_wh = std::max(0.0, status_.battery_wh - report.energy_wh);
  if (battery_empty_) status_.battery_wh = 0;
  status_.elapsed_s += report.duration_s;
  status_.odometry_m += report.progress_m;
  if (options_.clock != nullptr) options_.clock->advance(report.duration_s);
  return report;
}

}  // namespace sewerplan::hal
