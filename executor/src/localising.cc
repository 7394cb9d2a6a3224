// SPDX-License-Identifier: MIT
#include "localising.h"

#include <cmath>
#include <sstream>
#include <utility>
#include <variant>

#include "job_arithmetic.h"

namespace sewerplan::executor::detail {
namespace {

using localisation::DriveDirection;
using localisation::Verification;

// The direction of a drive as the filter counts it (the robot's own forward and backward: a
// backward push or scan goes backward), or empty for a job that does not drive.
std::optional<DriveDirection> drive_direction(const Job& job) {
  if (!rest_of(job, 0)) return std::nullopt;  // not a drive
  return approach_of(job) == hal::Approach::kRear ? DriveDirection::kBackward
                                                  : DriveDirection::kForward;
}

// A check without a manhole to check against (the tracking has the robot in a pipe): the filter's
// most likely explanation of the stop.
Verification unexpected_stop(const localisation::Estimate& estimate, const SewerMap& map) {
  Verification v;
  v.kind = Verification::Kind::kFalseDetection;
  if (estimate.lost()) {
    v.reason = "stopped at a manhole the plan did not drive to, and nothing on the map explains it";
    return v;
  }
  const localisation::Hypothesis& best = estimate.best();
  v.believed = best.pose;
  if (!best.assumptions.empty()) {
    switch (best.assumptions.front().kind) {
      case localisation::Assumption::Kind::kUnmappedJunction:
        v.kind = Verification::Kind::kUnmappedJunction;
        break;
      case localisation::Assumption::Kind::kMissedManhole:
        v.kind = Verification::Kind::kMissedManhole;
        break;
      case localisation::Assumption::Kind::kFalseDetection:
        v.kind = Verification::Kind::kFalseDetection;
        break;
    }
  } else if (std::holds_alternative<domain::AtSlot>(best.pose.position)) {
    v.kind = Verification::Kind::kWrongManhole;
  }
  v.reason = "stopped short of where the plan drove: " + localisation::describe(best.pose, map);
  return v;
}

}  // namespace

std::optional<Slot> missing_mouth(const Arrival& arrival, const SewerMap& map,
                                  const SignatureNoise& noise) {
  if (!arrival.expected || !arrival.observation) return std::nullopt;
  const domain::AtSlot& at = *arrival.expected;
  const SignatureMatch match =
      compare(expected_signature(map, at.manhole, at.slot), *arrival.observation, noise);
  if (match.unseen.empty()) return std::nullopt;
  const std::vector<SlotIndex> order = signature_slot_order(map, at.manhole, at.slot);
  return map.slot(at.manhole, order[match.unseen.front()]);
}

std::optional<TurnInManhole> straight_through(const Arrival& arrival, const SewerMap& map,
                                              PipeId pipe,
                                              const localisation::LocalisationOptions& options,
                                              const RobotProfile& profile) {
  if (!arrival.observation || arrival.observation->slots.empty()) return std::nullopt;
  const ManholeSignature& seen = *arrival.observation;
  const SignatureNoise& noise = options.noise;
  // The pipe goes on at the pipe's size: the map's, or the size the robot sees of the mouth it
  // came out of (a pipe narrower than mapped, which the robot has just driven, goes on narrower).
  const auto pipe_size = [&](const SlotSighting& s) {
    return std::abs(s.diameter_m - map.pipe(pipe).diameter_m) <= noise.max_diameter_m ||
           std::abs(s.diameter_m - seen.slots[0].diameter_m) <= noise.max_diameter_m;
  };
  // Straight on within straight_through_deg, seen up to two sightings' noise further (the arrival
  // mouth's and this one's): the window the filter's turn() gives a direction only seen.
  std::optional<std::size_t> best;
  double best_turn = options.straight_through_deg + 2 * noise.direction_deg;
  for (std::size_t i = 1; i < seen.slots.size(); ++i) {
    const SlotSighting& s = seen.slots[i];
    const double turn = std::abs(s.relative_deg - 180.0);  // relative_deg is in [0, 360)
    if (turn > best_turn || !pipe_size(s) || std::abs(s.step_m) > profile.max_step_m) continue;
    best = i;
    best_turn = turn;
  }
  if (!best) return std::nullopt;
  const SlotSighting& s = seen.slots[*best];
  return TurnInManhole{.from_slot = kBySighting,
                       .to_slot = static_cast<std::uint16_t>(*best),
                       .turn_deg = best_turn,
                       .step_m = s.step_m,
                       .manhole_diameter_m = seen.shaft_diameter_m,
                       .duration_s = profile.manhole_pass_s + best_turn * profile.turn_s_per_deg +
                                     std::abs(s.step_m) * profile.step_s_per_m};
}

std::string signature_text(const ManholeSignature& signature) {
  std::ostringstream out;
  out << signature.slots.size() << (signature.slots.size() == 1 ? " slot" : " slots") << " at ";
  for (std::size_t i = 0; i < signature.slots.size(); ++i) {
    out << (i == 0 ? "" : ", ") << std::lround(signature.slots[i].relative_deg);
  }
  out << "°";
  return out.str();
}

Localising::Localising(const SewerMap& map, double odometry_sd_fraction,
                       const localisation::JunctionMemory& memory,
                       localisation::LocalisationOptions options)
    : map_(map), odometry_sd_fraction_(odometry_sd_fraction), options_(std::move(options)) {
  Result<localisation::TopologicalFilter> filter =
      localisation::TopologicalFilter::create(map, options_);
  if (filter.has_value()) filter_.emplace(std::move(*filter));
  // The Replanner checked the memory when it learnt it (Replanner::learn): it fits the map.
  if (filter_) (void)filter_->recall(memory);
}

localisation::JunctionMemory Localising::memory() const {
  return filter_ ? filter_->memory() : localisation::JunctionMemory{};
}

void Localising::reset(const domain::RobotPosition& position, std::uint8_t heading_end) {
  usable_ = false;
  if (!filter_) return;
  localisation::Pose pose{.position = position};
  if (std::holds_alternative<domain::InPipe>(position)) pose.heading_end = heading_end;
  usable_ = filter_->reset(pose).has_value();
}

std::optional<localisation::Hypothesis> Localising::not_at_manhole() {
  if (!filter_ || !usable_) return std::nullopt;
  if (!filter_->not_at_manhole().has_value() || filter_->estimate().lost()) {
    usable_ = false;
    return std::nullopt;
  }
  return filter_->estimate().best();
}

localisation::Estimate Localising::estimate() const {
  if (!filter_ || !usable_) return {};
  return filter_->estimate();
}

std::optional<Arrival> Localising::follow(const Job& job, const hal::JobReport& report,
                                          const domain::RobotPosition& before,
                                          const domain::RobotPosition& after,
                                          std::uint8_t after_heading_end) {
  std::optional<Arrival> arrival = follow_filter(job, report, before, after);
  if (!usable_ && filter_) {
    // An update the filter refused (a drive it cannot follow from the place it has): it starts
    // again from the tracking's place, so that the next arrival is still checked.
    reset(after, after_heading_end);
    ++restarts_;
  }
  return arrival;
}

std::optional<Arrival> Localising::follow_filter(const Job& job, const hal::JobReport& report,
                                                 const domain::RobotPosition& before,
                                                 const domain::RobotPosition& after) {
  if (!usable_) return std::nullopt;
  localisation::TopologicalFilter& filter = *filter_;
  Result<void> step;
  if (const auto* turn = std::get_if<TurnInManhole>(&job)) {
    const auto* at = std::get_if<domain::AtSlot>(&before);
    if (turn->from_slot == kBySighting) {
      // Out through a mouth the robot saw: its direction relative to the arrival's. The angle the
      // joints measured is not fed here: at what the controller takes for a manhole the map lacks
      // it moved weight between the junction and mapped manholes, and on a 1,000-manhole meshed
      // network (5 campaigns of 40 runs) made more arrivals wrong (docs/localisation.md).
      if (report.ok()) {
        if (last_observation_ && turn->to_slot < last_observation_->slots.size()) {
          step = filter.turn(last_observation_->slots[turn->to_slot].relative_deg);
        } else {
          step = Error{ErrorCode::kInvalidArgument, "a turn by a mouth the robot did not see"};
        }
      }
    } else if (report.ok() && at != nullptr) {
      // The plan's passage, weighed by the angle the joints measured (mouths too close for a
      // sighting to tell apart).
      step = filter.pass(at->manhole, SlotIndex{turn->from_slot}, SlotIndex{turn->to_slot},
                         report.turn_measured_deg);
    }
    if (!step.has_value()) usable_ = false;
    return std::nullopt;
  }
  if (const auto* enter = std::get_if<EnterPipeFromManhole>(&job)) {
    if (report.ok()) step = filter.enter(SlotIndex{enter->slot});
    if (!step.has_value()) usable_ = false;
    return std::nullopt;
  }
  const std::optional<DriveDirection> direction = drive_direction(job);
  if (!direction) return std::nullopt;
  const bool arrived =
      report.observation.has_value() ||
      (ends_at_manhole(job) && report.ok() && std::holds_alternative<domain::AtSlot>(after));
  const double driven = std::max(0.0, report.progress_m);
  if (driven > 0 || arrived)
    step = filter.drive(driven, *direction, odometry_sd_fraction_ * driven);
  if (step.has_value() && arrived) {
    step = filter.arrive(report.observation);
  } else if (step.has_value() && driven > 0) {
    step = filter.no_manhole_within(driven);
  }
  if (!step.has_value()) {
    usable_ = false;
    return std::nullopt;
  }
  if (!arrived) return std::nullopt;
  last_observation_ = report.observation;
  Arrival arrival;
  arrival.observation = report.observation;
  arrival.forward = *direction == DriveDirection::kForward;
  if (const auto* at = std::get_if<domain::AtSlot>(&after)) {
    arrival.expected = *at;
    Result<Verification> checked = filter.verify_arrival(at->manhole, at->slot, report.observation);
    if (!checked.has_value()) {
      usable_ = false;
      return std::nullopt;
    }
    arrival.verification = std::move(*checked);
    return arrival;
  }
  // The tracking has the robot in a pipe: a drive of a distance (a scan of the whole pipe, a go-to)
  // that stopped at a manhole. At the far end of the pipe it drove in, the pipe is shorter than the
  // map says and the robot is where the drive was going; anything else does not match.
  const localisation::Estimate estimate = filter.estimate();
  const auto* in = std::get_if<domain::InPipe>(&after);
  if (in != nullptr && !estimate.lost()) {
    const localisation::Hypothesis& best = estimate.best();
    const auto* at = std::get_if<domain::AtSlot>(&best.pose.position);
    if (at != nullptr && !best.pose.at_unmapped_junction &&
        map_.slot(at->manhole, at->slot).pipe == in->pipe &&
        best.probability >= filter.options().verify_probability) {
      arrival.expected = *at;
      arrival.verification.kind = Verification::Kind::kMatches;
      arrival.verification.probability = best.probability;
      arrival.verification.believed = best.pose;
      return arrival;
    }
  }
  arrival.verification = unexpected_stop(estimate, map_);
  return arrival;
}

}  // namespace sewerplan::executor::detail
