// SPDX-License-Identifier: MIT
// The filter's updates: reset, enter, drive, arrive, turn, pass, no_manhole_within.
#include "sewerplan/localisation/topological_filter.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

#include "sewerplan/core/map_queries.h"

#include "likelihoods.h"
#include "track_geometry.h"

namespace sewerplan::localisation {

using detail::kNegativeInfinity;
using Track = TopologicalFilter::Track;

namespace {

Error invalid(std::string message) {
  return Error{ErrorCode::kInvalidArgument, std::move(message)};
}

std::string shown(double value) {
  std::ostringstream os;
  os << value;
  return os.str();
}

bool finite_in(double value, double lo, double hi) {
  return std::isfinite(value) && value >= lo && value <= hi;
}

// A hypothesis in `pipe` facing `heading_end`, `travelled_m` from the other end.
Track in_pipe(const Track& from, PipeId pipe, std::uint8_t heading_end, double travelled_m) {
  Track t = from;
  t.kind = Track::Kind::kInPipe;
  t.pipe = pipe;
  t.heading_end = heading_end;
  t.moving_end = heading_end;
  t.travelled_m = travelled_m;
  t.cleared_m = travelled_m;
  t.leg_from_m = travelled_m;
  t.arrival_misses = 0;
  return t;
}

// A distance along `pipe` from end `from` as counted from end `to`: the map's length between them.
double from_end(const Pipe& pipe, std::uint8_t from, std::uint8_t to, double distance_m) {
  return from == to ? distance_m : pipe.length_m - distance_m;
}

}  // namespace

Result<void> check_options(const LocalisationOptions& o) {
  auto bad = [](std::string_view name, double value, std::string_view range) {
    return invalid("localisation option " + std::string(name) + " = " + shown(value) + " is not " +
                   std::string(range));
  };
  if (!finite_in(o.length_sd_fraction, 0, 1))
    return bad("length_sd_fraction", o.length_sd_fraction, "in [0, 1]");
  if (!finite_in(o.miss_probability, 0, 0.999))
    return bad("miss_probability", o.miss_probability, "in [0, 0.999]");
  if (!finite_in(o.unmapped_junctions_per_m, 0, 1))
    return bad("unmapped_junctions_per_m", o.unmapped_junctions_per_m, "in [0, 1]");
  if (!finite_in(o.min_junction_spacing_m, 0, 100))
    return bad("min_junction_spacing_m", o.min_junction_spacing_m, "in [0, 100]");
  if (!finite_in(o.min_junction_shaft_m, 0, 2))
    return bad("min_junction_shaft_m", o.min_junction_shaft_m, "in [0, 2]");
  if (!finite_in(o.false_detections_per_m, 0, 1))
    return bad("false_detections_per_m", o.false_detections_per_m, "in [0, 1]");
  if (!finite_in(o.odometry_outlier_share, 0, 0.5))
    return bad("odometry_outlier_share", o.odometry_outlier_share, "in [0, 0.5]");
  if (!finite_in(o.odometry_outlier_scale, 1, 100))
    return bad("odometry_outlier_scale", o.odometry_outlier_scale, "in [1, 100]");
  if (o.max_misses < 0 || o.max_misses > 8) return bad("max_misses", o.max_misses, "in [0, 8]");
  if (!finite_in(o.straight_through_deg, 0, 90))
    return bad("straight_through_deg", o.straight_through_deg, "in [0, 90]");
  if (!finite_in(o.prune_ratio, 0, 0.5)) return bad("prune_ratio", o.prune_ratio, "in [0, 0.5]");
  if (o.max_hypotheses == 0) return invalid("localisation option max_hypotheses must be > 0");
  if (!finite_in(o.merge_distance_m, 0, 1000))
    return bad("merge_distance_m", o.merge_distance_m, "in [0, 1000]");
  if (!finite_in(o.ambiguity_probability, 0, 1))
    return bad("ambiguity_probability", o.ambiguity_probability, "in [0, 1]");
  if (!finite_in(o.verify_probability, 0, 1))
    return bad("verify_probability", o.verify_probability, "in [0, 1]");
  if (!finite_in(o.remember_mouth_probability, 0, 1))
    return bad("remember_mouth_probability", o.remember_mouth_probability, "in [0, 1]");
  if (!std::isfinite(o.turn_sd_deg) || o.turn_sd_deg <= 0 || o.turn_sd_deg > 90)
    return bad("turn_sd_deg", o.turn_sd_deg, "in (0, 90]");
  if (!finite_in(o.direction_off_share, 0, 1))
    return bad("direction_off_share", o.direction_off_share, "in [0, 1]");
  if (!finite_in(o.direction_off_max_deg, 0, 180))
    return bad("direction_off_max_deg", o.direction_off_max_deg, "in [0, 180]");
  const SignatureNoise& n = o.noise;
  for (auto [name, value] : {std::pair{"noise.direction_deg", n.direction_deg},
                             {"noise.step_m", n.step_m},
                             {"noise.diameter_m", n.diameter_m},
                             {"noise.shaft_m", n.shaft_m},
                             {"noise.max_direction_deg", n.max_direction_deg},
                             {"noise.max_step_m", n.max_step_m},
                             {"noise.max_diameter_m", n.max_diameter_m},
                             {"noise.max_shaft_m", n.max_shaft_m}}) {
    if (!std::isfinite(value) || value <= 0) return bad(name, value, "finite and > 0");
  }
  for (const auto& [name, value] :
       {std::pair<std::string_view, double>{"noise.mouth_off_share", n.mouth_off_share},
        {"noise.unmapped_mouth_share", n.unmapped_mouth_share}}) {
    if (!std::isfinite(value) || value < 0 || value >= 1) return bad(name, value, "in [0, 1)");
  }
  return {};
}

Result<TopologicalFilter> TopologicalFilter::create(const SewerMap& map,
                                                    LocalisationOptions options) {
  if (Result<void> ok = check_options(options); !ok.has_value()) return ok.error();
  return TopologicalFilter(map, std::move(options));
}

Result<void> TopologicalFilter::usable() const {
  if (mode_ == Mode::kLost) {
    return invalid("the localisation is lost (every hypothesis was ruled out): reset() it");
  }
  return {};
}

Result<void> TopologicalFilter::reset(const Pose& pose) {
  const SewerMap& map = *map_;
  Track t;
  Mode mode = Mode::kInPipe;
  if (const auto* in = std::get_if<domain::InManhole>(&pose.position)) {
    if (in->manhole.index() >= map.manhole_count())
      return invalid("reset: no manhole " + shown(in->manhole.value()) + " in the map");
    t.kind = Track::Kind::kInManhole;
    t.manhole = in->manhole;
    mode = Mode::kInManhole;
  } else if (const auto* at = std::get_if<domain::AtSlot>(&pose.position)) {
    if (at->manhole.index() >= map.manhole_count())
      return invalid("reset: no manhole " + shown(at->manhole.value()) + " in the map");
    const Manhole& m = map.manhole(at->manhole);
    if (at->slot.value() >= m.slot_count) {
      return invalid("reset: " + m.name + " has no slot " +
                     std::to_string(to_paper_number(at->slot)));
    }
    const Slot& slot = map.slot(at->manhole, at->slot);
    t.kind = Track::Kind::kAtMouth;
    t.manhole = at->manhole;
    t.slot = at->slot;
    t.pipe = slot.pipe;
    t.heading_end = slot.pipe_end;
    t.moving_end = slot.pipe_end;
    t.travelled_m = map.pipe(slot.pipe).length_m;
    t.cleared_m = t.anchor_m = t.leg_from_m = t.travelled_m;
    mode = Mode::kAtManhole;
  } else {
    const auto& pipe_place = std::get<domain::InPipe>(pose.position);
    if (pipe_place.pipe.index() >= map.pipe_count())
      return invalid("reset: no pipe " + shown(pipe_place.pipe.value()) + " in the map");
    const Pipe& pipe = map.pipe(pipe_place.pipe);
    if (!finite_in(pipe_place.offset_m, 0, pipe.length_m)) {
      return invalid("reset: offset " + shown(pipe_place.offset_m) + " m is not in " + pipe.name +
                     " (0 to " + shown(pipe.length_m) + " m)");
    }
    if (!pose.heading_end || *pose.heading_end > 1)
      return invalid("reset: a pose in pipe " + pipe.name + " needs a heading end, 0 or 1");
    t.kind = pose.at_unmapped_junction ? Track::Kind::kAtJunction : Track::Kind::kInPipe;
    t.pipe = pipe_place.pipe;
    t.heading_end = *pose.heading_end;
    t.moving_end = t.heading_end;
    t.travelled_m = t.heading_end == 1 ? pipe_place.offset_m : pipe.length_m - pipe_place.offset_m;
    t.cleared_m = t.travelled_m;
    t.anchor_m = t.leg_from_m = t.travelled_m;
    mode = pose.at_unmapped_junction ? Mode::kAtManhole : Mode::kInPipe;
  }
  tracks_.assign(1, std::move(t));
  mode_ = mode;
  arrived_by_ = last_drive_ = DriveDirection::kForward;
  return {};
}

Result<void> TopologicalFilter::enter(SlotIndex slot) {
  if (Result<void> ok = usable(); !ok.has_value()) return ok;
  if (mode_ != Mode::kInManhole) return invalid("enter: the robot is not in a start manhole");
  const SewerMap& map = *map_;
  for (const Track& t : tracks_) {
    const Manhole& m = map.manhole(t.manhole);
    if (slot.value() >= m.slot_count) {
      return invalid("enter: " + m.name + " has no slot " + std::to_string(to_paper_number(slot)));
    }
  }
  for (Track& t : tracks_) {
    const Slot& s = map.slot(t.manhole, slot);
    const auto heading = static_cast<std::uint8_t>(1 - s.pipe_end);
    t = in_pipe(t, s.pipe, heading, 0.0);
    t.odometry_var_m2 = t.map_var_m2 = 0;
    t.anchor_m = 0;
  }
  mode_ = Mode::kInPipe;
  return {};
}

Result<void> TopologicalFilter::drive(double odometry_m, DriveDirection direction, double sigma_m) {
  if (!std::isfinite(odometry_m) || odometry_m < 0)
    return invalid("drive: odometry " + shown(odometry_m) + " m is not a distance >= 0");
  if (!std::isfinite(sigma_m) || sigma_m < 0)
    return invalid("drive: odometry sigma " + shown(sigma_m) + " m is not >= 0");
  if (Result<void> ok = usable(); !ok.has_value()) return ok;
  if (mode_ == Mode::kInManhole)
    return invalid("drive: in the start manhole: enter() a pipe first");
  const SewerMap& map = *map_;
  bool dropped = false;
  for (Track& t : tracks_) {
    // On into the manhole it arrived at (the robot took it for a false detection): a hypothesis
    // at a mouth or a junction is held there by the pipe's end; one in the pipe drives on.
    const bool at_manhole = t.kind == Track::Kind::kAtMouth || t.kind == Track::Kind::kAtJunction;
    if (at_manhole && direction == arrived_by_ && (mode_ == Mode::kAtManhole || t.held)) {
      if (!t.held) t.odometry_var_m2 = t.map_var_m2 = 0;
      t.held = true;
      t.held_m += odometry_m;
      t.odometry_var_m2 += sigma_m * sigma_m;
      // A robot held there does not read metres: this hypothesis cannot explain the drive.
      if (!detail::held_in_reach(options_, t)) {
        t.log_weight = kNegativeInfinity;
        dropped = true;
      }
      continue;
    }
    t.held = false;
    t.held_m = 0;
    const double length = map.pipe(t.pipe).length_m;
    if (t.kind == Track::Kind::kAtMouth) {
      // Back out of the mouth into the pipe it arrived by.
      const bool mouth_ahead = map.slot(t.manhole, t.slot).pipe_end == t.heading_end;
      t.kind = Track::Kind::kInPipe;
      t.travelled_m = mouth_ahead ? length : 0.0;
      t.odometry_var_m2 = t.map_var_m2 = 0;
      t.anchor_m = t.leg_from_m = t.travelled_m;
    }
    t.kind = Track::Kind::kInPipe;
    const bool forward = direction == DriveDirection::kForward;
    t.moving_end = forward ? t.heading_end : static_cast<std::uint8_t>(1 - t.heading_end);
    // Backing past the mouth behind it goes below 0 until arrive() or no_manhole_within()
    // explains it (the pipe straight on beyond a manhole passed unseen).
    t.travelled_m += forward ? odometry_m : -odometry_m;
    t.odometry_var_m2 += sigma_m * sigma_m;
  }
  mode_ = Mode::kInPipe;
  last_drive_ = direction;
  if (dropped) normalise_and_prune();
  return {};
}

Result<void> TopologicalFilter::arrive(const std::optional<ManholeSignature>& observation) {
  if (observation) {
    if (Result<void> ok = check_signature(*observation); !ok.has_value()) {
      return invalid("arrive: the observed signature is not one a robot could see: " +
                     ok.error().message);
    }
  }
  if (Result<void> ok = usable(); !ok.has_value()) return ok;
  if (mode_ != Mode::kInPipe) return invalid("arrive: the robot has not driven since it stopped");
  scratch_.clear();
  for (const Track& t : tracks_) detail::explain_arrival(*this, t, observation, scratch_);
  tracks_.swap(scratch_);
  mode_ = Mode::kAtManhole;
  arrived_by_ = last_drive_;
  normalise_and_prune();
  remember_arrival(observation);
  return {};
}

Result<void> TopologicalFilter::no_manhole_within(double distance_m) {
  if (!std::isfinite(distance_m) || distance_m < 0)
    return invalid("no_manhole_within: distance " + shown(distance_m) + " m is not >= 0");
  if (Result<void> ok = usable(); !ok.has_value()) return ok;
  if (mode_ != Mode::kInPipe) return invalid("no_manhole_within: the robot is not in a pipe");
  scratch_.clear();
  for (const Track& t : tracks_) detail::explain_no_arrival(*this, t, distance_m, scratch_);
  tracks_.swap(scratch_);
  normalise_and_prune();
  return {};
}

Result<void> TopologicalFilter::not_at_manhole() {
  if (Result<void> ok = usable(); !ok.has_value()) return ok;
  if (mode_ != Mode::kAtManhole) return invalid("not_at_manhole: the robot has not arrived");
  for (Track& t : tracks_) {
    if (t.kind == Track::Kind::kAtJunction) {
      // Where the junction was taken to be, there was nothing: a false detection at that place.
      t.kind = Track::Kind::kInPipe;
      if (!t.assumptions.empty() &&
          t.assumptions.front().kind == Assumption::Kind::kUnmappedJunction) {
        t.assumptions.front().kind = Assumption::Kind::kFalseDetection;
      }
    } else if (t.kind != Track::Kind::kInPipe) {
      t.log_weight = kNegativeInfinity;
    }
  }
  normalise_and_prune();
  return {};
}

namespace {

Result<void> check_measured(std::string_view update, std::optional<double> measured_deg) {
  if (measured_deg && (!std::isfinite(*measured_deg) || *measured_deg < 0 || *measured_deg >= 360))
    return invalid(std::string(update) + ": measured turn " + shown(*measured_deg) +
                   " degrees is not in [0, 360)");
  return {};
}

}  // namespace

Result<void> TopologicalFilter::turn(double relative_deg, std::optional<double> measured_deg) {
  if (!std::isfinite(relative_deg) || relative_deg < 0 || relative_deg >= 360)
    return invalid("turn: direction " + shown(relative_deg) + " is not in [0, 360)");
  if (Result<void> ok = check_measured("turn", measured_deg); !ok.has_value()) return ok;
  if (Result<void> ok = usable(); !ok.has_value()) return ok;
  if (mode_ != Mode::kAtManhole) return invalid("turn: the robot is not at a manhole");
  scratch_.clear();
  for (const Track& t : tracks_) {
    if (std::optional<Track> next =
            detail::turned(*this, t, relative_deg, std::nullopt, measured_deg))
      scratch_.push_back(std::move(*next));
  }
  tracks_.swap(scratch_);
  mode_ = Mode::kInPipe;
  normalise_and_prune();
  return {};
}

Result<void> TopologicalFilter::pass(ManholeId manhole, SlotIndex from, SlotIndex to,
                                     std::optional<double> measured_deg) {
  const SewerMap& map = *map_;
  if (manhole.index() >= map.manhole_count())
    return invalid("pass: no manhole " + shown(manhole.value()) + " in the map");
  const Manhole& m = map.manhole(manhole);
  for (SlotIndex s : {from, to}) {
    if (s.value() >= m.slot_count)
      return invalid("pass: " + m.name + " has no slot " + std::to_string(to_paper_number(s)));
  }
  if (from == to) return invalid("pass: from and to are the same slot of " + m.name);
  if (Result<void> ok = check_measured("pass", measured_deg); !ok.has_value()) return ok;
  if (Result<void> ok = usable(); !ok.has_value()) return ok;
  if (mode_ != Mode::kAtManhole) return invalid("pass: the robot is not at a manhole");
  const double relative =
      detail::ccw_deg(map.slot(manhole, from).azimuth_deg, map.slot(manhole, to).azimuth_deg);
  const Passage passage{manhole, from, to};
  scratch_.clear();
  for (const Track& t : tracks_) {
    if (std::optional<Track> next = detail::turned(*this, t, relative, passage, measured_deg))
      scratch_.push_back(std::move(*next));
  }
  tracks_.swap(scratch_);
  mode_ = Mode::kInPipe;
  normalise_and_prune();
  return {};
}

namespace {

// Hypotheses that are one place: the same mouth, or the same pipe and heading within `merge_m`.
bool same_place(const Track& a, const Track& b, double merge_m) {
  if (a.kind != b.kind) return false;
  switch (a.kind) {
    case Track::Kind::kInManhole:
      return a.manhole == b.manhole;
    case Track::Kind::kAtMouth:
      return a.manhole == b.manhole && a.slot == b.slot;
    case Track::Kind::kInPipe:
    case Track::Kind::kAtJunction:
      return a.pipe == b.pipe && a.heading_end == b.heading_end &&
             std::abs(a.travelled_m - b.travelled_m) <= merge_m;
  }
  return false;
}

}  // namespace

void TopologicalFilter::normalise_and_prune() {
  // Most likely first; ties in a fixed order of place, so that the result is deterministic.
  std::stable_sort(tracks_.begin(), tracks_.end(),
                   [](const Track& a, const Track& b) { return a.log_weight > b.log_weight; });
  // Merge: a later (less likely) hypothesis at the same place adds its weight to the first.
  std::vector<Track> kept;
  kept.reserve(tracks_.size());
  for (Track& t : tracks_) {
    if (t.log_weight == kNegativeInfinity || std::isnan(t.log_weight)) continue;
    auto same = std::find_if(kept.begin(), kept.end(), [&](const Track& k) {
      return same_place(k, t, options_.merge_distance_m);
    });
    if (same == kept.end()) {
      kept.push_back(std::move(t));
      continue;
    }
    const double total = detail::log_add(same->log_weight, t.log_weight);
    const double wa = std::exp(same->log_weight - total);
    const double wb = 1 - wa;
    // The merged place and variance: the mixture's moments.
    const double mean = wa * same->travelled_m + wb * t.travelled_m;
    const double spread =
        wa * std::pow(same->travelled_m - mean, 2) + wb * std::pow(t.travelled_m - mean, 2);
    // The places' spread is no slip of the odometry's: the map's part.
    same->odometry_var_m2 = wa * same->odometry_var_m2 + wb * t.odometry_var_m2;
    same->map_var_m2 = wa * same->map_var_m2 + wb * t.map_var_m2 + spread;
    same->travelled_m = mean;
    same->log_weight = total;
  }
  if (kept.empty()) {
    tracks_.clear();
    mode_ = Mode::kLost;
    return;
  }
  std::stable_sort(kept.begin(), kept.end(),
                   [](const Track& a, const Track& b) { return a.log_weight > b.log_weight; });
  const double floor = kept.front().log_weight + std::log(options_.prune_ratio);
  std::size_t n = 0;
  while (n < kept.size() && n < options_.max_hypotheses && kept[n].log_weight >= floor) ++n;
  kept.resize(n);
  double total = kNegativeInfinity;
  for (const Track& t : kept) total = detail::log_add(total, t.log_weight);
  for (Track& t : kept) t.log_weight -= total;
  tracks_.swap(kept);
}

namespace {

bool by_pipe(const KnownJunction& a, const KnownJunction& b) { return a.pipe < b.pipe; }
bool stretch_by_pipe(const DrivenStretch& a, const DrivenStretch& b) { return a.pipe < b.pipe; }
bool mouth_by_manhole(const KnownMouth& a, const KnownMouth& b) { return a.manhole < b.manhole; }
bool mouth_by_place(const KnownMouth& a, const KnownMouth& b) {
  return a.manhole != b.manhole ? a.manhole < b.manhole : a.azimuth_deg < b.azimuth_deg;
}

// log(e^a + e^b), either of them minus infinity.
double log_sum(double a, double b) {
  if (a < b) std::swap(a, b);
  if (b == kNegativeInfinity) return a;
  return a + std::log1p(std::exp(b - a));
}

// The map's signature of `manhole` entered through `arrival`, with the known mouths [first, last)
// there added in order; `origin` gets, per slot of the result, the known mouth it stands for, or
// last for a mouth of the map.
template <class It>
ManholeSignature with_known_mouths(const SewerMap& map, ManholeId manhole, SlotIndex arrival,
                                   It first, It last, std::vector<It>* origin = nullptr) {
  ManholeSignature expected = expected_signature(map, manhole, arrival);
  const Slot& in = map.slot(manhole, arrival);
  std::vector<std::pair<SlotSighting, It>> slots;
  slots.reserve(expected.slots.size() + static_cast<std::size_t>(last - first));
  for (const SlotSighting& s : expected.slots) slots.emplace_back(s, last);
  for (It k = first; k != last; ++k) {
    slots.emplace_back(SlotSighting{.relative_deg = ccw_deg(in.azimuth_deg, k->azimuth_deg),
                                    .step_m = k->invert_z_m - in.invert_z_m,
                                    .diameter_m = k->diameter_m},
                       k);
  }
  // slots[0] stays the arrival's.
  std::stable_sort(slots.begin() + 1, slots.end(), [](const auto& a, const auto& b) {
    return a.first.relative_deg < b.first.relative_deg;
  });
  expected.slots.clear();
  if (origin != nullptr) origin->clear();
  for (const auto& [s, k] : slots) {
    expected.slots.push_back(s);
    if (origin != nullptr) origin->push_back(k);
  }
  return expected;
}

}  // namespace

double TopologicalFilter::junction_log_density(PipeId pipe_id, std::uint8_t end, double distance_m,
                                               double var_m2) const {
  const Pipe& pipe = map_->pipe(pipe_id);
  const double length_var = std::pow(options_.length_sd_fraction * pipe.length_m, 2);
  double density = 0;
  const KnownJunction key{.pipe = pipe_id};
  const auto [first, last] =
      std::equal_range(memory_.junctions.begin(), memory_.junctions.end(), key, by_pipe);
  for (auto k = first; k != last; ++k) {
    // Counted from the other end, the map's length lies between the two places.
    const double var = var_m2 + k->var_m2 + (k->from_end == end ? 0.0 : length_var);
    density += std::exp(
        detail::log_normal(distance_m, from_end(pipe, k->from_end, end, k->distance_m), var));
  }
  double fresh = options_.unmapped_junctions_per_m;
  const DrivenStretch stretch_key{.pipe = pipe_id};
  const auto [from, to] =
      std::equal_range(memory_.driven.begin(), memory_.driven.end(), stretch_key, stretch_by_pipe);
  for (auto s = from; s != to; ++s) {
    const double a = from_end(pipe, s->from_end, end, s->from_m);
    const double b = from_end(pipe, s->from_end, end, s->to_m);
    // Well inside it (two standard deviations of the place, and of the length between the ends).
    const double margin = 2 * std::sqrt(var_m2 + (s->from_end == end ? 0.0 : length_var));
    if (distance_m >= std::min(a, b) + margin && distance_m <= std::max(a, b) - margin) {
      fresh *= options_.miss_probability;  // driven there before without detecting it
      break;
    }
  }
  return density + fresh > 0 ? std::log(density + fresh) : kNegativeInfinity;
}

double TopologicalFilter::mapped_log_likelihood(ManholeId manhole, SlotIndex arrival,
                                                const ManholeSignature& observed) const {
  const double mapped =
      compare(expected_signature(*map_, manhole, arrival), observed, options_.noise).log_likelihood;
  const auto [first, last] = std::equal_range(memory_.mouths.begin(), memory_.mouths.end(),
                                              KnownMouth{.manhole = manhole}, mouth_by_manhole);
  if (first == last) return mapped;
  int sightings = first->sightings;
  for (auto k = first; k != last; ++k) sightings = std::min(sightings, k->sightings);
  const double with =
      compare(with_known_mouths(*map_, manhole, arrival, first, last), observed, options_.noise)
          .log_likelihood;
  const double there = static_cast<double>(sightings) / (sightings + 1.0);
  return log_sum(std::log(there) + with, std::log1p(-there) + mapped);
}

void TopologicalFilter::remember_mouths(ManholeId manhole, SlotIndex arrival,
                                        const ManholeSignature& observed) {
  const auto [first, last] = std::equal_range(memory_.mouths.begin(), memory_.mouths.end(),
                                              KnownMouth{.manhole = manhole}, mouth_by_manhole);
  using It = std::vector<KnownMouth>::iterator;
  std::vector<It> origin;
  const ManholeSignature expected =
      with_known_mouths(*map_, manhole, arrival, first, last, &origin);
  const SignatureMatch match = compare(expected, observed, options_.noise);
  // Each known mouth here seen again (+1) or not (-1).
  std::vector<int> seen(static_cast<std::size_t>(last - first), 0);
  for (std::size_t i = 0; i < origin.size(); ++i) {
    if (origin[i] == last) continue;
    const bool unseen =
        std::find(match.unseen.begin(), match.unseen.end(), i) != match.unseen.end();
    seen[static_cast<std::size_t>(origin[i] - first)] = unseen ? -1 : 1;
  }
  // The mouths seen that nothing expected: new ones, unless a known one unseen is within the
  // pairing's reach (one near the arrival's direction sorts first or last as the noise has it):
  // that one seen, not a second mouth.
  std::vector<KnownMouth> found;
  const Slot& in = map_->slot(manhole, arrival);
  for (const std::size_t j : match.unexpected) {
    const SlotSighting& s = observed.slots[j];
    const double azimuth = ccw_deg(0.0, in.azimuth_deg + s.relative_deg);
    const auto near = [&](const KnownMouth& k) {
      return std::abs(normalize_deg(k.azimuth_deg - azimuth)) <= options_.noise.max_direction_deg;
    };
    if (const It same = std::find_if(first, last, near); same != last) {
      seen[static_cast<std::size_t>(same - first)] = 1;
      continue;
    }
    found.push_back({.manhole = manhole,
                     .azimuth_deg = azimuth,
                     .invert_z_m = in.invert_z_m + s.step_m,
                     .diameter_m = s.diameter_m});
  }
  // A mouth not seen counts one fewer and is forgotten at none (a sensing error seen once is not
  // expected for ever).
  bool forgot = false;
  for (It k = first; k != last; ++k) {
    k->sightings += seen[static_cast<std::size_t>(k - first)];
    forgot = forgot || k->sightings <= 0;
  }
  if (forgot) std::erase_if(memory_.mouths, [](const KnownMouth& k) { return k.sightings <= 0; });
  for (const KnownMouth& k : found) {
    memory_.mouths.insert(
        std::upper_bound(memory_.mouths.begin(), memory_.mouths.end(), k, mouth_by_place), k);
  }
}

Result<void> check_memory(const JunctionMemory& memory, const SewerMap& map) {
  const auto within = [&](const Pipe& pipe, double d) {
    return std::isfinite(d) && d >= 0 && d <= pipe.length_m;
  };
  for (std::size_t i = 0; i < memory.junctions.size(); ++i) {
    const KnownJunction& j = memory.junctions[i];
    const std::string what = "remembered junction " + std::to_string(i + 1);
    if (j.pipe.index() >= map.pipe_count())
      return invalid(what + ": no pipe " + shown(j.pipe.value()) + " in the map");
    const Pipe& pipe = map.pipe(j.pipe);
    if (j.from_end > 1) return invalid(what + " in " + pipe.name + ": end must be 0 or 1");
    if (!within(pipe, j.distance_m)) {
      return invalid(what + " in " + pipe.name + ": distance " + shown(j.distance_m) +
                     " m is outside the pipe (0 to " + shown(pipe.length_m) + " m)");
    }
    if (!(std::isfinite(j.var_m2) && j.var_m2 > 0))
      return invalid(what + " in " + pipe.name + ": variance " + shown(j.var_m2) + " is not > 0");
    if (j.sightings < 1) return invalid(what + " in " + pipe.name + ": no sighting");
  }
  for (std::size_t i = 0; i < memory.driven.size(); ++i) {
    const DrivenStretch& s = memory.driven[i];
    const std::string what = "driven stretch " + std::to_string(i + 1);
    if (s.pipe.index() >= map.pipe_count())
      return invalid(what + ": no pipe " + shown(s.pipe.value()) + " in the map");
    const Pipe& pipe = map.pipe(s.pipe);
    if (s.from_end > 1) return invalid(what + " in " + pipe.name + ": end must be 0 or 1");
    if (!within(pipe, s.from_m) || !within(pipe, s.to_m) || !(s.from_m < s.to_m)) {
      return invalid(what + " in " + pipe.name + ": " + shown(s.from_m) + " to " + shown(s.to_m) +
                     " m is not a stretch of the pipe (0 to " + shown(pipe.length_m) + " m)");
    }
  }
  for (std::size_t i = 0; i < memory.mouths.size(); ++i) {
    const KnownMouth& k = memory.mouths[i];
    const std::string what = "remembered mouth " + std::to_string(i + 1);
    if (k.manhole.index() >= map.manhole_count())
      return invalid(what + ": no manhole " + shown(k.manhole.value()) + " in the map");
    const std::string at = what + " in " + map.manhole(k.manhole).name;
    if (!(std::isfinite(k.azimuth_deg) && k.azimuth_deg >= 0 && k.azimuth_deg < 360))
      return invalid(at + ": direction " + shown(k.azimuth_deg) + " is not in [0, 360)");
    if (!std::isfinite(k.invert_z_m))
      return invalid(at + ": invert " + shown(k.invert_z_m) + " m is not a number");
    if (!(std::isfinite(k.diameter_m) && k.diameter_m > 0))
      return invalid(at + ": diameter " + shown(k.diameter_m) + " m is not > 0");
    if (k.sightings < 1) return invalid(at + ": no sighting");
  }
  return {};
}

Result<void> TopologicalFilter::recall(JunctionMemory memory) {
  if (auto ok = check_memory(memory, *map_); !ok.has_value()) return ok;
  std::stable_sort(memory.junctions.begin(), memory.junctions.end(),
                   [](const KnownJunction& a, const KnownJunction& b) {
                     return a.pipe != b.pipe ? a.pipe < b.pipe : a.distance_m < b.distance_m;
                   });
  std::stable_sort(memory.driven.begin(), memory.driven.end(), stretch_by_pipe);
  std::stable_sort(memory.mouths.begin(), memory.mouths.end(), mouth_by_place);
  memory_ = std::move(memory);
  return {};
}

void TopologicalFilter::remember_arrival(const std::optional<ManholeSignature>& observation) {
  if (mode_ == Mode::kLost) return;
  const Track& best = tracks_.front();
  if (best.kind == Track::Kind::kAtMouth && observation &&
      std::exp(best.log_weight) >= options_.remember_mouth_probability) {
    remember_mouths(best.manhole, best.slot, *observation);
  }
  if (std::exp(best.log_weight) >= options_.verify_probability &&
      best.kind != Track::Kind::kInManhole) {
    const Pipe& pipe = map_->pipe(best.pipe);
    const auto end = static_cast<std::uint8_t>(1 - best.heading_end);
    // The stretch driven since the last stop in this pipe, without a detection.
    const double a = std::clamp(best.leg_from_m, 0.0, pipe.length_m);
    const double b = std::clamp(best.travelled_m, 0.0, pipe.length_m);
    if (a != b) {
      DrivenStretch s{
          .pipe = best.pipe, .from_end = end, .from_m = std::min(a, b), .to_m = std::max(a, b)};
      memory_.driven.insert(
          std::upper_bound(memory_.driven.begin(), memory_.driven.end(), s, stretch_by_pipe), s);
    }
    // A junction within three standard deviations of the map's length from a mapped end is not
    // told apart from that end's manhole with a lateral the map lacks: not remembered.
    const double length_sd = options_.length_sd_fraction * pipe.length_m;
    const bool clear_of_ends =
        best.travelled_m >= 3 * length_sd && best.travelled_m <= pipe.length_m - 3 * length_sd;
    if (best.kind == Track::Kind::kAtJunction && clear_of_ends) {
      const double var = best.odometry_var_m2 + best.map_var_m2 +
                         std::pow(options_.length_sd_fraction * best.anchor_m, 2);
      const double length_var = std::pow(options_.length_sd_fraction * pipe.length_m, 2);
      KnownJunction j{.pipe = best.pipe,
                      .from_end = end,
                      .distance_m = best.travelled_m,
                      .var_m2 = std::max(var, detail::kMinVarianceM2)};
      auto [first, last] =
          std::equal_range(memory_.junctions.begin(), memory_.junctions.end(), j, by_pipe);
      // The same junction again (within three standard deviations): the two places combined.
      auto same = std::find_if(first, last, [&](const KnownJunction& k) {
        const double here = from_end(pipe, end, k.from_end, j.distance_m);
        const double v = k.var_m2 + j.var_m2 + (k.from_end == end ? 0.0 : length_var);
        return std::abs(here - k.distance_m) <= 3 * std::sqrt(v);
      });
      if (same != last) {
        const double here = from_end(pipe, end, same->from_end, j.distance_m);
        const double v = j.var_m2 + (same->from_end == end ? 0.0 : length_var);
        const double w = same->var_m2 / (same->var_m2 + v);
        same->distance_m += w * (here - same->distance_m);
        same->var_m2 = same->var_m2 * v / (same->var_m2 + v);
        ++same->sightings;
      } else {
        auto at = std::find_if(first, last,
                               [&](const KnownJunction& k) { return k.distance_m > j.distance_m; });
        memory_.junctions.insert(at, j);
      }
    }
  }
  // A new stretch starts at every detection.
  for (Track& t : tracks_) t.leg_from_m = t.travelled_m;
}

}  // namespace sewerplan::localisation
