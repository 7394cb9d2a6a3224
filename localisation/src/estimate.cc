// SPDX-License-Identifier: MIT
// What the filter believes: the estimate, the verification of an arrival, and the manholes that
// would tell its hypotheses apart.
#include <algorithm>
#include <cmath>
#include <sstream>

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
      h.sd_m = std::sqrt(t.odometry_var_m2);
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
  const Track& other = *alt;  // exists: the expected mouth alone would have matched
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

// The mouth a hypothesis reaches next driving forward (itself, at a mouth), and how far it is.
std::pair<Mouth, double> next_mouth(const SewerMap& map, const Track& t) {
  switch (t.kind) {
    case Track::Kind::kAtMouth:
      return {std::pair{t.manhole, t.slot}, 0.0};
    case Track::Kind::kInPipe:
    case Track::Kind::kAtJunction: {
      const Pipe& pipe = map.pipe(t.pipe);
      const PipeEnd& far = pipe.ends[t.heading_end];
      if (!far.manhole) return {std::nullopt, 0.0};
      return {std::pair{*far.manhole, far.slot}, std::max(pipe.length_m - t.travelled_m, 0.0)};
    }
    case Track::Kind::kInManhole:
      return {std::nullopt, 0.0};
  }
  return {std::nullopt, 0.0};
}

// Through `mouth`'s manhole into the slot `relative_deg` from it, to the far end of that pipe.
Mouth through(const SewerMap& map, const Mouth& mouth, double relative_deg, double tolerance_deg) {
  if (!mouth) return std::nullopt;
  const std::optional<SlotIndex> to =
      detail::slot_towards(map, mouth->first, mouth->second, relative_deg, tolerance_deg);
  if (!to) return std::nullopt;
  const Slot& slot = map.slot(mouth->first, *to);
  const PipeEnd& far = map.pipe(slot.pipe).ends[1 - slot.pipe_end];
  if (!far.manhole) return std::nullopt;
  return std::pair{*far.manhole, far.slot};
}

struct Search {
  const SewerMap& map;
  const SignatureNoise& noise;
  std::size_t max_passes;
  std::vector<DistinguishingManhole>& found;

  void visit(const std::pair<ManholeId, SlotIndex>& best, const std::vector<Mouth>& others,
             std::vector<Passage>& route, double distance_m) {
    const ManholeSignature seen = expected_signature(map, best.first, best.second);
    std::size_t separated = 0;
    for (const Mouth& o : others) {
      if (!o) {
        ++separated;
      } else if (o->first != best.first &&
                 !compare(seen, expected_signature(map, o->first, o->second), noise).matches) {
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
    if (route.size() >= max_passes) return;
    const Manhole& m = map.manhole(best.first);
    const double base = map.slot(best.first, best.second).azimuth_deg;
    for (std::uint16_t s = 0; s < m.slot_count; ++s) {
      const SlotIndex to{s};
      if (to == best.second) continue;
      const Slot& slot = map.slot(best.first, to);
      const Pipe& pipe = map.pipe(slot.pipe);
      const PipeEnd& far = pipe.ends[1 - slot.pipe_end];
      if (!far.manhole) continue;
      const double relative = detail::ccw_deg(base, slot.azimuth_deg);
      std::vector<Mouth> next_others;
      next_others.reserve(others.size());
      for (const Mouth& o : others)
        next_others.push_back(through(map, o, relative, noise.max_direction_deg));
      route.push_back({best.first, best.second, to});
      visit({*far.manhole, far.slot}, next_others, route, distance_m + pipe.length_m);
      route.pop_back();
    }
  }
};

}  // namespace

std::vector<DistinguishingManhole> TopologicalFilter::distinguishing_manholes(
    std::size_t max_passes, std::size_t max_results) const {
  std::vector<DistinguishingManhole> found;
  if (!estimate().ambiguous) return found;
  const auto [best, distance] = next_mouth(*map_, tracks_.front());
  if (!best) return found;
  std::vector<Mouth> others;
  for (std::size_t i = 1; i < tracks_.size(); ++i) {
    if (std::exp(tracks_[i].log_weight) < options_.ambiguity_probability) continue;
    others.push_back(next_mouth(*map_, tracks_[i]).first);
  }
  std::vector<Passage> route;
  Search{*map_, options_.noise, max_passes, found}.visit(*best, others, route, distance);
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
