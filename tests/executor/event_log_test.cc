// SPDX-License-Identifier: MIT
// Executor::subscribe_log: the event log appended event by event, and a log that cannot be
// written reported in the mission report while the mission goes on unchanged.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "sewerplan/core/output_file.h"
#include "sewerplan/domain/robot_state.h"
#include "sewerplan/executor/event_json.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/sim_robot.h"

#include "support/ais_testbed.h"
#include <unistd.h>

namespace sewerplan::executor {
namespace {

struct PaperMission {
  testing::AisTestbed ais = testing::load_ais_testbed();
  ManualClock clock;
  Replanner replanner{ais.map, ais.mission, {.clock = &clock}};
  hal::SimRobot robot{ais.map, ais.mission.profile,
                      hal::InPipe{std::get<domain::InPipe>(replanner.progress().position).pipe,
                                  std::get<domain::InPipe>(replanner.progress().position).offset_m,
                                  hal::Heading::kTowardsEnd1}};
};

struct LoggedRun {
  MissionReport report;
  std::string lines;  // every event as a JSON line, as seen by an observer
  std::size_t events = 0;
};

LoggedRun run_mission(LogFile* log) {
  PaperMission m;
  Executor executor(m.ais.map, m.replanner, m.robot);
  LoggedRun run;
  executor.subscribe([&run](const Event& e) {
    run.lines += to_json_line(e) + '\n';
    ++run.events;
  });
  if (log != nullptr) executor.subscribe_log(*log);
  run.report = executor.run();
  return run;
}

TEST(ExecutorLog, TheLogHoldsEveryEventAsALine) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("sewerplan_events_" + std::to_string(::getpid()) + ".jsonl");
  Result<LogFile> log = LogFile::open(path);
  ASSERT_TRUE(log.has_value()) << log.error().message;
  const LoggedRun run = run_mission(&*log);
  ASSERT_TRUE(log->close().has_value());
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  std::filesystem::remove(path);
  EXPECT_EQ(text.str(), run.lines);
  EXPECT_TRUE(run.report.log_errors.empty());
}

TEST(ExecutorLog, AFailingLogIsReportedAndTheMissionGoesOn) {
  const LoggedRun without = run_mission(nullptr);
  Result<LogFile> log = LogFile::open("/dev/full");
  ASSERT_TRUE(log.has_value()) << log.error().message;
  const LoggedRun with = run_mission(&*log);
  // The same mission, to the same end.
  EXPECT_EQ(with.report.outcome, without.report.outcome);
  EXPECT_EQ(with.report.end, without.report.end);
  EXPECT_EQ(with.report.tasks_done, without.report.tasks_done);
  EXPECT_EQ(with.report.jobs, without.report.jobs);
  EXPECT_EQ(with.lines, without.lines);
  // ... and the report names the log, why, and what was lost: every event.
  ASSERT_EQ(with.report.log_errors.size(), 1U);
  EXPECT_EQ(with.report.log_errors[0], "cannot write /dev/full: No space left on device (" +
                                           std::to_string(with.events) + " of " +
                                           std::to_string(with.events) + " events lost)");
  std::ostringstream text;
  text << with.report;
  EXPECT_NE(text.str().find("log not written: cannot write /dev/full"), std::string::npos)
      << text.str();
}

}  // namespace
}  // namespace sewerplan::executor
