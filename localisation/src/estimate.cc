// SPDX-License-Identifier: MIT
// What the filter believes: the estimate, the verification of an arrival, and the manholes that
// would tell its hypotheses apart.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

#include "sewerplan/core/map_queries.h"
#include "sewerplan/localisation/topological_filter.h"

#include "likelihoods.h"
#include "track_geometry.h"

namespace sewerplan::localisation {

using Track = TopologicalFilter::Track;

namespace {

std::string metres(double value) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(2);
  os << value;
  return os.str();
}

Hypothesis hypothesis_of(const SewerMap& map, const Track& t) {
  Hypothesis h;
  h.probability = std::exp(t.log_weight);
  h.assumptions = t.assumptions;
  switch (t.kind) {
    case Track::Kind::kInManhole:
      h.pose.position = domain::InManhole{t.manhole};
      break;
    case Track::Kind::kAtMouth:
      h.pose.position = domain::AtSlot{t.manhole, t.slot};
      break;
    case Track::Kind::kInPipe:
    case Track::Kind::kAtJunction: {
      const Pipe& pipe = map.pipe(t.pipe);
      const double travelled = std::clamp(t.travelled_m, 0.0, pipe.length_m);
      h.pose.position =
          domain::InPipe{t.pipe, t.heading_end == 1 ? travelled : pipe.length_m - travelled};
      h.pose.heading_end = t.heading_end;
      h.pose.at_unmapped_junction = t.kind == Track::Kind::kAtJunction;
      h.sd_m = std::sqrt(t.odometry_var_m2 + t.map_var_m2);
      break;
    }
  }
  return h;
}

bool at_mouth(const Track& t, ManholeId m, SlotIndex s) {
  return t.kind == Track::Kind::kAtMouth && t.manhole == m && t.slot == s;
}

std::string probability_text(double p) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(2);
  os << "p=" << p;
  return os.str();
}

}  // namespace

std::string_view to_string(Assumption::Kind kind) {
  switch (kind) {
    case Assumption::Kind::kUnmappedJunction:
      return "unmapped-junction";
    case Assumption::Kind::kMissedManhole:
      return "missed-manhole";
    case Assumption::Kind::kFalseDetection:
      return "false-detection";
  }
  return "?";
}

std::string_view to_string(Verification::Kind kind) {
  switch (kind) {
    case Verification::Kind::kMatches:
      return "matches";
    case Verification::Kind::kWrongManhole:
      return "wrong-manhole";
    case Verification::Kind::kUnmappedJunction:
      return "unmapped-junction";
    case Verification::Kind::kMissedManhole:
      return "missed-manhole";
    case Verification::Kind::kFalseDetection:
      return "false-detection";
    case Verification::Kind::kSignatureDiffers:
      return "signature-differs";
  }
  return "?";
}

std::string describe(const Pose& pose, const SewerMap& map) {
  const auto* in = std::get_if<domain::InPipe>(&pose.position);
  if (in == nullptr) return domain::describe(pose.position, map);
  const Pipe& pipe = map.pipe(in->pipe);
  if (pose.at_unmapped_junction) {
    return "at an unmapped junction in " + pipe.name + " at " + metres(in->offset_m) + " m";
  }
  std::string text = domain::describe(pose.position, map);
  if (pose.heading_end) {
    const PipeEnd& end = pipe.ends[*pose.heading_end];
    text += end.manhole ? " facing " + map.manhole(*end.manhole).name : " facing its blind end";
  }
  return text;
}

Estimate TopologicalFilter::estimate() const {
  Estimate e;
  e.hypotheses.reserve(tracks_.size());
  for (const Track& t : tracks_) e.hypotheses.push_back(hypothesis_of(*map_, t));
  std::stable_sort(
      e.hypotheses.begin(), e.hypotheses.end(),
      [](const Hypothesis& a, const Hypothesis& b) { return a.probability > b.probability; });
  const auto likely = std::count_if(
      e.hypotheses.begin(), e.hypotheses.end(),
      [&](const Hypothesis& h) { return h.probability >= options_.ambiguity_probability; });
  e.ambiguous = likely >= 2;
  return e;
}

Result<Verification> TopologicalFilter::verify_arrival(
    ManholeId expected, SlotIndex arrival,
    const std::optional<ManholeSignature>& observation) const {
  const SewerMap& map = *map_;
  if (expected.index() >= map.manhole_count()) {
    return Error{ErrorCode::kInvalidArgument,
                 "verify_arrival: no manhole " + std::to_string(expected.value()) + " in the map"};
  }
  const Manhole& m = map.manhole(expected);
  if (arrival.value() >= m.slot_count) {
    return Error{ErrorCode::kInvalidArgument, "verify_arrival: " + m.name + " has no slot " +
                                                  std::to_string(to_paper_number(arrival))};
  }
  if (observation) {
    if (Result<void> ok = check_signature(*observation); !ok.has_value()) {
      return Error{ErrorCode::kInvalidArgument,
                   "verify_arrival: the observed signature is not one a robot could see: " +
                       ok.error().message};
    }
  }
  if (Result<void> ok = usable(); !ok.has_value()) return ok.error();
  if (mode_ != Mode::kAtManhole) {
    return Error{ErrorCode::kInvalidArgument, "verify_arrival: the robot is not at a manhole"};
  }
  Verification v;
  for (const Track& t : tracks_) {
    if (at_mouth(t, expected, arrival)) v.probability += std::exp(t.log_weight);
  }
  const Track& best = tracks_.front();  // sorted by normalise_and_prune()
  v.believed = hypothesis_of(map, best).pose;
  const std::string want = domain::describe(domain::AtSlot{expected, arrival}, map);
  std::optional<SignatureMatch> match;
  if (observation)
    match = compare(expected_signature(map, expected, arrival), *observation, options_.noise);
  if (at_mouth(best, expected, arrival)) {
    if (match && !match->matches) {
      v.kind = Verification::Kind::kSignatureDiffers;
      v.reason = want + " by the odometry, but " + match->reason;
      return v;
    }
    if (v.probability >= options_.verify_probability) return v;  // matches
  }
  // The most likely explanation that is not the expected mouth.
  auto alt = std::find_if(tracks_.begin(), tracks_.end(),
                          [&](const Track& t) { return !at_mouth(t, expected, arrival); });
  if (alt == tracks_.end()) return v;  // every hypothesis is the expected mouth
  const Track& other = *alt;
  const Pose pose = hypothesis_of(map, other).pose;
  const std::string odds = " (" + probability_text(std::exp(other.log_weight)) + "; " + want + " " +
                           probability_text(v.probability) + ")";
  switch (other.kind) {
    case Track::Kind::kAtMouth:
      if (other.arrival_misses > 0 && !other.assumptions.empty() &&
          other.assumptions.front().manhole) {
        v.kind = Verification::Kind::kMissedManhole;
        v.reason = "drove through " + map.manhole(*other.assumptions.front().manhole).name +
                   " without seeing it: " + describe(pose, map) + odds;
      } else {
        v.kind = Verification::Kind::kWrongManhole;
        v.reason = describe(pose, map) + ", not " + want + odds;
      }
      break;
    case Track::Kind::kAtJunction:
      v.kind = Verification::Kind::kUnmappedJunction;
      v.reason = "a manhole the map lacks: " + describe(pose, map) + odds;
      break;
    case Track::Kind::kInPipe:
    case Track::Kind::kInManhole:
      v.kind = Verification::Kind::kFalseDetection;
      v.reason = "no manhole there: " + describe(pose, map) + odds;
      break;
  }
  if (match && !match->matches) v.reason += "; " + match->reason;
  return v;
}

namespace {

using Mouth = std::optional<std::pair<ManholeId, SlotIndex>>;

// A hypothesis on a route planned under another: at a mapped mouth, at a manhole the map lacks in
// a pipe (or a false detection there), or off the map (neither).
struct Virtual {
  Mouth mouth;
  std::optional<PipeId> pipe;
  std::uint8_t heading_end = 1;
};

// The mouth at the end of a pipe, entered at `end`'s other end.
Mouth far_mouth(const SewerMap& map, PipeId pipe, std::size_t end) {
  const PipeEnd& far = map.pipe(pipe).ends[end];
  if (!far.manhole) return std::nullopt;
  return std::pair{*far.manhole, far.slot};
}

// The mouth a hypothesis in a pipe reaches driving on, and how far it is.
std::pair<Mouth, double> next_mouth(const SewerMap& map, const Track& t) {
  const Pipe& pipe = map.pipe(t.pipe);
  return {far_mouth(map, t.pipe, t.heading_end), std::max(pipe.length_m - t.travelled_m, 0.0)};
}

// A hypothesis at a manhole as a Virtual.
Virtual at_manhole(const Track& t) {
  if (t.kind == Track::Kind::kAtMouth) return {.mouth = std::pair{t.manhole, t.slot}};
  if (t.kind == Track::Kind::kInManhole) return {};
  return {.pipe = t.pipe, .heading_end = t.heading_end};
}

// Where `v` gets leaving its manhole through the mouth `relative_deg` from its arrival mouth and
// driving to the next manhole.
Mouth leave(const SewerMap& map, const Virtual& v, double relative_deg,
            const LocalisationOptions& o) {
  if (v.mouth) {
    const std::optional<SlotIndex> to = detail::slot_towards(
        map, v.mouth->first, v.mouth->second, relative_deg, o.noise.max_direction_deg);
    if (!to) return std::nullopt;
    const Slot& slot = map.slot(v.mouth->first, *to);
    return far_mouth(map, slot.pipe, 1 - slot.pipe_end);
  }
  if (v.pipe && std::abs(normalize_deg(relative_deg - 180.0)) <= o.straight_through_deg)
    return far_mouth(map, *v.pipe, v.heading_end);
  return std::nullopt;
}

struct Search {
  const SewerMap& map;
  const LocalisationOptions& options;
  std::size_t max_passes;
  std::vector<DistinguishingManhole>& found;

  // The robot arrives at `best` (under the most likely hypothesis), the others at theirs.
  void visit(const std::pair<ManholeId, SlotIndex>& best, const std::vector<Virtual>& others,
             std::vector<Passage>& route, double distance_m) {
    const ManholeSignature seen = expected_signature(map, best.first, best.second);
    std::size_t separated = 0;
    for (const Virtual& o : others) {
      if (!o.mouth) {
        ++separated;
      } else if (o.mouth->first != best.first &&
                 !compare(seen, expected_signature(map, o.mouth->first, o.mouth->second),
                          options.noise)
                      .matches) {
        ++separated;
      }
    }
    if (separated > 0) {
      found.push_back({.manhole = best.first,
                       .arrival = best.second,
                       .route = route,
                       .distance_m = distance_m,
                       .separated = separated});
    }
    expand(best, others, route, distance_m);
  }

  // Every way on from `best` through another of its mouths.
  void expand(const std::pair<ManholeId, SlotIndex>& best, const std::vector<Virtual>& others,
              std::vector<Passage>& route, double distance_m) {
    if (route.size() >= max_passes) return;
    const Manhole& m = map.manhole(best.first);
    const double base = map.slot(best.first, best.second).azimuth_deg;
    for (std::uint16_t s = 0; s < m.slot_count; ++s) {
      const SlotIndex to{s};
      if (to == best.second) continue;
      const Slot& slot = map.slot(best.first, to);
      const Mouth next = far_mouth(map, slot.pipe, 1 - slot.pipe_end);
      if (!next) continue;
      const double relative = detail::ccw_deg(base, slot.azimuth_deg);
      std::vector<Virtual> next_others;
      next_others.reserve(others.size());
      for (const Virtual& o : others)
        next_others.push_back({.mouth = leave(map, o, relative, options)});
      route.push_back({best.first, best.second, to});
      visit(*next, next_others, route, distance_m + map.pipe(slot.pipe).length_m);
      route.pop_back();
    }
  }
};

}  // namespace

std::vector<DistinguishingManhole> TopologicalFilter::distinguishing_manholes(
    std::size_t max_passes, std::size_t max_results) const {
  std::vector<DistinguishingManhole> found;
  if (mode_ == Mode::kLost || mode_ == Mode::kInManhole || !estimate().ambiguous) return found;
  const Track& best = tracks_.front();
  std::vector<const Track*> others;
  for (std::size_t i = 1; i < tracks_.size(); ++i) {
    if (std::exp(tracks_[i].log_weight) >= options_.ambiguity_probability)
      others.push_back(&tracks_[i]);
  }
  Search search{*map_, options_, max_passes, found};
  std::vector<Passage> route;
  std::vector<Virtual> virtuals;
  if (mode_ == Mode::kInPipe) {
    // Driving on, every hypothesis reaches the mouth ahead of it.
    const auto [mouth, distance] = next_mouth(*map_, best);
    for (const Track* t : others) virtuals.push_back({.mouth = next_mouth(*map_, *t).first});
    if (mouth) search.visit(*mouth, virtuals, route, distance);
  } else if (best.kind == Track::Kind::kAtMouth) {
    for (const Track* t : others) virtuals.push_back(at_manhole(*t));
    search.expand({best.manhole, best.slot}, virtuals, route, 0.0);
  } else {
    // At a manhole the map lacks (or none): the map goes on only straight ahead.
    const auto [mouth, distance] = next_mouth(*map_, best);
    for (const Track* t : others)
      virtuals.push_back({.mouth = leave(*map_, at_manhole(*t), 180.0, options_)});
    if (mouth) search.visit(*mouth, virtuals, route, distance);
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const DistinguishingManhole& a, const DistinguishingManhole& b) {
                     return std::tie(b.separated, a.distance_m) <
                            std::tie(a.separated, b.distance_m);
                   });
  // Each manhole and arrival once, by its best route.
  std::vector<DistinguishingManhole> unique;
  for (DistinguishingManhole& d : found) {
    const bool seen = std::any_of(unique.begin(), unique.end(), [&](const auto& u) {
      return u.manhole == d.manhole && u.arrival == d.arrival;
    });
    if (!seen) unique.push_back(std::move(d));
    if (unique.size() == max_results) break;
  }
  return unique;
}

}  // namespace sewerplan::localisation
