// SPDX-License-Identifier: MIT
// Candump logs: bus traffic recorded and replayed in the log format of can-utils (candump -l,
// canplayer, log2asc), so that users' own tools read what sewerplan recorded and the other way
// round.
//
// One frame a line: "(1700000000.123456) can0 123#DEADBEEF", with 8 hex digits for an extended
// identifier and "#R" for a remote request (can_frame.h). RecordingCanBus wraps any CanBus and
// writes every frame sent and received. ReplayCanBus plays a log back to a controller: it serves
// the node's frames (job_protocol.h tells them apart by identifier) in order, and checks that the
// controller sends what the log says it sent (its heartbeats aside, which follow the wall clock).
// A CanRobot and an Executor run on a replay give the event log of the recorded run.
//
//   Result<LogFile> out = LogFile::open("run.log");
//   RecordingCanBus recording(*bus, *out, clock, "can0");
//   ...
//   Result<std::vector<CandumpRecord>> log = read_candump_file("run.log");
//   ReplayCanBus replay(*log);
//
// Thread safety: RecordingCanBus and ReplayCanBus are not thread-safe: one thread uses each.
#pragma once

#include <cstddef>
#include <filesystem>
#include <istream>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/output_file.h"
#include "sewerplan/core/result.h"
#include "sewerplan/hal/can/can_bus.h"
#include "sewerplan/hal/can/can_frame.h"

namespace sewerplan::hal {

struct CandumpRecord {
  double time_s = 0;  // seconds since the epoch, microseconds in the file
  std::string interface = "can0";
  CanFrame frame;
  std::size_t line = 0;  // in the file it was read from; 0 when not read
  friend bool operator==(const CandumpRecord&, const CandumpRecord&) = default;
};

// "(1700000000.123456) can0 123#DEADBEEF", without a line end.
std::string candump_line(const CandumpRecord& record);
Result<CandumpRecord> parse_candump_line(std::string_view line);
// Every record of a log; empty lines are skipped. Errors name the file and the line:
// "run.log:12: expected ID#DATA, found no '#' in '123DEAD'".
Result<std::vector<CandumpRecord>> read_candump(std::istream& in, const std::string& file_name);
Result<std::vector<CandumpRecord>> read_candump_file(const std::filesystem::path& path);

// Writes each frame that passes through `inner`, stamped with `clock` (seconds since the epoch for
// a real log; any clock for tests).
class RecordingCanBus final : public CanBus {
 public:
  // All must outlive the recorder.
  RecordingCanBus(CanBus& inner, std::ostream& out, const Clock& clock,
                  std::string interface = "can0");
  // Appends each frame's line to `log` as it passes (one write a frame, so a crash keeps every
  // frame before it); a failed write does not stop the bus: `log` counts it (output_file.h).
  RecordingCanBus(CanBus& inner, LogFile& log, const Clock& clock, std::string interface = "can0");
  Result<void> send(const CanFrame& frame) override;
  Result<std::optional<CanFrame>> receive(double timeout_s) override;
  Result<void> recover() override { return inner_.recover(); }
  std::string name() const override { return inner_.name(); }

 private:
  void write(const CanFrame& frame);
  CanBus& inner_;
  std::ostream* out_ = nullptr;  // one of the two
  LogFile* log_ = nullptr;
  const Clock& clock_;
  std::string interface_;
};

// Plays a recorded run back to a controller. receive() never waits: at the end of the log it
// answers "nothing arrived" at once, so a controller's timeouts pass without delay.
class ReplayCanBus final : public CanBus {
 public:
  explicit ReplayCanBus(std::vector<CandumpRecord> records, std::string file_name = "replay");
  // kBusError when the controller sends a frame the log does not have next (heartbeats aside).
  Result<void> send(const CanFrame& frame) override;
  Result<std::optional<CanFrame>> receive(double timeout_s) override;
  std::string name() const override { return "replay:" + file_name_; }
  // The controller's frames of the log it has not sent.
  std::size_t unsent() const;

 private:
  std::vector<CandumpRecord> from_node_;
  std::vector<CandumpRecord> from_controller_;
  std::size_t next_in_ = 0;
  std::size_t next_out_ = 0;
  std::string file_name_;
};

}  // namespace sewerplan::hal
