// SPDX-License-Identifier: MIT
#include "track_geometry.h"

#include <algorithm>
#include <cmath>

#include "sewerplan/core/map_queries.h"

#include "likelihoods.h"

namespace sewerplan::localisation::detail {
namespace {

double log_or_never(double probability) {
  return probability > 0 ? std::log(probability) : kNegativeInfinity;
}

double offset_from_start(const Pipe& pipe, std::uint8_t heading_end, double travelled_m) {
  return heading_end == 1 ? travelled_m : pipe.length_m - travelled_m;
}

void assume(Track& track, Assumption assumption) {
  track.assumptions.insert(track.assumptions.begin(), assumption);
  if (track.assumptions.size() > kMaxAssumptions) track.assumptions.resize(kMaxAssumptions);
}

// The manholes passed unseen on the way, oldest first, as assumptions on `track`.
void assume_missed(Track& track, const std::vector<ManholeId>& passed) {
  for (ManholeId m : passed) {
    assume(track, {.kind = Assumption::Kind::kMissedManhole, .manhole = m});
  }
}

OdometryTails tails(const LocalisationOptions& o) {
  return {.share = o.odometry_outlier_share, .scale = o.odometry_outlier_scale};
}

// The spread of a place whose odometry has variance `odometry_var` and the map's lengths `map_var`.
PlaceSpread spread(const LocalisationOptions& o, double odometry_var, double map_var) {
  return {.odometry_var = odometry_var, .map_var = map_var, .tails = tails(o)};
}

// One pipe of the chain a forward-moving hypothesis may have reached by missing manholes.
struct ChainStep {
  PipeId pipe{0};
  std::uint8_t heading_end = 1;
  double base_m = 0;  // where this pipe starts, in the hypothesis's travelled coordinate
  // Variance of the robot's place relative to base_m: the odometry's, and the map's (the lengths
  // of the pipes passed unseen).
  double odometry_var = 0;
  double map_var = 0;
  double length_var = 0;  // variance of this pipe's length left ahead
  double log_pass = 0;    // log P(every earlier mouth passed unseen)
  std::vector<ManholeId> passed;
};

// Walks `track`'s chain ahead (up to max_misses manholes passed straight on), calling
// visit(step, mouth_at_m, place, log_beyond_lower) for each pipe; stops where the robot cannot have
// gone. A manhole passed unseen goes on into each mouth that may be its straight on (see
// chain_onward): the chain branches there.
template <class Visit>
void walk_chain_from(const TopologicalFilter& filter, ChainStep step, int k, double lower0_m,
                     double t, Visit& visit) {
  const SewerMap& map = filter.map();
  const LocalisationOptions& o = filter.options();
  const double log_miss = log_or_never(o.miss_probability);
  const Pipe& pipe = map.pipe(step.pipe);
  const double mouth = step.base_m + pipe.length_m;
  const PlaceSpread place = spread(o, step.odometry_var, step.map_var + step.length_var);
  const double sd =
      std::sqrt(std::max(step.odometry_var + step.map_var + step.length_var, kMinVarianceM2));
  const double lower = k == 0 ? lower0_m : step.base_m;
  // Known: the mouth lies beyond `lower` (nothing was detected before it).
  const double log_beyond_lower = log_phi_within(mouth - lower, place);
  visit(step, mouth, place, log_beyond_lower);
  const PipeEnd& far = pipe.ends[step.heading_end];
  if (k == o.max_misses || !far.manhole || log_miss == kNegativeInfinity) return;
  if (mouth - 4 * sd > t) return;  // the mouth is well ahead: not passed
  const double log_passed = log1m_exp(log_phi_within(mouth - t, place) - log_beyond_lower);
  for (const auto& [next, log_map_off] : chain_onward(map, o, *far.manhole, far.slot)) {
    ChainStep on = step;
    on.log_pass += log_miss + log_passed + log_map_off;
    if (on.log_pass == kNegativeInfinity) continue;
    on.passed.push_back(*far.manhole);
    const Slot& slot = map.slot(*far.manhole, next);
    on.pipe = slot.pipe;
    on.heading_end = static_cast<std::uint8_t>(1 - slot.pipe_end);
    on.base_m = mouth;
    on.map_var += on.length_var;
    on.length_var = std::pow(o.length_sd_fraction * map.pipe(slot.pipe).length_m, 2);
    walk_chain_from(filter, std::move(on), k + 1, lower0_m, t, visit);
  }
}

template <class Visit>
void walk_chain(const TopologicalFilter& filter, const Track& track, double lower0_m, Visit visit) {
  const SewerMap& map = filter.map();
  const LocalisationOptions& o = filter.options();
  ChainStep step{.pipe = track.pipe,
                 .heading_end = track.heading_end,
                 .odometry_var = track.odometry_var_m2,
                 .map_var = track.map_var_m2,
                 .length_var = std::pow(
                     o.length_sd_fraction * (map.pipe(track.pipe).length_m - track.anchor_m), 2)};
  walk_chain_from(filter, std::move(step), 0, lower0_m, track.travelled_m, visit);
}

// `track` moved into the chain step's pipe at `here_m` from its start.
Track placed(const Track& track, const ChainStep& step, double here_m, bool first) {
  Track c = track;
  c.pipe = step.pipe;
  c.heading_end = step.heading_end;
  c.moving_end = step.heading_end;
  c.travelled_m = here_m;
  c.cleared_m = here_m;
  if (!first) {
    c.odometry_var_m2 = step.odometry_var;
    c.map_var_m2 = step.map_var;
    c.anchor_m = 0;
    c.leg_from_m = 0;
  }
  c.arrival_misses = static_cast<std::uint8_t>(step.passed.size());
  assume_missed(c, step.passed);
  return c;
}

}  // namespace

double ccw_deg(double from_deg, double to_deg) {
  double a = std::fmod(to_deg - from_deg, 360.0);
  if (a < 0) a += 360.0;
  if (a >= 360.0) a -= 360.0;
  return a;
}

MouthAhead mouth_ahead(const SewerMap& map, const Track& track) {
  const Pipe& pipe = map.pipe(track.pipe);
  const PipeEnd& end = pipe.ends[track.moving_end];
  return {.manhole = end.manhole,
          .slot = end.slot,
          .at_m = track.moving_end == track.heading_end ? pipe.length_m : 0.0};
}

std::optional<SlotIndex> slot_towards(const SewerMap& map, ManholeId manhole, SlotIndex arrival,
                                      double relative_deg, double tolerance_deg) {
  const double base = map.slot(manhole, arrival).azimuth_deg;
  std::optional<SlotIndex> best;
  double best_off = tolerance_deg;
  const std::uint16_t n = map.manhole(manhole).slot_count;
  for (std::uint16_t s = 0; s < n; ++s) {
    if (s == arrival.value()) continue;
    const double off = std::abs(
        normalize_deg(ccw_deg(base, map.slot(manhole, SlotIndex{s}).azimuth_deg) - relative_deg));
    if (off <= best_off) {
      if (best && off == best_off) continue;  // the first of equals
      best = SlotIndex{s};
      best_off = off;
    }
  }
  return best;
}

std::vector<std::pair<SlotIndex, double>> chain_onward(const SewerMap& map,
                                                       const LocalisationOptions& o,
                                                       ManholeId manhole, SlotIndex arrival) {
  std::vector<std::pair<SlotIndex, double>> onward;
  const std::uint16_t n = map.manhole(manhole).slot_count;
  for (std::uint16_t s = 0; s < n; ++s) {
    if (s == arrival.value()) continue;
    const double excess =
        turn_off_straight_deg(map, manhole, arrival, SlotIndex{s}) - o.straight_through_deg;
    if (excess <= 0) {
      onward.emplace_back(SlotIndex{s}, 0.0);
    } else if (excess < o.direction_off_max_deg) {
      onward.emplace_back(
          SlotIndex{s}, std::log(o.direction_off_share * (1.0 - excess / o.direction_off_max_deg)));
    }
  }
  return onward;
}

double turn_off_straight_deg(const SewerMap& map, ManholeId manhole, SlotIndex arrival,
                             SlotIndex to) {
  return std::abs(normalize_deg(
      ccw_deg(map.slot(manhole, arrival).azimuth_deg, map.slot(manhole, to).azimuth_deg) - 180.0));
}

namespace {

// The explanations of one hypothesis's arrival, appended to `out`.
struct ArrivalExplainer {
  const TopologicalFilter& filter;
  const SewerMap& map;
  const LocalisationOptions& o;
  const Track& track;
  const std::optional<ManholeSignature>& observation;
  std::vector<Track>& out;
  double log_detect = std::log1p(-o.miss_probability);
  double log_false = log_or_never(o.false_detections_per_m);

  // How well the observation fits the map's manhole `m` entered through `slot` (with the mouths
  // the filter learnt there).
  double mapped_fit(ManholeId m, SlotIndex slot) const {
    return observation ? filter.mapped_log_likelihood(m, slot, *observation) : 0.0;
  }

  // At the mouth of `m`'s `slot`, `log_place` the odometry's and the misses' part of the weight.
  void at_mouth(Track c, ManholeId m, SlotIndex slot, double log_place) {
    c.kind = Track::Kind::kAtMouth;
    c.manhole = m;
    c.slot = slot;
    c.odometry_var_m2 = c.map_var_m2 = 0;
    c.anchor_m = c.cleared_m = c.travelled_m;
    c.log_weight = track.log_weight + log_detect + log_place + mapped_fit(m, slot);
    out.push_back(std::move(c));
  }

  // The alternatives to a mapped mouth, the robot being at `frame`'s place, with log-probability
  // `log_here` of not having reached the mouth ahead: an unmapped junction, a false detection.
  void alternatives(const Track& frame, double log_here) {
    const Pipe& pipe = map.pipe(frame.pipe);
    const double offset = offset_from_start(pipe, frame.heading_end, frame.travelled_m);
    const bool room_for_junction =
        offset >= o.min_junction_spacing_m && offset <= pipe.length_m - o.min_junction_spacing_m;
    // A junction here: near one the filter already knows in this pipe, or a new one (fewer where
    // the robot drove before and saw none). The place counts from the end the robot entered by,
    // uncertain by the odometry and by the map's length back to where it was last known.
    const double log_junction =
        room_for_junction
            ? filter.junction_log_density(
                  frame.pipe, static_cast<std::uint8_t>(1 - frame.heading_end), frame.travelled_m,
                  frame.odometry_var_m2 + frame.map_var_m2 +
                      std::pow(o.length_sd_fraction * frame.anchor_m, 2))
            : kNegativeInfinity;
    if (log_junction != kNegativeInfinity) {
      const double fit = observation
                             ? unmapped_junction_log_likelihood(*observation, pipe.diameter_m,
                                                                o.min_junction_shaft_m, o.noise)
                             : 0.0;
      Track j = frame;
      j.kind = Track::Kind::kAtJunction;
      j.log_weight = track.log_weight + log_here + log_detect + log_junction + fit;
      assume(j,
             {.kind = Assumption::Kind::kUnmappedJunction, .pipe = frame.pipe, .offset_m = offset});
      if (j.log_weight != kNegativeInfinity) out.push_back(std::move(j));
    }
    if (log_false != kNegativeInfinity) {
      const double fit = observation ? false_detection_log_likelihood(
                                           *observation, o.min_junction_shaft_m, o.noise)
                                     : 0.0;
      Track f = frame;
      f.kind = Track::Kind::kInPipe;
      f.log_weight = track.log_weight + log_here + log_false + fit;
      assume(f,
             {.kind = Assumption::Kind::kFalseDetection, .pipe = frame.pipe, .offset_m = offset});
      out.push_back(std::move(f));
    }
  }
};

}  // namespace

namespace {

// A backing hypothesis seen from behind: the same place with the end it moves towards as its
// heading, so the chain of mouths behind it is walked as the chain ahead of a forward drive. Its
// own inverse: the travelled coordinate counts from the other end (travelled' = length -
// travelled), and so do the anchor and the cleared distance.
Track mirrored(const SewerMap& map, const Track& track) {
  const double length = map.pipe(track.pipe).length_m;
  Track m = track;
  m.heading_end = static_cast<std::uint8_t>(1 - track.heading_end);
  m.travelled_m = length - track.travelled_m;
  m.anchor_m = length - track.anchor_m;
  m.cleared_m = length - track.cleared_m;
  m.leg_from_m = length - track.leg_from_m;
  return m;
}

// The explanations of a hypothesis driving towards the end it faces.
void arrival_ahead(const TopologicalFilter& filter, const Track& track,
                   const std::optional<ManholeSignature>& observation, std::vector<Track>& out) {
  const SewerMap& map = filter.map();
  ArrivalExplainer explain{filter, map, filter.options(), track, observation, out};
  const double t = track.travelled_m;
  walk_chain(
      filter, track, track.cleared_m,
      [&](const ChainStep& step, double mouth, const PlaceSpread& place, double log_beyond_lower) {
        const Pipe& pipe = map.pipe(step.pipe);
        const bool first = step.passed.empty();
        const PipeEnd& far = pipe.ends[step.heading_end];
        if (far.manhole) {
          explain.at_mouth(placed(track, step, pipe.length_m, first), *far.manhole, far.slot,
                           step.log_pass + log_normal(t, mouth, place) - log_beyond_lower);
        }
        const double here = t - step.base_m;
        if (!first && here < 0) return;
        const double log_here = step.log_pass + log_phi_within(mouth - t, place) - log_beyond_lower;
        explain.alternatives(placed(track, step, std::clamp(here, 0.0, pipe.length_m), first),
                             log_here);
      });
}

void no_arrival_ahead(const TopologicalFilter& filter, const Track& track, double distance_m,
                      std::vector<Track>& out) {
  const SewerMap& map = filter.map();
  const double t = track.travelled_m;
  walk_chain(
      filter, track, std::max(track.cleared_m, t - distance_m),
      [&](const ChainStep& step, double mouth, const PlaceSpread& place, double log_beyond_lower) {
        const Pipe& pipe = map.pipe(step.pipe);
        const bool first = step.passed.empty();
        // Past a manhole missed short of its mapped place (the pipe shorter than mapped, the
        // odometry short of the mouth): just beyond it, weighed by the chance the mouth was passed.
        const double here = t - step.base_m;
        Track c = placed(track, step, std::clamp(here, 0.0, pipe.length_m), first);
        if (first) c.travelled_m = t;  // beyond the mapped length: the pipe is longer
        c.cleared_m = c.travelled_m;
        c.log_weight =
            track.log_weight + step.log_pass + log_phi_within(mouth - t, place) - log_beyond_lower;
        out.push_back(std::move(c));
      });
}

// Runs `ahead` on `track`, mirrored when it backs: a robot backing up passes the mouth behind it
// unseen as one driving forward passes the mouth ahead (into the pipe straight on), and the
// places found are turned back to face the way the robot does. A place beyond the mapped length
// behind it (the pipe is longer than the map says) stays at the mouth: the travelled coordinate
// starts there.
template <class Ahead>
void explain_either_way(const TopologicalFilter& filter, const Track& track,
                        std::vector<Track>& out, Ahead ahead) {
  if (track.moving_end == track.heading_end) {
    ahead(track, out);
    return;
  }
  const SewerMap& map = filter.map();
  const std::size_t first = out.size();
  ahead(mirrored(map, track), out);
  for (std::size_t i = first; i < out.size(); ++i) {
    Track& c = out[i];
    c = mirrored(map, c);
    c.moving_end = static_cast<std::uint8_t>(1 - c.heading_end);
    const double length = map.pipe(c.pipe).length_m;
    c.travelled_m = std::clamp(c.travelled_m, 0.0, length);
    c.anchor_m = std::clamp(c.anchor_m, 0.0, length);
    c.cleared_m = std::clamp(c.cleared_m, 0.0, length);
    c.leg_from_m = std::clamp(c.leg_from_m, 0.0, length);
  }
}

}  // namespace

// The odometry of a robot held at a mouth: its drive's variance, and at least kHeldSdM (a robot
// stopping against a manhole's edge may turn its wheels a few centimetres).
constexpr double kHeldSdM = 0.1;
PlaceSpread held_spread(const LocalisationOptions& o, const Track& track) {
  return spread(o, std::max(track.odometry_var_m2, kHeldSdM * kHeldSdM), 0);
}

// A hypothesis held at its mouth or junction (Track::held): after `log_drive` for the odometry
// having read what it did while the robot stood still, it stays where it is.
Track held_there(const Track& track, double log_drive) {
  Track c = track;
  c.log_weight += log_drive;
  c.held = false;
  c.held_m = 0;
  c.odometry_var_m2 = c.map_var_m2 = 0;
  c.arrival_misses = 0;
  return c;
}

bool held_in_reach(const LocalisationOptions& options, const Track& track) {
  const PlaceSpread held = held_spread(options, track);
  const double wide_var = held.tails.scale * held.tails.scale * held.odometry_var + held.map_var;
  return track.held_m <= 4 * std::sqrt(wide_var);
}

void explain_arrival(const TopologicalFilter& filter, const Track& track,
                     const std::optional<ManholeSignature>& observation, std::vector<Track>& out) {
  if (track.held) {
    // At the mouth it faces again: the odometry's density of the held drive at 0 m, the detection,
    // and the observation's fit to that mouth or junction.
    const LocalisationOptions& o = filter.options();
    double fit = 0;
    if (observation) {
      fit = track.kind == Track::Kind::kAtMouth
                ? filter.mapped_log_likelihood(track.manhole, track.slot, *observation)
                : unmapped_junction_log_likelihood(*observation,
                                                   filter.map().pipe(track.pipe).diameter_m,
                                                   o.min_junction_shaft_m, o.noise);
    }
    const double log_drive = std::log1p(-o.miss_probability) +
                             log_normal(track.held_m, 0.0, held_spread(o, track)) + fit;
    Track c = held_there(track, log_drive);
    if (c.log_weight != kNegativeInfinity) out.push_back(std::move(c));
    return;
  }
  explain_either_way(filter, track, out, [&](const Track& t, std::vector<Track>& into) {
    arrival_ahead(filter, t, observation, into);
  });
}

void explain_no_arrival(const TopologicalFilter& filter, const Track& track, double distance_m,
                        std::vector<Track>& out) {
  if (track.held) {
    // Still facing its mouth, unseen: the odometry read at least `distance_m` while the robot
    // stood still, and the detection missed.
    const LocalisationOptions& o = filter.options();
    Track c = track;
    c.log_weight +=
        log_or_never(o.miss_probability) + log_phi_within(-distance_m, held_spread(o, track));
    if (c.log_weight != kNegativeInfinity) out.push_back(std::move(c));
    return;
  }
  explain_either_way(filter, track, out, [&](const Track& t, std::vector<Track>& into) {
    no_arrival_ahead(filter, t, distance_m, into);
  });
}

std::optional<Track> turned(const TopologicalFilter& filter, const Track& track,
                            double relative_deg, const std::optional<Passage>& passage,
                            std::optional<double> measured_deg) {
  const SewerMap& map = filter.map();
  const LocalisationOptions& o = filter.options();
  // The robot's own turn, where its joints measured one: better than the plan's or the sighting's.
  const double direction = measured_deg.value_or(relative_deg);
  switch (track.kind) {
    case Track::Kind::kAtMouth: {
      std::optional<SlotIndex> to;
      if (passage && passage->manhole == track.manhole && passage->from == track.slot) {
        to = passage->to;
      } else {
        to = slot_towards(map, track.manhole, track.slot, direction, o.noise.max_direction_deg);
      }
      if (!to) return std::nullopt;
      const Slot& slot = map.slot(track.manhole, *to);
      Track c = track;
      if (measured_deg) {
        const double mapped =
            ccw_deg(map.slot(track.manhole, track.slot).azimuth_deg, slot.azimuth_deg);
        c.log_weight += turn_log_likelihood(*measured_deg, mapped,
                                            {.sd_deg = o.turn_sd_deg,
                                             .off_share = o.direction_off_share,
                                             .off_max_deg = o.direction_off_max_deg});
      }
      c.kind = Track::Kind::kInPipe;
      c.pipe = slot.pipe;
      c.heading_end = static_cast<std::uint8_t>(1 - slot.pipe_end);
      c.moving_end = c.heading_end;
      c.travelled_m = c.cleared_m = c.leg_from_m = 0;
      c.odometry_var_m2 = c.map_var_m2 = 0;
      c.anchor_m = 0;
      return c;
    }
    case Track::Kind::kAtJunction:
    case Track::Kind::kInPipe: {
      // A manhole the map lacks, or no manhole at all: only straight on stays on the map. Through
      // a junction rear first, the robot leaves front first: it faces the end it was backing to.
      // A direction the robot only saw (not measured by its joints) is straight on as far off as
      // two sightings' noise beyond (the mouth it left by and the one it came out of), as the
      // controller passes it (executor's straight_through): beyond 30 degrees alone, a pass the
      // controller made took the filter off the junction it had acted on.
      const double window = measured_deg ? o.straight_through_deg
                                         : o.straight_through_deg + 2 * o.noise.direction_deg;
      if (std::abs(normalize_deg(direction - 180.0)) > window) return std::nullopt;
      const bool rear_first =
          track.kind == Track::Kind::kAtJunction && track.moving_end != track.heading_end;
      Track c = rear_first ? mirrored(map, track) : track;
      // Its mouth straight on is unknown within the window (no map to weigh the angle by).
      if (measured_deg) {
        c.log_weight += std::log((1 - kTurnOutlierShare) /
                                     (2 * std::max(o.straight_through_deg, o.turn_sd_deg)) +
                                 kTurnOutlierShare / 360.0);
      }
      c.kind = Track::Kind::kInPipe;
      c.moving_end = c.heading_end;
      c.cleared_m = c.leg_from_m = c.travelled_m;
      return c;
    }
    case Track::Kind::kInManhole:
      return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace sewerplan::localisation::detail
