// SPDX-License-Identifier: MIT
// FaultScenario: the trouble hidden in a simulated sewer, which the robot meets only by driving.
//
// The paper's robot meets three kinds of trouble (Adria, Streich and Hertzberg 2004, section 4.7):
// the path is blocked (BLOCKAGE), going on could damage it (DANGER), or it fails itself
// (MALFUNCTION). A FaultScenario is the ground truth behind those reports for the simulated robot
// (sim_robot.h): obstacles in pipes (transient ones clear when the head is lifted next to them or
// after a push, permanent ones never), dangerous spots in pipes and dangerous passages through
// manholes, malfunctions at a job or a time (transient: a reboot clears them; permanent: the robot
// is done), and optionally a battery holding less than the profile says. The planner never sees
// it. Scenarios are plain values: read from a JSON file (docs/simulation.md), drawn at random from
// a seed and rates, and written back so that a random scenario can be replayed.
//
//   Diagnostics diagnostics;
//   Result<FaultScenario> faults =
//       read_faults("datasets/ais-testbed/faults/blocked-p5.json", map, diagnostics);
//   FaultScenario drawn = *random_faults(map, {.seed = 7, .obstacle_rate_per_km = 20});
//   write_faults_json(drawn, map, std::cout);
//
// Thread safety: Plain values and pure functions: const access from several threads is safe.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/sewer_map.h"

namespace simdjson::dom {
class element;  // JsonElement (core/json_fields.h), which this header does not pull in
}  // namespace simdjson::dom

namespace sewerplan::hal {

inline constexpr std::string_view kFaultsJsonFormat = "sewerplan-faults";
inline constexpr int kFaultsJsonVersion = 1;

enum class ObstacleKind : std::uint8_t {
  kTransientLift,  // clears when the head is lifted within reach of it
  kTransientPush,  // clears when the robot pushes against it
  kPermanent,      // never clears
};

// "transient_lift", "transient_push", "permanent".
std::string_view to_string(ObstacleKind kind);
std::optional<ObstacleKind> obstacle_kind_from_string(std::string_view name);
// The names obstacle_kind_from_string reads, "transient_lift, transient_push, permanent".
std::string obstacle_kind_names();

// Something in pipe `pipe` at `offset_m` from its ends[0] that the robot cannot drive past, in
// either direction.
struct Obstacle {
  PipeId pipe{0};
  double offset_m = 0;
  ObstacleKind kind = ObstacleKind::kPermanent;
  friend bool operator==(const Obstacle&, const Obstacle&) = default;
};

// A place in a pipe the robot must not drive onto (a hole, a deep sump), in either direction.
struct DangerSpot {
  PipeId pipe{0};
  double offset_m = 0;
  friend bool operator==(const DangerSpot&, const DangerSpot&) = default;
};

// A passage of `manhole` between two slots (from 0) the robot must not take, in either direction.
struct DangerousPassage {
  ManholeId manhole{0};
  SlotIndex from_slot{0};
  SlotIndex to_slot{0};
  friend bool operator==(const DangerousPassage&, const DangerousPassage&) = default;
};

enum class MalfunctionKind : std::uint8_t {
  kTransient,  // the job fails, and every job until reboot(); reboot() clears it
  kPermanent,  // the job and every later one fail; reboot() fails
};

// "transient", "permanent".
std::string_view to_string(MalfunctionKind kind);
std::optional<MalfunctionKind> malfunction_kind_from_string(std::string_view name);
// The names malfunction_kind_from_string reads, "transient, permanent".
std::string malfunction_kind_names();

// The malfunction strikes the job with this index (from 0, counting every job executed) ...
struct AtJob {
  std::uint32_t index = 0;
  friend bool operator==(const AtJob&, const AtJob&) = default;
};
// ... or when the mission's time reaches `time_s` (during a job, or at the next job's start).
struct AtTime {
  double time_s = 0;
  friend bool operator==(const AtTime&, const AtTime&) = default;
};

struct Malfunction {
  std::variant<AtJob, AtTime> when = AtJob{};
  MalfunctionKind kind = MalfunctionKind::kTransient;
  friend bool operator==(const Malfunction&, const Malfunction&) = default;
};

struct FaultScenario {
  std::vector<Obstacle> obstacles;
  std::vector<DangerSpot> danger_spots;
  std::vector<DangerousPassage> dangerous_passages;
  std::vector<Malfunction> malfunctions;
  // The charge the battery really holds at the start; empty: the profile's battery_wh.
  std::optional<double> battery_wh;

  bool empty() const;
  friend bool operator==(const FaultScenario&, const FaultScenario&) = default;
};

// One line per fault with IDs ("obstacle pipe #4 at 12.30 m (permanent)"); for names use
// write_faults_json.
std::ostream& operator<<(std::ostream& os, const Obstacle& obstacle);
std::ostream& operator<<(std::ostream& os, const DangerSpot& spot);
std::ostream& operator<<(std::ostream& os, const DangerousPassage& passage);
std::ostream& operator<<(std::ostream& os, const Malfunction& malfunction);
std::ostream& operator<<(std::ostream& os, const FaultScenario& scenario);

// Checks that every ID belongs to `map`, offsets lie in their pipes, the passages' slots exist
// and differ, times and the battery are finite and not negative. The error names each fault.
Result<void> validate_faults(const FaultScenario& scenario, const SewerMap& map);

// --- Random scenarios -----------------------------------------------------------------------

// Rates for random_faults. Faults are placed on drivable pipes only: diameter within
// [min_pipe_diameter_m, max_pipe_diameter_m] (a robot profile's limits) and no shorter than
// 2 x end_margin_m; offsets are uniform at least end_margin_m from either end.
struct RandomFaultOptions {
  std::uint64_t seed = 0;
  double obstacle_rate_per_km = 0;       // expected obstacles per km of drivable pipe (Poisson)
  double transient_share = 0.5;          // of obstacles; transient ones are half lift, half push
  double danger_rate_per_km = 0;         // expected danger spots per km of drivable pipe (Poisson)
  double dangerous_passage_share = 0;    // probability that a passage between drivable pipes is one
  double malfunction_rate_per_hour = 0;  // Poisson process in mission time over horizon_s
  double permanent_malfunction_share = 0;
  double horizon_s = 4 * 3600.0;
  double min_pipe_diameter_m = 0.30;
  double max_pipe_diameter_m = 0.60;
  double end_margin_m = 0.5;
};

// The limits of random_faults: rates beyond these are no sewer's, and more faults than
// kMaxRandomFaults (expected, before drawing) would take the drawing hours and gigabytes.
inline constexpr double kMaxFaultsPerKm = 1000;          // obstacles, and danger spots: one a metre
inline constexpr double kMaxMalfunctionsPerHour = 3600;  // one a second
inline constexpr double kMaxHorizon_s = 7 * 24 * 3600.0;
inline constexpr std::size_t kMaxRandomFaults = 1'000'000;

// The drivable pipes of `profile` (its diameter limits): where random faults lie, for `simulate`
// and `campaign` alike.
RandomFaultOptions random_fault_options(const RobotProfile& profile);

// A scenario drawn with Rng (core/rng.h) only: the same map and options give the same scenario on
// every platform. Faults come in pipe, manhole and time order. An error if a rate or share is
// negative or not finite, a share exceeds 1, a rate or the horizon exceeds its limit above, or
// more than kMaxRandomFaults faults are expected on `map`. Runtime: O(pipes + slots^2 per manhole
// + faults).
Result<FaultScenario> random_faults(const SewerMap& map, const RandomFaultOptions& options);

// --- JSON files (format: docs/simulation.md) --------------------------------------------------

// Reads a fault file's text; names are resolved against `map`. Every problem goes to
// `diagnostics` as "file:$.obstacles[0].pipe: ..." and the load fails with kParse (not JSON, or
// not the format) or kInvalidArgument (unknown names, bad kinds, offsets outside the pipe, ...).
Result<FaultScenario> read_faults_json(std::string_view text, const std::string& file_name,
                                       const SewerMap& map, Diagnostics& diagnostics);
// The same, of faults parsed already (json_fields.h) at JSON path `path` of `file_name`: a
// request's body that holds them among other members ("body:$.faults.obstacles[0].pipe: ...").
Result<FaultScenario> read_faults_value(const simdjson::dom::element& value,
                                        const std::string& path, const std::string& file_name,
                                        const SewerMap& map, Diagnostics& diagnostics);
Result<FaultScenario> read_faults(const std::filesystem::path& path, const SewerMap& map,
                                  Diagnostics& diagnostics);

// Writes `scenario` in the format read_faults_json reads, names from `map`; numbers are written
// exactly (shortest round-trip form), so reading it back gives an equal scenario.
void write_faults_json(const FaultScenario& scenario, const SewerMap& map, std::ostream& out);
std::string faults_json(const FaultScenario& scenario, const SewerMap& map);

}  // namespace sewerplan::hal
