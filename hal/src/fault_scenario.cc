// SPDX-License-Identifier: MIT
#include "sewerplan/hal/fault_scenario.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "sewerplan/core/enum_names.h"
#include "sewerplan/core/rng.h"

namespace sewerplan::hal {
namespace {

// The kinds as a faults file names them (docs/simulation.md).
constexpr detail::EnumNames<ObstacleKind, 3> kObstacleKinds{{
    {ObstacleKind::kTransientLift, "transient_lift"},
    {ObstacleKind::kTransientPush, "transient_push"},
    {ObstacleKind::kPermanent, "permanent"},
}};

constexpr detail::EnumNames<MalfunctionKind, 2> kMalfunctionKinds{{
    {MalfunctionKind::kTransient, "transient"},
    {MalfunctionKind::kPermanent, "permanent"},
}};

static_assert(detail::distinct(kObstacleKinds) && detail::distinct(kMalfunctionKinds));

class StreamFormat {
 public:
  explicit StreamFormat(std::ostream& os)
      : os_(os), flags_(os.flags()), precision_(os.precision()) {
    os_ << std::fixed << std::setprecision(2);
  }
  ~StreamFormat() {
    os_.flags(flags_);
    os_.precision(precision_);
  }
  StreamFormat(const StreamFormat&) = delete;
  StreamFormat& operator=(const StreamFormat&) = delete;

 private:
  std::ostream& os_;
  std::ios_base::fmtflags flags_;
  std::streamsize precision_;
};

// A Poisson-distributed count with mean `mean`, by Knuth's multiplication method (the means here
// are small: faults per pipe). Large means are split so that exp(-mean) stays representable.
std::uint32_t poisson(Rng& rng, double mean) {
  std::uint32_t count = 0;
  while (mean > 0) {
    const double part = std::min(mean, 50.0);
    mean -= part;
    const double limit = std::exp(-part);
    double product = rng.uniform01();
    while (product > limit) {
      ++count;
      product *= rng.uniform01();
    }
  }
  return count;
}

bool drivable(const Pipe& pipe, const RandomFaultOptions& o) {
  return pipe.diameter_m >= o.min_pipe_diameter_m && pipe.diameter_m <= o.max_pipe_diameter_m &&
         pipe.length_m >= 2 * o.end_margin_m;
}

Result<void> check_options(const RandomFaultOptions& o) {
  std::string problems;
  const auto rate = [&](std::string_view name, double value) {
    if (!(std::isfinite(value) && value >= 0)) {
      problems += std::string(problems.empty() ? "" : "; ") + std::string(name) +
                  " must be finite and >= 0";
    }
  };
  const auto share = [&](std::string_view name, double value) {
    if (!(value >= 0 && value <= 1)) {
      problems +=
          std::string(problems.empty() ? "" : "; ") + std::string(name) + " must be from 0 to 1";
    }
  };
  const auto at_most = [&](std::string_view name, double value, double limit, const char* unit) {
    if (value > limit) {
      std::ostringstream out;
      out << name << " must be at most " << limit << unit << ", got " << value;
      problems += std::string(problems.empty() ? "" : "; ") + out.str();
    }
  };
  rate("obstacle_rate_per_km", o.obstacle_rate_per_km);
  rate("danger_rate_per_km", o.danger_rate_per_km);
  rate("malfunction_rate_per_hour", o.malfunction_rate_per_hour);
  rate("horizon_s", o.horizon_s);
  at_most("obstacle_rate_per_km", o.obstacle_rate_per_km, kMaxFaultsPerKm, " (one a metre)");
  at_most("danger_rate_per_km", o.danger_rate_per_km, kMaxFaultsPerKm, " (one a metre)");
  at_most("malfunction_rate_per_hour", o.malfunction_rate_per_hour, kMaxMalfunctionsPerHour,
          " (one a second)");
  at_most("horizon_s", o.horizon_s, kMaxHorizon_s, " s (a week)");
  rate("end_margin_m", o.end_margin_m);
  share("transient_share", o.transient_share);
  share("dangerous_passage_share", o.dangerous_passage_share);
  share("permanent_malfunction_share", o.permanent_malfunction_share);
  if (!problems.empty()) {
    return Error{ErrorCode::kInvalidArgument, "random faults: " + problems};
  }
  return {};
}

}  // namespace

std::string_view to_string(ObstacleKind kind) { return detail::name_of(kObstacleKinds, kind); }

std::optional<ObstacleKind> obstacle_kind_from_string(std::string_view name) {
  return detail::value_of(kObstacleKinds, name);
}

std::string obstacle_kind_names() { return detail::names_joined(kObstacleKinds); }

std::string_view to_string(MalfunctionKind kind) {
  return detail::name_of(kMalfunctionKinds, kind);
}

std::optional<MalfunctionKind> malfunction_kind_from_string(std::string_view name) {
  return detail::value_of(kMalfunctionKinds, name);
}

std::string malfunction_kind_names() { return detail::names_joined(kMalfunctionKinds); }

bool FaultScenario::empty() const {
  return obstacles.empty() && danger_spots.empty() && dangerous_passages.empty() &&
         malfunctions.empty() && !battery_wh;
}

std::ostream& operator<<(std::ostream& os, const Obstacle& obstacle) {
  StreamFormat format(os);
  return os << "obstacle in pipe " << obstacle.pipe << " at " << obstacle.offset_m << " m ("
            << to_string(obstacle.kind) << ')';
}

std::ostream& operator<<(std::ostream& os, const DangerSpot& spot) {
  StreamFormat format(os);
  return os << "danger in pipe " << spot.pipe << " at " << spot.offset_m << " m";
}

std::ostream& operator<<(std::ostream& os, const DangerousPassage& passage) {
  return os << "dangerous passage in manhole " << passage.manhole << " from slot "
            << to_paper_number(passage.from_slot) << " to slot "
            << to_paper_number(passage.to_slot);
}

std::ostream& operator<<(std::ostream& os, const Malfunction& malfunction) {
  StreamFormat format(os);
  os << to_string(malfunction.kind) << " malfunction ";
  if (const auto* at_job = std::get_if<AtJob>(&malfunction.when)) {
    return os << "at job " << at_job->index;
  }
  return os << "at " << std::get<AtTime>(malfunction.when).time_s << " s";
}

std::ostream& operator<<(std::ostream& os, const FaultScenario& scenario) {
  os << "faults:";
  if (scenario.empty()) return os << " none";
  for (const Obstacle& o : scenario.obstacles) os << "\n  " << o;
  for (const DangerSpot& d : scenario.danger_spots) os << "\n  " << d;
  for (const DangerousPassage& p : scenario.dangerous_passages) os << "\n  " << p;
  for (const Malfunction& m : scenario.malfunctions) os << "\n  " << m;
  if (scenario.battery_wh) {
    StreamFormat format(os);
    os << "\n  battery " << *scenario.battery_wh << " Wh";
  }
  return os;
}

Result<void> validate_faults(const FaultScenario& scenario, const SewerMap& map) {
  std::ostringstream problems;
  const auto in_pipe = [&](const auto& fault, PipeId pipe, double offset_m) {
    if (pipe.index() >= map.pipe_count()) {
      problems << '\n' << fault << ": no such pipe";
    } else if (!(offset_m >= 0 && offset_m <= map.pipe(pipe).length_m)) {
      problems << '\n'
               << fault << ": offset outside the pipe (0 to " << map.pipe(pipe).length_m << " m)";
    }
  };
  for (const Obstacle& o : scenario.obstacles) in_pipe(o, o.pipe, o.offset_m);
  for (const DangerSpot& d : scenario.danger_spots) in_pipe(d, d.pipe, d.offset_m);
  for (const DangerousPassage& p : scenario.dangerous_passages) {
    if (p.manhole.index() >= map.manhole_count()) {
      problems << '\n' << p << ": no such manhole";
    } else if (p.from_slot.value() >= map.manhole(p.manhole).slot_count ||
               p.to_slot.value() >= map.manhole(p.manhole).slot_count || p.from_slot == p.to_slot) {
      problems << '\n'
               << p << ": the manhole has " << map.manhole(p.manhole).slot_count
               << " slots; from and to must be two of them";
    }
  }
  for (const Malfunction& m : scenario.malfunctions) {
    if (const auto* at = std::get_if<AtTime>(&m.when); at && !(at->time_s >= 0)) {
      problems << '\n' << m << ": the time must be >= 0";
    }
  }
  if (scenario.battery_wh && !(std::isfinite(*scenario.battery_wh) && *scenario.battery_wh >= 0)) {
    problems << "\nbattery_wh must be finite and >= 0";
  }
  if (problems.str().empty()) return {};
  return Error{ErrorCode::kInvalidArgument, "invalid fault scenario:" + problems.str()};
}

RandomFaultOptions random_fault_options(const RobotProfile& profile) {
  RandomFaultOptions o;
  o.min_pipe_diameter_m = profile.min_pipe_diameter_m;
  o.max_pipe_diameter_m = profile.max_pipe_diameter_m;
  return o;
}

Result<FaultScenario> random_faults(const SewerMap& map, const RandomFaultOptions& options) {
  if (Result<void> ok = check_options(options); !ok.has_value()) return ok.error();
  // The expected number of faults, before drawing any: a long network at a high rate would
  // otherwise draw without bound (hours and gigabytes).
  double drivable_km = 0;
  for (PipeId id : map.pipe_ids()) {
    if (drivable(map.pipe(id), options)) drivable_km += map.pipe(id).length_m / 1000.0;
  }
  const double expected =
      (options.obstacle_rate_per_km + options.danger_rate_per_km) * drivable_km +
      options.malfunction_rate_per_hour * options.horizon_s / 3600.0;
  if (!(expected <= static_cast<double>(kMaxRandomFaults))) {
    std::ostringstream out;
    out << "random faults: " << expected << " faults expected (" << drivable_km
        << " km of drivable pipe), at most " << kMaxRandomFaults
        << " can be drawn: lower the rates";
    return Error{ErrorCode::kInvalidArgument, out.str()};
  }
  // One independent stream per kind of fault, so that changing one rate leaves the others alone.
  Rng root(options.seed);
  Rng obstacles = root.split();
  Rng dangers = root.split();
  Rng passages = root.split();
  Rng malfunctions = root.split();
  FaultScenario scenario;
  for (PipeId id : map.pipe_ids()) {
    const Pipe& pipe = map.pipe(id);
    if (!drivable(pipe, options)) continue;
    const double lo_m = options.end_margin_m;
    const double hi_m = pipe.length_m - options.end_margin_m;
    const double length_km = pipe.length_m / 1000.0;
    const std::uint32_t n_obstacles = poisson(obstacles, options.obstacle_rate_per_km * length_km);
    for (std::uint32_t i = 0; i < n_obstacles; ++i) {
      Obstacle o{id, lo_m < hi_m ? obstacles.uniform(lo_m, hi_m) : lo_m, ObstacleKind::kPermanent};
      if (obstacles.bernoulli(options.transient_share)) {
        o.kind =
            obstacles.bernoulli(0.5) ? ObstacleKind::kTransientLift : ObstacleKind::kTransientPush;
      }
      scenario.obstacles.push_back(o);
    }
    const std::uint32_t n_dangers = poisson(dangers, options.danger_rate_per_km * length_km);
    for (std::uint32_t i = 0; i < n_dangers; ++i) {
      scenario.danger_spots.push_back({id, lo_m < hi_m ? dangers.uniform(lo_m, hi_m) : lo_m});
    }
  }
  if (options.dangerous_passage_share > 0) {
    for (ManholeId m : map.manhole_ids()) {
      const auto slots = map.slots(m);
      for (std::uint16_t a = 0; a < slots.size(); ++a) {
        for (auto b = static_cast<std::uint16_t>(a + 1); b < slots.size(); ++b) {
          if (!drivable(map.pipe(slots[a].pipe), options) ||
              !drivable(map.pipe(slots[b].pipe), options)) {
            continue;
          }
          if (passages.bernoulli(options.dangerous_passage_share)) {
            scenario.dangerous_passages.push_back({m, SlotIndex{a}, SlotIndex{b}});
          }
        }
      }
    }
  }
  // A Poisson process in mission time: exponential gaps between malfunctions.
  const double rate_per_s = options.malfunction_rate_per_hour / 3600.0;
  if (rate_per_s > 0) {
    double time_s = 0;
    while (true) {
      time_s += -std::log(1.0 - malfunctions.uniform01()) / rate_per_s;
      if (time_s > options.horizon_s) break;
      const bool permanent = malfunctions.bernoulli(options.permanent_malfunction_share);
      scenario.malfunctions.push_back(
          {AtTime{time_s}, permanent ? MalfunctionKind::kPermanent : MalfunctionKind::kTransient});
      if (permanent) break;  // nothing after a permanent fault can happen
    }
  }
  return scenario;
}

}  // namespace sewerplan::hal
