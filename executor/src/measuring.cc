// SPDX-License-Identifier: MIT
#include "sewerplan/executor/measuring.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "job_arithmetic.h"

namespace sewerplan::executor {

Measurer::Measurer(const SewerMap& map, MeasurementSource source, MeasuringOptions options)
    : map_(map), options_(options), measurements_(measurements_of(map, std::move(source))) {}

JobObserver Measurer::observer() {
  return [this](const JobSeen& seen) {
    observe(seen.job, seen.report, seen.before, seen.after, seen.direction);
  };
}

double Measurer::sigma_m(double distance_m, PipeId pipe, bool in_water) const {
  double fraction = options_.odometry_sigma_fraction;
  if (in_water) fraction *= options_.water_sigma_factor;
  const Pipe& p = map_.pipe(pipe);
  if (p.ends[0].manhole && p.ends[1].manhole) {
    const double fall_m = map_.slot(*p.ends[0].manhole, p.ends[0].slot).invert_z_m -
                          map_.slot(*p.ends[1].manhole, p.ends[1].slot).invert_z_m;
    if (std::abs(fall_m) > options_.steep_fall_fraction * p.length_m)
      fraction *= options_.steep_sigma_factor;
  }
  return std::hypot(fraction * distance_m, options_.odometry_sigma_floor_m);
}

bool Measurer::valid(const ManholeSignature& seen, const std::string& where) {
  if (Result<void> checked = check_signature(seen); !checked.has_value()) {
    rejected_.push_back(where + ": signature: " + checked.error().message);
    return false;
  }
  return true;
}

bool Measurer::near_an_end(const Pipe& pipe, double offset_m, double sigma_m) {
  const double margin = std::max(options_.end_margin_sigmas * sigma_m, options_.end_margin_m);
  for (std::uint8_t e = 0; e < 2; ++e) {
    const double from_end = std::abs(offset_m - domain::end_offset_m(pipe, e));
    if (!pipe.ends[e].manhole || from_end > margin) continue;
    rejected_.push_back(pipe.name + " at " + std::to_string(offset_m) + " m: a manhole seen " +
                        std::to_string(from_end) + " m from " +
                        map_.manhole(*pipe.ends[e].manhole).name +
                        ", too near to tell from it: no junction");
    return true;
  }
  return false;
}

bool Measurer::too_narrow(const Pipe& pipe, double offset_m, const ManholeSignature& seen) {
  if (seen.shaft_diameter_m >= options_.min_junction_shaft_m) return false;
  rejected_.push_back(pipe.name + " at " + std::to_string(offset_m) + " m: a manhole seen with a " +
                      std::to_string(seen.shaft_diameter_m) + " m shaft, narrower than " +
                      std::to_string(options_.min_junction_shaft_m) +
                      " m: a false detection, no junction");
  return true;
}

void Measurer::observe(const Job& job, const hal::JobReport& report,
                       const domain::RobotPosition& before, const domain::RobotPosition& after,
                       double direction) {
  if (const auto* t = std::get_if<TurnInManhole>(&job)) turn(*t, report, before, after);
  if (std::holds_alternative<TurnInManhole>(job) ||
      std::holds_alternative<EnterPipeFromManhole>(job)) {
    leg_.reset();
    if (report.ok()) start_leg(after);
    return;
  }
  if (direction != 0) drive(job, report, after, direction);
  if (!report.observation) return;
  if (const auto* at = std::get_if<domain::AtSlot>(&after)) {
    arrival(at->manhole, at->slot, *report.observation);
    return;
  }
  // In a pipe with no leg to measure from (a drive that started in the pipe): a junction at the
  // controller's offset, as uncertain as the drive from the nearer end.
  const auto* in = std::get_if<domain::InPipe>(&after);
  if (leg_ || in == nullptr) return;
  const Pipe& pipe = map_.pipe(in->pipe);
  if (!valid(*report.observation, pipe.name)) return;
  const double sigma =
      sigma_m(std::min(in->offset_m, pipe.length_m - in->offset_m), in->pipe, report.in_water);
  if (near_an_end(pipe, in->offset_m, sigma) || too_narrow(pipe, in->offset_m, *report.observation))
    return;
  measurements_.junctions.push_back({.pipe = in->pipe,
                                     .offset_m = in->offset_m,
                                     .sigma_m = sigma,
                                     .signature = *report.observation,
                                     .source = 0});
}

void Measurer::turn(const TurnInManhole& job, const hal::JobReport& report,
                    const domain::RobotPosition& before, const domain::RobotPosition& after) {
  // A turn by sighting is through a manhole the map lacks: nothing of the map to measure.
  if (!report.ok() || !report.turn_measured_deg || job.from_slot == kBySighting) return;
  // The manhole: where the controller had the robot, at the mouth it turned from, or in the pipe
  // it turned into, at that pipe's end in the manhole.
  std::optional<ManholeId> manhole;
  if (const auto* at = std::get_if<domain::AtSlot>(&before);
      at != nullptr && at->slot.value() == job.from_slot) {
    manhole = at->manhole;
  } else if (const auto* in = std::get_if<domain::InPipe>(&after)) {
    const Pipe& pipe = map_.pipe(in->pipe);
    for (std::uint8_t e = 0; e < 2; ++e) {
      if (pipe.ends[e].manhole && pipe.ends[e].slot.value() == job.to_slot &&
          std::abs(in->offset_m - domain::end_offset_m(pipe, e)) <= 1e-6) {
        manhole = pipe.ends[e].manhole;
      }
    }
  }
  if (!manhole) return;
  const std::size_t slots = map_.slots(*manhole).size();
  const double measured = *report.turn_measured_deg;
  const std::string& name = map_.manhole(*manhole).name;
  if (job.from_slot >= slots || job.to_slot >= slots || job.from_slot == job.to_slot) return;
  if (!std::isfinite(measured) || measured < 0 || measured >= 360) {
    rejected_.push_back(name + ": a turn measured at " + std::to_string(measured) +
                        " degrees, not in [0, 360)");
    return;
  }
  add_turn(measurements_, *manhole,
           {.from = SlotIndex{job.from_slot},
            .to = SlotIndex{job.to_slot},
            .relative_deg = measured,
            .sigma_deg = options_.turn_sigma_deg,
            .source = 0});
}

void Measurer::start_leg(const domain::RobotPosition& after) {
  const auto* in = std::get_if<domain::InPipe>(&after);
  if (in == nullptr) return;
  const Pipe& pipe = map_.pipe(in->pipe);
  for (std::uint8_t e = 0; e < 2; ++e) {
    if (pipe.ends[e].manhole && std::abs(in->offset_m - domain::end_offset_m(pipe, e)) <= 1e-6) {
      leg_ = Leg{.pipe = in->pipe, .from_end = e};
      return;
    }
  }
}

namespace {

// Whether a job's report spoils the leg it is part of: a push (its wheels turn against the
// obstacle, and a real robot's odometry counts the slip), or a report the link lost part of
// (what the robot drove is not all known). A drive that stopped short (an obstacle or a danger
// ahead, a fault, its bound without a manhole) counts what it drove, and recovery's manoeuvres
// (backing up, driving on) are drives the robot reports: the leg goes on.
bool spoils_leg(const Job& job, const hal::JobReport& report) {
  return std::holds_alternative<Push>(job) ||
         (report.error && report.error->cause == hal::RobotErrorCause::kLink);
}

}  // namespace

void Measurer::drive(const Job& job, const hal::JobReport& report,
                     const domain::RobotPosition& after, double direction) {
  if (!leg_) return;
  const Pipe& pipe = map_.pipe(leg_->pipe);
  if (!std::isfinite(report.progress_m) || report.progress_m < 0) {
    rejected_.push_back(pipe.name + ": odometry " + std::to_string(report.progress_m) +
                        " is not a distance");
    leg_->clean = false;
  } else {
    // +1 towards ends[1]; the far end is ends[1 - from_end].
    const double towards_far = leg_->from_end == 0 ? direction : -direction;
    leg_->driven_m += towards_far * report.progress_m;
  }
  if (spoils_leg(job, report)) leg_->clean = false;
  if (report.in_water) leg_->in_water = true;

  if (const auto* at = std::get_if<domain::AtSlot>(&after)) {
    const Slot& slot = map_.slot(at->manhole, at->slot);
    if (slot.pipe != leg_->pipe || slot.pipe_end == leg_->from_end) {
      leg_.reset();  // back where it started, or somewhere the leg does not lead
    } else if (report.observation ||
               (detail::ends_at_manhole(job) && report.ok() && !leg_->refused_at_end)) {
      end_leg(at->manhole, at->slot);
    }
    // Otherwise the controller has the robot at the far mouth by the map's distance alone (a scan
    // or a drive of a distance that saw no manhole): in a pipe longer than mapped it stopped short
    // of it, and the drive to the manhole that follows ends the leg. Or by its word alone, against
    // the robot's sighting there (refused_at_end): only an arrival the robot sees ends the leg.
    return;
  }
  const auto* in = std::get_if<domain::InPipe>(&after);
  if (!report.observation || in == nullptr || in->pipe != leg_->pipe) return;
  const std::string where = pipe.name + " at " + std::to_string(in->offset_m) + " m";
  if (!valid(*report.observation, where)) return;
  const std::uint8_t far = 1 - leg_->from_end;
  const PipeEnd& far_end = pipe.ends[far];
  const double remaining = pipe.length_m - leg_->driven_m;
  if (far_end.manhole && remaining >= 0 &&
      remaining <= options_.early_arrival_fraction * pipe.length_m &&
      compare(expected_signature(map_, *far_end.manhole, far_end.slot), *report.observation,
              options_.noise)
          .matches) {
    const ManholeId m = *far_end.manhole;
    const SlotIndex s = far_end.slot;
    end_leg(m, s);
    arrival(m, s, *report.observation);
    return;
  }
  // Seen where the controller has the robot at the far end, and not taken for the far manhole
  // (unlike it, the controller took it for a false detection).
  if (far_end.manhole && std::abs(in->offset_m - domain::end_offset_m(pipe, far)) <= 1e-6) {
    leg_->refused_at_end = true;
  }
  const double sigma = sigma_m(std::abs(leg_->driven_m), leg_->pipe, leg_->in_water);
  if (near_an_end(pipe, in->offset_m, sigma) || too_narrow(pipe, in->offset_m, *report.observation))
    return;
  measurements_.junctions.push_back({.pipe = leg_->pipe,
                                     .offset_m = in->offset_m,
                                     .sigma_m = sigma,
                                     .signature = *report.observation,
                                     .source = 0});
}

void Measurer::end_leg(ManholeId manhole, SlotIndex slot) {
  (void)slot;
  const Leg leg = *leg_;
  leg_.reset();
  if (!leg.clean || leg.driven_m <= 0) return;
  const Pipe& pipe = map_.pipe(leg.pipe);
  // Of the pipe's mapped length, not of what the leg read: every pass of a pipe drives the same
  // length, and a sigma of the reading made a leg that slipped short look more precise, pulling
  // the pooled mean down (and the corrected length away from the map's).
  const double sigma = sigma_m(pipe.length_m, leg.pipe, leg.in_water);
  add_length(measurements_, leg.pipe, leg.driven_m, sigma * sigma, 0);
  // Position: the manhole left's map position plus the pipe's chord, scaled by measured / mapped
  // length (map_measurements.h).
  const std::optional<ManholeId> from = pipe.ends[leg.from_end].manhole;
  if (!from) return;
  const Position& a = map_.manhole(*from).position;
  const Position& b = map_.manhole(manhole).position;
  const double chord = std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
  if (chord <= 0 || pipe.length_m <= 0) return;
  const double scale = leg.driven_m / pipe.length_m;
  const double position_sigma = sigma * chord / pipe.length_m;
  add_position(measurements_, manhole, a.x_m + (b.x_m - a.x_m) * scale,
               a.y_m + (b.y_m - a.y_m) * scale, position_sigma * position_sigma, 0);
}

void Measurer::arrival(ManholeId manhole, SlotIndex slot, const ManholeSignature& seen) {
  if (!valid(seen, map_.manhole(manhole).name)) return;
  add_observation(measurements_, manhole, slot, seen, 0);
}

}  // namespace sewerplan::executor
