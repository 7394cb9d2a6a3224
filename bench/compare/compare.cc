// SPDX-License-Identifier: MIT
// sewerplan-compare: sewerplan against FF and Fast Downward on the same instances.
//
// A grid of generated networks and missions (and the datasets) is written to a work directory as
// map.json and mission.json, and as the PDDL export; each planner solves it under the same time
// limit and memory cap; every plan is validated by sewerplan's validator and costed by its cost
// model. Results go to a CSV file and a Markdown table (docs/benchmarks.md). The external planners
// are the user's: this program only runs the paths it is given.
//
//   sewerplan-compare --ff ~/planners/ff --fd ~/planners/downward/fast-downward.py
//       --sizes 10,100,1000 --tasks 3,10 --seeds 1,2 --time-limit 300 --out results/
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/output_file.h"
#include "sewerplan/domain/mission_generator.h"
#include "sewerplan/search/planner.h"

#include "planners.h"
#include "report.h"

namespace sewerplan::compare {
namespace {

namespace fs = std::filesystem;

struct Options {
  PlannerPaths paths;
  std::vector<std::size_t> sizes{10, 100, 1000, 10000, 100000};
  std::vector<std::size_t> tasks{3, 10, 20};
  std::vector<std::uint64_t> seeds{1, 2, 3};
  std::vector<std::string> datasets;  // MAP:MISSION
  bool no_datasets = false;
  double time_limit_s = 300;
  std::size_t memory_limit_mb = 8192;
  std::string out = "compare-results";
  std::string spread = "uniform";  // where generated missions' tasks lie (mission_generator.h)
};

std::optional<Instance> load_instance(Instance instance, std::string& error) {
  Diagnostics d;
  Result<SewerMap> map = read_map(instance.directory / "map.json", d);
  if (!map.has_value()) {
    error = map.error().message;
    return std::nullopt;
  }
  Result<Mission> mission = read_mission(instance.directory / "mission.json", *map, d);
  if (!mission.has_value()) {
    error = mission.error().message;
    return std::nullopt;
  }
  instance.map = std::move(*map);
  instance.mission = std::move(*mission);
  instance.manholes = instance.map.manhole_count();
  instance.tasks = instance.mission.tasks.size();
  return instance;
}

// Writes a generated instance's files; a mission seed that gives no mission is reported.
std::optional<Instance> generated(std::size_t manholes, std::size_t tasks, std::uint64_t seed,
                                  domain::MissionSpread spread, const fs::path& root,
                                  std::string& error) {
  Instance instance{.name = "g" + std::to_string(manholes) + "-t" + std::to_string(tasks) + "-s" +
                            std::to_string(seed),
                    .seed = std::to_string(seed)};
  instance.directory = root / instance.name;
  if (Result<void> made = create_output_directory(instance.directory); !made.has_value()) {
    error = made.error().message;
    return std::nullopt;
  }
  Result<SewerMap> map =
      generate_network({.manholes = manholes, .seed = seed, .topology = Topology::kMeshed});
  if (!map.has_value()) {
    error = map.error().message;
    return std::nullopt;
  }
  // Generated missions can be impossible (the robot's limits make some routes one-way); such an
  // instance says nothing about speed, so mission seeds are drawn until sewerplan finds a plan
  // or proves none exists eight times.
  std::optional<Mission> mission;
  for (std::uint64_t attempt = 0; attempt < 8 && !mission; ++attempt) {
    Result<Mission> candidate = domain::generate_mission(
        *map, {.tasks = tasks, .seed = seed + 1000 * attempt, .spread = spread});
    if (!candidate.has_value()) {
      error = candidate.error().message;
      return std::nullopt;
    }
    auto plan = search::plan_mission(*map, *candidate, domain::initial_progress(*candidate, *map),
                                     {.time_limit_s = 60});
    if (plan.has_value() || plan.error().code != ErrorCode::kNoPlan) mission = *candidate;
  }
  if (!mission) {
    error = "eight generated missions without a plan";
    return std::nullopt;
  }
  if (Result<void> w = write_map(*map, instance.directory / "map.json"); !w.has_value()) {
    error = w.error().message;
    return std::nullopt;
  }
  std::ostringstream out;
  write_mission_json(*mission, *map, out);
  if (Result<void> w = write_text_file(instance.directory / "mission.json", out.str());
      !w.has_value()) {
    error = w.error().message;
    return std::nullopt;
  }
  return load_instance(std::move(instance), error);
}

std::optional<Instance> dataset(const std::string& spec, const fs::path& root, std::string& error) {
  const auto colon = spec.find(':');
  if (colon == std::string::npos) {
    error = "--dataset " + spec + ": expected MAP:MISSION";
    return std::nullopt;
  }
  const fs::path map = spec.substr(0, colon);
  const fs::path mission = spec.substr(colon + 1);
  Instance instance{.name = map.parent_path().filename().string() + "-" + mission.stem().string(),
                    .seed = "-"};
  instance.directory = root / instance.name;
  if (Result<void> made = create_output_directory(instance.directory); !made.has_value()) {
    error = made.error().message;
    return std::nullopt;
  }
  std::error_code ec;
  fs::copy_file(map, instance.directory / "map.json", fs::copy_options::overwrite_existing, ec);
  if (!ec) {
    fs::copy_file(mission, instance.directory / "mission.json",
                  fs::copy_options::overwrite_existing, ec);
  }
  if (ec) {
    error = spec + ": " + ec.message();
    return std::nullopt;
  }
  return load_instance(std::move(instance), error);
}

std::string brief(const Outcome& o) {
  std::ostringstream s;
  s << o.planner << ' ' << o.status;
  if (o.solved()) s << ' ' << std::setprecision(3) << o.wall_s << " s";
  return s.str();
}

int run(const Options& options) {
  const fs::path root = options.out;
  if (Result<void> made = create_output_directory(root / "instances"); !made.has_value()) {
    std::cerr << "sewerplan-compare: " << made.error().message << '\n';
    return 3;
  }
  std::vector<std::string> datasets = options.datasets;
  if (datasets.empty() && !options.no_datasets) {
    // The source tree's copy, or, installed (the Debian package), the one beside the binary.
    std::string dir = std::string(SEWERPLAN_SOURCE_DIR) + "/datasets/ais-testbed/";
    std::error_code ec;
    if (!fs::exists(dir, ec)) {
      const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
      if (!ec)
        dir = (exe.parent_path().parent_path() / "share/sewerplan/datasets/ais-testbed/").string();
    }
    datasets.push_back(dir + "map.json:" + dir + "missions/paper.json");
  }
  const std::size_t total =
      datasets.size() + options.sizes.size() * options.tasks.size() * options.seeds.size();
  const RunLimits limits{.time_limit_s = options.time_limit_s,
                         .memory_limit_mb = options.memory_limit_mb};
  std::ostringstream settings;
  settings << "time limit " << options.time_limit_s << " s, memory cap " << options.memory_limit_mb
           << " MiB per run; Fast Downward alias " << options.paths.fd_alias;
  Result<Report> opened = Report::open(root / "results.csv", root / "results.md", settings.str());
  if (!opened.has_value()) {
    std::cerr << "sewerplan-compare: " << opened.error().message << '\n';
    return 3;
  }
  Report& report = *opened;
  std::size_t index = 0;
  auto solve = [&](std::optional<Instance> instance, const std::string& label,
                   const std::string& error) {
    ++index;
    std::cerr << '[' << index << '/' << total << "] " << label << ": " << std::flush;
    if (!instance) {
      std::cerr << "skipped (" << error << ")\n";
      report.skipped(label, error);
      return;
    }
    std::vector<Outcome> outcomes{run_sewerplan(*instance, options.paths, limits)};
    std::cerr << brief(outcomes.back()) << std::flush;
    if (!options.paths.ff.empty()) {
      outcomes.push_back(run_ff(*instance, options.paths, limits));
      std::cerr << ", " << brief(outcomes.back()) << std::flush;
    }
    if (!options.paths.fd.empty()) {
      outcomes.push_back(run_fd(*instance, options.paths, limits));
      std::cerr << ", " << brief(outcomes.back()) << std::flush;
    }
    std::cerr << '\n';
    report.add(*instance, outcomes);
  };
  for (const std::string& spec : datasets) {
    std::string error;
    auto instance = dataset(spec, root / "instances", error);
    const std::string label = instance ? instance->name : spec;
    solve(std::move(instance), label, error);
  }
  for (std::size_t manholes : options.sizes) {
    for (std::size_t tasks : options.tasks) {
      for (std::uint64_t seed : options.seeds) {
        std::string error;
        auto instance =
            generated(manholes, tasks, seed, *domain::mission_spread_from_string(options.spread),
                      root / "instances", error);
        solve(std::move(instance),
              "g" + std::to_string(manholes) + "-t" + std::to_string(tasks) + "-s" +
                  std::to_string(seed),
              error);
      }
    }
  }
  if (Result<void> w = report.finish(); !w.has_value()) {
    std::cerr << "sewerplan-compare: " << w.error().message << '\n';
    return 3;
  }
  std::cerr << "wrote " << (root / "results.csv").string() << " and "
            << (root / "results.md").string() << '\n';
  return 0;
}

}  // namespace
}  // namespace sewerplan::compare

int main(int argc, char** argv) {
  using namespace sewerplan::compare;  // NOLINT: this program's own namespace
  if (argc == 6 && std::string(argv[1]) == "--native-run") {
    // The child ends without destructors: freeing the map, the mission and the plan piece by
    // piece, only for the kernel to unmap them, is time FF's process does not spend either
    // (docs/benchmarks.md, the runner's start and end).
    const int code = native_child(argv[2], argv[3], argv[4], std::stod(argv[5]));
    std::cout.flush();
    std::_Exit(code);
  }
  Options options;
  CLI::App app{"sewerplan-compare: sewerplan against FF and Fast Downward on the same instances"};
  app.add_option("--ff", options.paths.ff, "Path of the FF executable (skipped if not given)")
      ->check(CLI::ExistingFile);
  app.add_option("--fd", options.paths.fd,
                 "Path of Fast Downward's fast-downward.py (skipped if not given)")
      ->check(CLI::ExistingFile);
  app.add_option("--fd-alias", options.paths.fd_alias, "Fast Downward alias")
      ->capture_default_str();
  app.add_option("--sizes", options.sizes, "Generated networks' manhole counts")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--tasks", options.tasks, "Tasks per generated mission")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--mission-spread", options.spread,
                 "Where generated missions' tasks lie: uniform, clustered or near-exit")
      ->check(CLI::IsMember({"uniform", "clustered", "near-exit"}))
      ->capture_default_str();
  app.add_option("--seeds", options.seeds, "Seeds of network and mission")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--dataset", options.datasets,
                 "MAP:MISSION files to include (default: the AIS test environment)");
  app.add_flag("--no-datasets", options.no_datasets, "Only generated instances");
  app.add_option("--time-limit", options.time_limit_s, "Seconds per planner run")
      ->capture_default_str();
  app.add_option("--memory-limit", options.memory_limit_mb, "MiB of address space per run")
      ->capture_default_str();
  app.add_option("--out", options.out, "Directory for instances and results")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  std::error_code ec;
  options.paths.self = std::filesystem::read_symlink("/proc/self/exe", ec).string();
  if (ec) options.paths.self = argv[0];
  return run(options);
}
