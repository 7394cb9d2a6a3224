// SPDX-License-Identifier: MIT
#include "sewerplan/hal/world_errors.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <utility>

#include "sewerplan/core/map_builder.h"
#include "sewerplan/core/overloaded.h"
#include "sewerplan/core/rng.h"

namespace sewerplan::hal {
namespace {

// One key of the "key=value" form: its field, and whether it is a share (at most 1) or a share
// that must stay below 1 (a relative error that would leave nothing).
struct Key {
  std::string_view name;
  double WorldErrorProfile::*field;
  double max;
};

const std::array<Key, 16>& keys() {
  static const std::array<Key, 16> k{{
      {"lengths", &WorldErrorProfile::length_share, 1},
      {"length_rel", &WorldErrorProfile::length_max_rel, 0.9},
      {"length_abs", &WorldErrorProfile::length_max_abs_m, 1000},
      {"directions", &WorldErrorProfile::direction_share, 1},
      {"direction_deg", &WorldErrorProfile::direction_max_deg, 90},
      {"positions", &WorldErrorProfile::position_share, 1},
      {"position_m", &WorldErrorProfile::position_max_m, 1000},
      {"junctions", &WorldErrorProfile::junction_share, 1},
      {"laterals_extra", &WorldErrorProfile::lateral_extra_share, 1},
      {"laterals_missing", &WorldErrorProfile::lateral_missing_share, 1},
      {"diameters", &WorldErrorProfile::diameter_share, 1},
      {"diameter_rel", &WorldErrorProfile::diameter_max_rel, 0.9},
      {"drift", &WorldErrorProfile::drift, 1},
      {"wet", &WorldErrorProfile::wet_share, 1},
      {"missed", &WorldErrorProfile::missed_share, 1},
      {"false_per_km", &WorldErrorProfile::false_per_km, 1000},
  }};
  return k;
}

std::string known_keys() {
  std::string known;
  for (const Key& k : keys()) known += (known.empty() ? "" : ", ") + std::string(k.name);
  return known;
}

std::string known_profiles() {
  std::string known;
  for (const NamedWorldErrors& p : kWorldErrorProfiles) {
    known += (known.empty() ? "" : ", ") + std::string(p.name);
  }
  return known;
}

Result<void> check_profile(const WorldErrorProfile& profile) {
  for (const Key& k : keys()) {
    const double v = profile.*(k.field);
    if (!(std::isfinite(v) && v >= 0 && v <= k.max)) {
      std::ostringstream os;
      os << "world errors: " << k.name << " = " << v << " is not in [0, " << k.max << "]";
      return Error{ErrorCode::kInvalidArgument, os.str()};
    }
  }
  return {};
}

double normalise_deg(double deg) {
  double d = std::fmod(deg, 360.0);
  if (d < 0) d += 360.0;
  if (d >= 360.0) d -= 360.0;
  return d;
}

// An error of up to `max`: uniform in [max/4, max], of either sign.
double signed_error(Rng& rng, double max) {
  const double magnitude = rng.uniform(0.25 * max, max);
  return rng.bernoulli(0.5) ? magnitude : -magnitude;
}

// The map as the records MapBuilder takes, to be changed into the world.
struct Records {
  std::vector<ManholeRecord> manholes;
  std::vector<PipeRecord> pipes;
  std::vector<PointRecord> points;
  std::vector<FindingRecord> findings;
};

Records records_of(const SewerMap& map) {
  Records r;
  r.manholes.reserve(map.manhole_count());
  for (ManholeId id : map.manhole_ids()) {
    const Manhole& m = map.manhole(id);
    ManholeRecord record{.name = m.name,
                         .position = m.position,
                         .diameter_m = m.diameter_m,
                         .exit = m.exit,
                         .variant = m.variant,
                         .shaft_length_m = m.shaft_length_m,
                         .shaft_width_m = m.shaft_width_m,
                         .depth_m = m.depth_m,
                         .slots = {}};
    for (const Slot& s : map.slots(id)) {
      record.slots.push_back(SlotRecord{
          .pipe = map.pipe(s.pipe).name, .azimuth_deg = s.azimuth_deg, .invert_z_m = s.invert_z_m});
    }
    r.manholes.push_back(std::move(record));
  }
  for (const Pipe& p : map.pipes()) {
    PipeRecord record{.name = p.name,
                      .length_m = p.length_m,
                      .diameter_m = p.diameter_m,
                      .shape = p.shape,
                      .height_m = p.height_m,
                      .blockage_risk = p.blockage_risk};
    if (p.ends[0].manhole) record.from = map.manhole(*p.ends[0].manhole).name;
    if (p.ends[1].manhole) record.to = map.manhole(*p.ends[1].manhole).name;
    r.pipes.push_back(std::move(record));
  }
  for (const InspectionPoint& p : map.points()) {
    r.points.push_back(PointRecord{p.name, map.pipe(p.pipe).name, p.offset_m});
  }
  for (const Finding& f : map.findings()) {
    r.findings.push_back(FindingRecord{.pipe = map.pipe(f.pipe).name,
                                       .code = f.code,
                                       .characterisation = f.characterisation,
                                       .station_m = f.offset_m,
                                       .quantity1 = f.quantity1,
                                       .quantity2 = f.quantity2});
  }
  return r;
}

// A map place in the world, from the lengths and splits alone.
WorldSpot spot_in(double map_length_m, double world_length_m, const PipeSplit* split, PipeId pipe,
                  double offset_m) {
  if (split == nullptr) {
    if (world_length_m == map_length_m) return {pipe, offset_m};
    return {pipe, std::clamp(offset_m * world_length_m / map_length_m, 0.0, world_length_m)};
  }
  const double scaled = std::clamp(offset_m * world_length_m / map_length_m, 0.0, world_length_m);
  if (scaled <= split->at_m) return {pipe, scaled};
  return {split->rest, scaled - split->at_m};
}

class WorldMaker {
 public:
  WorldMaker(const SewerMap& map, const WorldErrorProfile& profile, std::uint64_t seed)
      : map_(map), profile_(profile), rng_(seed), r_(records_of(map)) {
    made_blind_.assign(map.pipe_count(), false);
  }

  Result<TrueWorld> make(std::uint64_t seed) && {
    // One stream per model, split in a fixed order: a rate changed in one model leaves the
    // others' draws as they were.
    Rng lengths = rng_.split(), diameters = rng_.split(), directions = rng_.split(),
        positions = rng_.split(), missing = rng_.split(), extra = rng_.split(),
        junctions = rng_.split(), wet = rng_.split();
    draw_lengths(lengths);
    draw_diameters(diameters);
    draw_directions(directions);
    draw_positions(positions);
    draw_missing_laterals(missing);
    draw_extra_laterals(extra);
    draw_junctions(junctions);
    move_points_and_findings();

    MapBuilder builder(map_.name(), line_locator("<true world of " + map_.name() + ">"));
    builder.set_crs(map_.crs());
    for (ManholeRecord& m : r_.manholes) builder.add_manhole(std::move(m));
    for (PipeRecord& p : r_.pipes) builder.add_pipe(std::move(p));
    for (PointRecord& p : r_.points) builder.add_point(std::move(p));
    for (FindingRecord& f : r_.findings) builder.add_finding(std::move(f));
    Diagnostics diagnostics;
    Result<SewerMap> world = std::move(builder).build(diagnostics);
    if (!world.has_value()) {
      return Error{ErrorCode::kInvalidMap,
                   "the true world of " + map_.name() + " is invalid: " + world.error().message};
    }
    TrueWorld truth{.world = std::move(*world),
                    .seeded = std::move(seeded_),
                    .splits = std::move(splits_),
                    .wet = {},
                    .profile = profile_,
                    .seed = seed};
    truth.wet.resize(truth.world.pipe_count());
    for (std::size_t p = 0; p < truth.wet.size(); ++p) {
      truth.wet[p] = wet.bernoulli(profile_.wet_share);
    }
    return truth;
  }

 private:
  // Lengths: L (1 + r) + a, r of up to length_max_rel, a uniform in +-length_max_abs_m; at least
  // a tenth of the map's length.
  void draw_lengths(Rng& rng) {
    for (PipeId id : map_.pipe_ids()) {
      if (!rng.bernoulli(profile_.length_share)) continue;
      const double map_m = map_.pipe(id).length_m;
      const double rel =
          profile_.length_max_rel > 0 ? signed_error(rng, profile_.length_max_rel) : 0;
      const double abs_m = profile_.length_max_abs_m > 0
                               ? rng.uniform(-profile_.length_max_abs_m, profile_.length_max_abs_m)
                               : 0;
      const double world_m = std::max(0.1 * map_m, map_m * (1 + rel) + abs_m);
      if (world_m == map_m) continue;
      r_.pipes[id.index()].length_m = world_m;
      seeded_.push_back(Discrepancy{
          .kind = Discrepancy::Kind::kLengthOff, .pipe = id, .map_value = map_m, .value = world_m});
    }
  }

  void draw_diameters(Rng& rng) {
    for (PipeId id : map_.pipe_ids()) {
      if (!rng.bernoulli(profile_.diameter_share) || profile_.diameter_max_rel <= 0) continue;
      const double factor =
          1 - rng.uniform(0.25 * profile_.diameter_max_rel, profile_.diameter_max_rel);
      PipeRecord& p = r_.pipes[id.index()];
      const double map_m = p.diameter_m;
      p.diameter_m *= factor;
      p.height_m = *p.height_m * factor;
      seeded_.push_back(Discrepancy{.kind = Discrepancy::Kind::kDiameterSmaller,
                                    .pipe = id,
                                    .map_value = map_m,
                                    .value = p.diameter_m});
    }
  }

  void draw_directions(Rng& rng) {
    for (ManholeId m : map_.manhole_ids()) {
      for (std::size_t s = 0; s < map_.slots(m).size(); ++s) {
        if (!rng.bernoulli(profile_.direction_share) || profile_.direction_max_deg <= 0) continue;
        SlotRecord& slot = r_.manholes[m.index()].slots[s];
        const double map_deg = slot.azimuth_deg;
        slot.azimuth_deg = normalise_deg(map_deg + signed_error(rng, profile_.direction_max_deg));
        seeded_.push_back(Discrepancy{.kind = Discrepancy::Kind::kDirectionOff,
                                      .manhole = m,
                                      .slot = SlotIndex{static_cast<std::uint16_t>(s)},
                                      .map_value = map_deg,
                                      .value = slot.azimuth_deg});
      }
    }
  }

  // A direction uniform on the circle by rejection from the unit disc (no trigonometry, so the
  // same on every platform).
  void draw_positions(Rng& rng) {
    for (ManholeId m : map_.manhole_ids()) {
      if (!rng.bernoulli(profile_.position_share) || profile_.position_max_m <= 0) continue;
      const double distance_m =
          rng.uniform(0.25 * profile_.position_max_m, profile_.position_max_m);
      double x = 0, y = 0, r2 = 0;
      do {
        x = rng.uniform(-1, 1);
        y = rng.uniform(-1, 1);
        r2 = x * x + y * y;
      } while (r2 > 1 || r2 < 0.01);
      const double scale = distance_m / std::sqrt(r2);
      Position& p = r_.manholes[m.index()].position;
      p.x_m += x * scale;
      p.y_m += y * scale;
      seeded_.push_back(
          Discrepancy{.kind = Discrepancy::Kind::kPositionOff, .manhole = m, .value = distance_m});
    }
  }

  // The last slot of a manhole with three or more (a junction's lateral): its pipe stops blind
  // short of the manhole. Not when the pipe's other end is blind already.
  void draw_missing_laterals(Rng& rng) {
    for (ManholeId m : map_.manhole_ids()) {
      const std::size_t count = map_.slots(m).size();
      if (count < 3 || !rng.bernoulli(profile_.lateral_missing_share)) continue;
      const Slot& last = map_.slots(m)[count - 1];
      PipeRecord& pipe = r_.pipes[last.pipe.index()];
      if (!pipe.from || !pipe.to || made_blind_[last.pipe.index()]) continue;
      (last.pipe_end == 0 ? pipe.from : pipe.to).reset();
      made_blind_[last.pipe.index()] = true;
      r_.manholes[m.index()].slots.pop_back();
      // A direction drawn for the slot that is not there is no discrepancy of its own.
      const SlotIndex gone{static_cast<std::uint16_t>(count - 1)};
      std::erase_if(seeded_, [&](const Discrepancy& d) {
        return d.kind == Discrepancy::Kind::kDirectionOff && d.manhole == m && d.slot == gone;
      });
      seeded_.push_back(Discrepancy{.kind = Discrepancy::Kind::kMissingLateral,
                                    .pipe = last.pipe,
                                    .manhole = m,
                                    .slot = SlotIndex{static_cast<std::uint16_t>(count - 1)}});
    }
  }

  std::string new_pipe_name() { return "world-P" + std::to_string(++new_pipes_); }

  // A house lateral: a blind pipe of 5-30 m and 0.15-0.30 m into the middle of the manhole's
  // widest gap between slots (+- a quarter of the gap), its invert 0-0.30 m above the floor.
  void add_lateral(ManholeRecord& m, double azimuth_deg, Rng& rng) {
    const std::string name = new_pipe_name();
    const double diameter_m = rng.uniform(0.15, 0.30);
    r_.pipes.push_back(PipeRecord{.name = name,
                                  .from = std::nullopt,
                                  .to = m.name,
                                  .length_m = rng.uniform(5, 30),
                                  .diameter_m = diameter_m,
                                  .height_m = diameter_m});
    m.slots.push_back(SlotRecord{.pipe = name,
                                 .azimuth_deg = normalise_deg(azimuth_deg),
                                 .invert_z_m = m.position.z_m + rng.uniform(0, 0.3)});
  }

  static double widest_gap_middle(const ManholeRecord& m, Rng& rng) {
    std::vector<double> az;
    for (const SlotRecord& s : m.slots) az.push_back(normalise_deg(s.azimuth_deg));
    std::sort(az.begin(), az.end());
    if (az.empty()) return rng.uniform(0, 360);
    double best_gap = 0, best_start = 0;
    for (std::size_t i = 0; i < az.size(); ++i) {
      const double next = i + 1 < az.size() ? az[i + 1] : az[0] + 360;
      if (next - az[i] > best_gap) {
        best_gap = next - az[i];
        best_start = az[i];
      }
    }
    return best_start + best_gap / 2 + rng.uniform(-best_gap / 4, best_gap / 4);
  }

  void draw_extra_laterals(Rng& rng) {
    for (ManholeId m : map_.manhole_ids()) {
      if (!rng.bernoulli(profile_.lateral_extra_share)) continue;
      ManholeRecord& record = r_.manholes[m.index()];
      const double azimuth_deg = normalise_deg(widest_gap_middle(record, rng));
      add_lateral(record, azimuth_deg, rng);
      seeded_.push_back(Discrepancy{
          .kind = Discrepancy::Kind::kUnmappedLateral, .manhole = m, .value = azimuth_deg});
    }
  }

  // Per map manhole, with junction_share, one unmapped junction: a manhole of 1.0 m in a mapped
  // pipe with manholes at both ends and at least 6 m long, 30-70 % of the way along it, with a
  // lateral at right angles (+-20 degrees, to either side).
  void draw_junctions(Rng& rng) {
    std::vector<PipeId> candidates;
    for (PipeId id : map_.pipe_ids()) {
      const PipeRecord& p = r_.pipes[id.index()];
      if (p.from && p.to && !made_blind_[id.index()] && p.length_m >= 6) candidates.push_back(id);
    }
    for (std::size_t i = 0; i < map_.manhole_count() && !candidates.empty(); ++i) {
      if (!rng.bernoulli(profile_.junction_share)) continue;
      const std::size_t pick = rng.below(candidates.size());
      const PipeId id = candidates[pick];
      candidates.erase(candidates.begin() + static_cast<std::ptrdiff_t>(pick));
      split(id, rng);
    }
  }

  void split(PipeId id, Rng& rng) {
    const Pipe& map_pipe = map_.pipe(id);
    const ManholeId from = *map_pipe.ends[0].manhole;
    const ManholeId to = *map_pipe.ends[1].manhole;
    SlotRecord& from_slot = r_.manholes[from.index()].slots[map_pipe.ends[0].slot.index()];
    SlotRecord& to_slot = r_.manholes[to.index()].slots[map_pipe.ends[1].slot.index()];
    PipeRecord& pipe = r_.pipes[id.index()];
    const double length_m = pipe.length_m;
    const double at_m = length_m * rng.uniform(0.3, 0.7);
    const double share = at_m / length_m;
    const Position& a = r_.manholes[from.index()].position;
    const Position& b = r_.manholes[to.index()].position;
    const double invert_z_m =
        from_slot.invert_z_m + share * (to_slot.invert_z_m - from_slot.invert_z_m);
    const std::string junction = "world-J" + std::to_string(++new_manholes_);
    const std::string rest = new_pipe_name();
    ManholeRecord j{
        .name = junction,
        .position = {a.x_m + share * (b.x_m - a.x_m), a.y_m + share * (b.y_m - a.y_m), invert_z_m},
        .diameter_m = 1.0,
        .slots = {}};
    const double back_deg = normalise_deg(from_slot.azimuth_deg + 180);
    const double on_deg = normalise_deg(to_slot.azimuth_deg + 180);
    j.slots.push_back(
        SlotRecord{.pipe = pipe.name, .azimuth_deg = back_deg, .invert_z_m = invert_z_m});
    j.slots.push_back(SlotRecord{.pipe = rest, .azimuth_deg = on_deg, .invert_z_m = invert_z_m});
    const double turn = std::abs(normalise_deg(on_deg - back_deg) - 180);
    j.variant = turn <= 10 ? 'A' : 'B';
    PipeRecord rest_pipe = pipe;
    rest_pipe.name = rest;
    rest_pipe.from = junction;
    rest_pipe.length_m = length_m - at_m;
    pipe.to = junction;
    pipe.length_m = at_m;
    to_slot.pipe = rest;
    r_.pipes.push_back(std::move(rest_pipe));
    const PipeId rest_id{static_cast<std::uint32_t>(r_.pipes.size() - 1)};
    const double side = rng.bernoulli(0.5) ? 90 : -90;
    add_lateral(j, back_deg + side + rng.uniform(-20, 20), rng);
    r_.manholes.push_back(std::move(j));
    splits_.push_back(PipeSplit{id, rest_id, at_m});
    seeded_.push_back(Discrepancy{
        .kind = Discrepancy::Kind::kUnmappedJunction, .pipe = id, .offset_m = at_m, .value = 3});
  }

  // Inspection points and findings keep their share of the way along their pipe (the world's
  // length), on the split's rest beyond a junction.
  void move_points_and_findings() {
    std::vector<const PipeSplit*> split_of(map_.pipe_count(), nullptr);
    for (const PipeSplit& s : splits_) split_of[s.pipe.index()] = &s;
    const auto move = [&](PipeId id, std::string& pipe_name, double& offset_m) {
      const PipeSplit* s = split_of[id.index()];
      const double world_m =
          r_.pipes[id.index()].length_m + (s ? r_.pipes[s->rest.index()].length_m : 0);
      const WorldSpot spot = spot_in(map_.pipe(id).length_m, world_m, s, id, offset_m);
      pipe_name = r_.pipes[spot.pipe.index()].name;
      offset_m = spot.offset_m;
    };
    for (std::size_t i = 0; i < r_.points.size(); ++i) {
      move(map_.point(PointId{static_cast<std::uint32_t>(i)}).pipe, r_.points[i].pipe,
           r_.points[i].offset_m);
    }
    for (std::size_t i = 0; i < r_.findings.size(); ++i) {
      move(map_.findings()[i].pipe, r_.findings[i].pipe, r_.findings[i].station_m);
    }
  }

  const SewerMap& map_;
  const WorldErrorProfile& profile_;
  Rng rng_;
  Records r_;
  std::vector<bool> made_blind_;  // per map pipe: an end made blind (a missing lateral)
  std::vector<Discrepancy> seeded_;
  std::vector<PipeSplit> splits_;
  std::size_t new_pipes_ = 0;
  std::size_t new_manholes_ = 0;
};

}  // namespace

Result<WorldErrorProfile> parse_world_errors(std::string_view text) {
  WorldErrorProfile profile;
  const std::string whole(text);
  if (text.empty()) {
    return Error{ErrorCode::kInvalidArgument,
                 "--world-errors: empty (a profile: " + known_profiles() + "; or key=value,...)"};
  }
  if (const std::string_view first = text.substr(0, text.find(','));
      first.find('=') == std::string_view::npos) {
    const auto named = std::find_if(kWorldErrorProfiles.begin(), kWorldErrorProfiles.end(),
                                    [&](const NamedWorldErrors& p) { return p.name == first; });
    if (named == kWorldErrorProfiles.end()) {
      return Error{ErrorCode::kInvalidArgument, "--world-errors: unknown profile '" +
                                                    std::string(first) +
                                                    "' (known: " + known_profiles() + ")"};
    }
    profile = named->profile;
    text = first.size() == text.size() ? std::string_view{} : text.substr(first.size() + 1);
    if (first.size() != whole.size() && text.empty()) {
      return Error{ErrorCode::kInvalidArgument, "--world-errors: '" + whole + "' ends in ','"};
    }
  }
  while (!text.empty()) {
    const std::size_t comma = text.find(',');
    const std::string_view item = text.substr(0, comma);
    text = comma == std::string_view::npos ? std::string_view{} : text.substr(comma + 1);
    const auto bad = [&](const std::string& why) {
      return Error{ErrorCode::kInvalidArgument,
                   "--world-errors: '" + std::string(item) + "': " + why};
    };
    const std::size_t eq = item.find('=');
    if (eq == std::string_view::npos) {
      return bad("no '=' (a profile comes first; keys: " + known_keys() + ")");
    }
    const std::string_view name = item.substr(0, eq);
    const std::string_view value = item.substr(eq + 1);
    const auto key =
        std::find_if(keys().begin(), keys().end(), [&](const Key& k) { return k.name == name; });
    if (key == keys().end()) return bad("unknown key (known: " + known_keys() + ")");
    double v = 0;
    const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
    if (value.empty() || ec != std::errc() || end != value.data() + value.size() ||
        !std::isfinite(v)) {
      return bad("not a number");
    }
    if (!(v >= 0 && v <= key->max)) {
      std::ostringstream os;
      os << "must be from 0 to " << key->max;
      return bad(os.str());
    }
    profile.*(key->field) = v;
    if (comma != std::string_view::npos && text.empty()) return bad("followed by an empty item");
  }
  return profile;
}

std::string format_world_errors(const WorldErrorProfile& profile) {
  std::ostringstream os;
  os << std::setprecision(17);
  bool first = true;
  for (const Key& k : keys()) {
    os << (first ? "" : ",") << k.name << '=' << profile.*(k.field);
    first = false;
  }
  return os.str();
}

Result<TrueWorld> make_true_world(const SewerMap& map, const WorldErrorProfile& profile,
                                  std::uint64_t seed) {
  if (Result<void> ok = check_profile(profile); !ok.has_value()) return ok.error();
  return WorldMaker(map, profile, seed).make(seed);
}

SensingModel make_sensing(const TrueWorld& truth) {
  const WorldErrorProfile& p = truth.profile;
  SensingModel s;
  s.drift = p.drift;
  s.wet = truth.wet;
  s.missed_share = p.missed_share;
  s.false_per_km = p.false_per_km;
  s.observe = !(p == WorldErrorProfile{});
  if (s.observe) {
    s.signature_noise = SignatureNoise{};
    // The joint encoders' error of a turn's angle (docs/simulation.md, "Sensing").
    s.turn_noise_deg = 1.0;
  }
  // A stream apart from the world's draws (splitmix64's constant).
  s.seed = Rng(truth.seed ^ 0x9e3779b97f4a7c15ULL).next();
  return s;
}

namespace {

const PipeSplit* split_of(const TrueWorld& truth, PipeId pipe) {
  const PipeSplit* split = nullptr;
  for (const PipeSplit& s : truth.splits) {
    if (s.pipe == pipe) split = &s;
  }
  return split;
}

}  // namespace

double world_length_m(const TrueWorld& truth, PipeId pipe) {
  const PipeSplit* split = split_of(truth, pipe);
  return truth.world.pipe(pipe).length_m + (split ? truth.world.pipe(split->rest).length_m : 0);
}

WorldSpot world_spot(const SewerMap& map, const TrueWorld& truth, PipeId pipe, double offset_m) {
  return spot_in(map.pipe(pipe).length_m, world_length_m(truth, pipe), split_of(truth, pipe), pipe,
                 offset_m);
}

SimPose world_pose(const SewerMap& map, const TrueWorld& truth, const SimPose& pose) {
  const auto* in = std::get_if<InPipe>(&pose);
  if (in == nullptr) return pose;
  const WorldSpot spot = world_spot(map, truth, in->pipe, in->offset_m);
  return InPipe{spot.pipe, spot.offset_m, in->heading};
}

FaultScenario world_faults(const SewerMap& map, const TrueWorld& truth, FaultScenario faults) {
  for (Obstacle& o : faults.obstacles) {
    const WorldSpot spot = world_spot(map, truth, o.pipe, o.offset_m);
    o.pipe = spot.pipe;
    o.offset_m = spot.offset_m;
  }
  for (DangerSpot& d : faults.danger_spots) {
    const WorldSpot spot = world_spot(map, truth, d.pipe, d.offset_m);
    d.pipe = spot.pipe;
    d.offset_m = spot.offset_m;
  }
  std::erase_if(faults.dangerous_passages, [&](const DangerousPassage& d) {
    const std::size_t count = truth.world.manhole(d.manhole).slot_count;
    return d.from_slot.value() >= count || d.to_slot.value() >= count;
  });
  return faults;
}

}  // namespace sewerplan::hal
