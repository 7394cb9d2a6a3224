// SPDX-License-Identifier: MIT
// The event log's codec: JSON lines read back into the same typed events and written back to the
// same bytes; logs of earlier versions read; bad lines named by file and line; the readable line.
#include "sewerplan/executor/event_json.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "sewerplan/executor/event_text.h"
#include "sewerplan/executor/events.h"
#include "sewerplan/executor/replanner.h"

#include "event_fields.h"
#include "support/enum_round_trip.h"
#include "support/paths.h"

namespace sewerplan::executor {
namespace {

std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

using testing::expect_round_trip;

TEST(EnumNames, EveryValueRoundTripsThroughItsNameAndBack) {
  expect_round_trip({MissionOutcome::kEnded, MissionOutcome::kBeacon, MissionOutcome::kHalted},
                    parse_mission_outcome);
  expect_round_trip({BeaconCause::kNone, BeaconCause::kNoExit, BeaconCause::kStuck,
                     BeaconCause::kMalfunction, BeaconCause::kLink, BeaconCause::kLimit},
                    parse_beacon_cause);
  expect_round_trip({HazardEvent::Observed::kPassed, HazardEvent::Observed::kBlocked},
                    parse_hazard_observed);
  expect_round_trip({Failure::Kind::kBlockage, Failure::Kind::kDangerInPipe,
                     Failure::Kind::kDangerousPassage, Failure::Kind::kStuck},
                    parse_failure_kind);
  expect_round_trip(
      {PlanResponse::Decision::kFollowPlan, PlanResponse::Decision::kDegraded,
       PlanResponse::Decision::kExitOnReserve, PlanResponse::Decision::kCallForRecovery,
       PlanResponse::Decision::kStuck, PlanResponse::Decision::kInvalidReport},
      parse_decision);
  expect_round_trip({PlanResponse::Rung::kSearch, PlanResponse::Rung::kBestSoFar,
                     PlanResponse::Rung::kCurrentPlan, PlanResponse::Rung::kRepairedPlan,
                     PlanResponse::Rung::kGreedy, PlanResponse::Rung::kNearestExit},
                    parse_rung);
}

TEST(EnumNames, EveryEventTypeRoundTripsThroughItsNameAndBack) {
  using detail::EventType;
  expect_round_trip(
      {EventType::kPlan, EventType::kReplan, EventType::kAction, EventType::kJob, EventType::kError,
       EventType::kRecovery, EventType::kFailure, EventType::kTaskDone, EventType::kTaskDropped,
       EventType::kReserve, EventType::kArrival, EventType::kHazard, EventType::kBeacon,
       EventType::kMissionEnd},
      detail::parse_event_type);
}

TEST(EnumNames, AnEventIsNamedByItsType) {
  EXPECT_EQ(type_name(Event{.what = PlanEvent{.replan = false}}), "plan");
  EXPECT_EQ(type_name(Event{.what = PlanEvent{.replan = true}}), "replan");
  EXPECT_EQ(type_name(Event{.what = TaskDoneEvent{}}), "task_done");
  EXPECT_EQ(type_name(Event{.what = MissionEndEvent{}}), "mission_end");
}

class EventLogFile : public ::testing::TestWithParam<const char*> {};

TEST_P(EventLogFile, ReadsBackIntoEventsThatWriteTheSameBytes) {
  const std::string text = file_text(testing::test_data_path(std::string("events/") + GetParam()));
  ASSERT_FALSE(text.empty());
  Diagnostics d;
  Result<std::vector<Event>> events = read_event_log(text, GetParam(), d);
  ASSERT_TRUE(events.has_value()) << d.error_summary();
  std::string written;
  for (const Event& e : *events) written += to_json_line(e) + '\n';
  EXPECT_EQ(written, text);
  ASSERT_FALSE(events->empty());
  EXPECT_TRUE(std::holds_alternative<MissionEndEvent>(events->back().what));
}

INSTANTIATE_TEST_SUITE_P(Golden, EventLogFile,
                         ::testing::Values("paper.jsonl", "demo.jsonl", "blocked-p5.jsonl",
                                           "transient-p1.jsonl", "random-1.jsonl", "random-2.jsonl",
                                           "random-3.jsonl", "random-4.jsonl", "random-5.jsonl",
                                           "random-6.jsonl"));

TEST(EventLog, ALogOfTheFirstVersionStillReads) {
  // Decisions named "follow", no decision and beacon cause at the mission's end.
  const std::string text =
      file_text(testing::source_dir() / "fuzz" / "corpus" / "event_log" / "demo.jsonl");
  Diagnostics d;
  Result<std::vector<Event>> events = read_event_log(text, "demo.jsonl", d);
  ASSERT_TRUE(events.has_value()) << d.error_summary();
  const auto* plan = std::get_if<PlanEvent>(&events->front().what);
  ASSERT_NE(plan, nullptr);
  EXPECT_EQ(plan->decision, PlanResponse::Decision::kFollowPlan);
  EXPECT_EQ(plan->goals, (std::vector<std::string>{"sample", "inspect", "end"}));
  const auto* end = std::get_if<MissionEndEvent>(&events->back().what);
  ASSERT_NE(end, nullptr);
  EXPECT_EQ(end->outcome, MissionOutcome::kEnded);
  EXPECT_EQ(end->beacon_cause, BeaconCause::kNone);
}

TEST(EventLog, EveryKindOfEventReadsBackEqual) {
  const std::vector<Event> events{
      {0, PlanEvent{.reason = "start", .goals = {"a"}, .steps = 3, .cost_s = 1.5}},
      {1.25, PlanEvent{.replan = true, .decision = PlanResponse::Decision::kDegraded}},
      {1.5, PlanEvent{.replan = true, .rung = PlanResponse::Rung::kGreedy}},
      {1.5, PlanEvent{.replan = true, .cost_s = 2, .strand_probability = 0.0975}},
      {2, ActionEvent{"DRIVE_PIPE_TO_MANHOLE P1 M3", "drive_to_manhole", 9.5, "x"}},
      {3, JobEvent{"DriveForward(0.30 m/s, 2.83 m)", 2.8285, false}},
      {3, ErrorEvent{hal::RobotErrorKind::kDanger, "danger", "in pipe P1 at 2.00 m"}},
      {4, RecoveryEvent{RecoveryPhase::kLiftHeadAndRetry, true}},
      {5, FailureEvent{Failure::Kind::kBlockage, FailureEvent::InPipe{"P5", 3.951}, "obstacle"}},
      {5, FailureEvent{Failure::Kind::kDangerousPassage, FailureEvent::Passage{"M8", 1, 2}, "d"}},
      {5, FailureEvent{Failure::Kind::kStuck, std::monostate{}, "motor"}},
      {6, TaskDoneEvent{"sample"}},
      {6, TaskDroppedEvent{"inspect", "cut off"}},
      {6.5, ReserveEvent{"exit M4", 3.25, 5.5, 6}},
      {6.75, ArrivalEvent{"M6 slot 2", "wrong-manhole", 0.125, "at M7 slot 1 (P9)", "M7",
                          "3 slots at 0, 90, 180°", "M7 fits, M6 not: 3 slots seen, 4 expected"}},
      {6.875, HazardEvent{"P5", 12.5, "BBA roots", HazardEvent::Observed::kPassed, 0.1, 0.0625, 3}},
      {6.9, HazardEvent{"P5", 12.5, "BBA roots", HazardEvent::Observed::kBlocked, 0.0625, 1, 3}},
      {7, BeaconEvent{"no exit"}},
      {8, MissionEndEvent{.outcome = MissionOutcome::kHalted,
                          .tasks_done = {"sample"},
                          .replans = 2,
                          .beacon_cause = BeaconCause::kLink}}};
  std::string text;
  for (const Event& e : events) text += to_json_line(e) + '\n';
  Diagnostics d;
  Result<std::vector<Event>> read = read_event_log(text, "all.jsonl", d);
  ASSERT_TRUE(read.has_value()) << d.error_summary() << text;
  EXPECT_EQ(*read, events) << text;
  // The rung is written when it is not the search's (issue 34), so older logs read the same.
  EXPECT_NE(text.find(R"("cost_s":0.0,"rung":"greedy"})"), std::string::npos) << text;
  EXPECT_EQ(text.find(R"("rung":"search")"), std::string::npos) << text;
}

// Counts the flushes of the stream written to.
class SyncCounter : public std::stringbuf {
 public:
  int syncs = 0;

 protected:
  int sync() override {
    ++syncs;
    return std::stringbuf::sync();
  }
};

TEST(EventLog, TheWriterFlushesEveryLineSoThatAWatcherSeesIt) {
  SyncCounter buffer;
  std::ostream out(&buffer);
  const EventObserver write = json_lines_writer(out);
  write({0, PlanEvent{.reason = "start"}});
  EXPECT_EQ(buffer.syncs, 1);
  write({3, JobEvent{"DriveForward(0.30 m/s, 2.83 m)", 2.83, true}});
  EXPECT_EQ(buffer.syncs, 2);
  const std::string text = buffer.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2);
}

TEST(EventLog, BadLinesAreNamedByFileAndLineAndOtherTypesSkipped) {
  const std::string text =
      "{\"t_s\":0.0,\"type\":\"task_done\",\"task\":\"a\"}\n"
      "not json\n"
      "\n"
      "{\"t_s\":1.0,\"type\":\"job\",\"ok\":\"yes\"}\n"
      "{\"t_s\":1.0,\"type\":\"plan\",\"decision\":\"maybe\"}\n"
      "{\"t_s\":1.0,\"type\":\"from_a_newer_version\",\"x\":1}\n"
      "{\"t_s\":1.0}\n"
      "{\"t_s\":1.0,\"type\":\"task_done\",\"task\":\"a\",\"task\":\"b\"}\n"
      "{\"t_s\":1.0,\"type\":\"plan\",\"steps\":2.5,\"goals\":[\"a\",7]}\n";
  Diagnostics d;
  EXPECT_FALSE(read_event_log(text, "run.jsonl", d).has_value());
  const std::string errors = d.error_summary();
  EXPECT_NE(errors.find("run.jsonl:2: error: not a JSON object"), std::string::npos) << errors;
  EXPECT_NE(errors.find("run.jsonl:4:$.ok: error: expected true or false, got \"yes\""),
            std::string::npos)
      << errors;
  EXPECT_NE(errors.find("run.jsonl:5:$.decision: error: unknown decision 'maybe'"),
            std::string::npos)
      << errors;
  EXPECT_NE(errors.find("run.jsonl:7: error: no \"type\""), std::string::npos) << errors;
  EXPECT_EQ(errors.find("run.jsonl:6"), std::string::npos) << errors;
  // simdjson alone would keep the first "task" and drop the second without a word.
  EXPECT_NE(errors.find("run.jsonl:8:$.task: error: field 'task' given twice"), std::string::npos)
      << errors;
  EXPECT_NE(errors.find("run.jsonl:9:$.steps: error: expected a whole number from 0 to "),
            std::string::npos)
      << errors;
  EXPECT_NE(errors.find("run.jsonl:9:$.goals[1]: error: expected a name (a string), got 7"),
            std::string::npos)
      << errors;

  // Counts are read exactly: one past 2^53 is not rounded down into range.
  Diagnostics big;
  EXPECT_FALSE(read_event_log("{\"t_s\":1.0,\"type\":\"plan\",\"steps\":9007199254740993}\n",
                              "big.jsonl", big)
                   .has_value());
  EXPECT_NE(
      big.error_summary().find("big.jsonl:1:$.steps: error: expected a whole number from 0 to "
                               "9007199254740992, got 9007199254740993"),
      std::string::npos)
      << big.error_summary();

  Diagnostics fine;
  const std::vector<LoggedEvent> skipped = read_event_log_lines(
      "\n{\"t_s\":1.0,\"type\":\"from_a_newer_version\"}\n{\"type\":\"beacon\"}\n", "x", fine);
  EXPECT_FALSE(fine.has_errors()) << fine.error_summary();
  ASSERT_EQ(skipped.size(), 1U);
  EXPECT_EQ(skipped.front().line, 3U);
}

TEST(EventLog, TheReadableLineHasTheTimeTheTypeAndTheFieldsInOrder) {
  EXPECT_EQ(readable_line({39.262, ErrorEvent{hal::RobotErrorKind::kBlockage,
                                              "obstacle in P1 at 3.00 m", "in pipe P1 at 2.95 m"}}),
            "[    39.3 s] error        kind=blockage reason=obstacle in P1 at 3.00 m where=in pipe "
            "P1 at 2.95 m");
  EXPECT_EQ(readable_line({1, JobEvent{"TurnInManhole", 2.8285, true}}),
            "[     1.0 s] job          job=TurnInManhole progress_m=2.83 ok=yes");
  EXPECT_EQ(readable_line({2, PlanEvent{.replan = true, .goals = {"a", "b"}, .steps = 4}}),
            "[     2.0 s] replan       reason= planning_ms=0.0 decision=follow-plan goals=[a, b] "
            "dropped=[] end= steps=4 cost_s=0.0");
}

}  // namespace
}  // namespace sewerplan::executor
