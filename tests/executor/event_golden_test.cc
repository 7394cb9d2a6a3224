// SPDX-License-Identifier: MIT
// The event log's JSON lines stay byte-identical: missions on the paper's test environment, with
// and without faults, against logs written before events became typed (tests/data/events/).
// Planning times are 0 (a ManualClock), so the logs are the same on every run.
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "sewerplan/executor/event_json.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"

#include "support/ais_testbed.h"
#include "support/paths.h"

namespace sewerplan::executor {
namespace {

struct Scenario {
  const char* golden;      // in tests/data/events/
  const char* fault_file;  // in datasets/ais-testbed/faults/, or empty
  hal::RandomFaultOptions random;
  bool push_allowed = false;
};

hal::FaultScenario faults_of(const Scenario& s, const SewerMap& map) {
  if (*s.fault_file != '\0') {
    Diagnostics d;
    std::ifstream in(testing::dataset_path(std::string("ais-testbed/faults/") + s.fault_file));
    std::stringstream text;
    text << in.rdbuf();
    auto f = hal::read_faults_json(text.str(), s.fault_file, map, d);
    EXPECT_TRUE(f.has_value()) << d.error_summary();
    return f.has_value() ? *f : hal::FaultScenario{};
  }
  if (s.random.seed == 0) return {};
  auto f = hal::random_faults(map, s.random);
  EXPECT_TRUE(f.has_value());
  return f.has_value() ? *f : hal::FaultScenario{};
}

std::string run_log(const Scenario& s) {
  const auto ais = testing::load_ais_testbed();
  ManualClock clock;
  Replanner replanner(ais.map, ais.mission, {.clock = &clock});
  const auto& start = std::get<domain::InPipe>(replanner.progress().position);
  hal::SimRobot robot(ais.map, ais.mission.profile,
                      hal::InPipe{start.pipe, start.offset_m, hal::Heading::kTowardsEnd1},
                      faults_of(s, ais.map));
  ExecutorOptions options;
  options.recovery.push_allowed = s.push_allowed;
  std::ostringstream json;
  Executor executor(ais.map, replanner, robot, options);
  executor.subscribe(json_lines_writer(json));
  (void)executor.run();
  return json.str();
}

std::string golden(const char* name) {
  std::ifstream in(testing::test_data_path(std::string("events/") + name));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

hal::RandomFaultOptions harsh(std::uint64_t seed) {
  return {.seed = seed,
          .obstacle_rate_per_km = 60,
          .danger_rate_per_km = 15,
          .dangerous_passage_share = 0.2,
          .malfunction_rate_per_hour = 4,
          .permanent_malfunction_share = 0.2};
}

class EventGolden : public ::testing::TestWithParam<Scenario> {};

// SEWERPLAN_UPDATE_GOLDEN=1 rewrites the golden logs after an intended change of the format;
// review their diff before committing it.
TEST_P(EventGolden, TheLogIsByteIdenticalToTheOneWrittenBefore) {
  const Scenario& s = GetParam();
  if (std::getenv("SEWERPLAN_UPDATE_GOLDEN") != nullptr) {
    std::ofstream(testing::test_data_path(std::string("events/") + s.golden)) << run_log(s);
  }
  const std::string expected = golden(s.golden);
  ASSERT_FALSE(expected.empty()) << s.golden;
  EXPECT_EQ(run_log(s), expected);
}

INSTANTIATE_TEST_SUITE_P(
    Ais, EventGolden,
    ::testing::Values(
        Scenario{"paper.jsonl", "", {}}, Scenario{"demo.jsonl", "demo.json", {}},
        Scenario{"blocked-p5.jsonl", "blocked-p5.json", {}},
        Scenario{"transient-p1.jsonl", "transient-p1.json", {}},
        Scenario{"random-1.jsonl", "", harsh(1)}, Scenario{"random-2.jsonl", "", harsh(2), true},
        Scenario{"random-3.jsonl", "", harsh(3)}, Scenario{"random-4.jsonl", "", harsh(4)},
        Scenario{"random-5.jsonl", "", harsh(5)}, Scenario{"random-6.jsonl", "", harsh(6)},
        // A permanent malfunction: the beacon. Danger spots everywhere.
        Scenario{"beacon.jsonl",
                 "",
                 {.seed = 7, .malfunction_rate_per_hour = 30, .permanent_malfunction_share = 1}},
        Scenario{"danger.jsonl", "", {.seed = 8, .danger_rate_per_km = 100}}),
    [](const auto& test) {
      std::string name = test.param.golden;
      name = name.substr(0, name.find('.'));
      for (char& c : name) c = c == '-' ? '_' : c;
      return name;
    });

}  // namespace
}  // namespace sewerplan::executor
