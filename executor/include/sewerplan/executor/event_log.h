// SPDX-License-Identifier: MIT
// EventLog: what happened during a mission, as JSON lines and as a readable live log.
//
// Every event has the mission time `t_s` (the robot's clock) and a `type`: "plan" and "replan"
// (reason, planning time, goals, dropped tasks, end), "action", "job", "error" (blockage, danger,
// malfunction, with the robot's reason), "recovery" (the phase tried and its result),
// "failure" (what the Replanner is told: kind, and the pipe and offset_m or the manhole and paper
// slot numbers), "task_done", "task_dropped" (with the reason), "beacon", "mission_end". Fields are
// plain values, so a log can be replayed and compared.
//
//   std::ofstream file("events.jsonl");
//   EventLog log(&file, &std::cout);
//   log.add(12.5, "error", {{"kind", "blockage"}, {"reason", "obstacle in P5 at 4.00 m"}});
//
// Thread safety: An EventLog is not thread-safe: the executor's thread writes it.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace sewerplan::executor {

using EventValue = std::variant<std::string, double, std::int64_t, bool, std::vector<std::string>>;

struct Event {
  double t_s = 0;
  std::string type;
  std::vector<std::pair<std::string, EventValue>> fields;
  friend bool operator==(const Event&, const Event&) = default;
};

class EventLog {
 public:
  // Either stream may be null. `readable` gets one line per event for people watching.
  explicit EventLog(std::ostream* json_lines = nullptr, std::ostream* readable = nullptr);

  void add(double t_s, std::string type, std::vector<std::pair<std::string, EventValue>> fields);
  const std::vector<Event>& events() const { return events_; }
  std::size_t count(std::string_view type) const;

  // One event as a JSON object on one line.
  static std::string to_json(const Event& event);

 private:
  std::ostream* json_lines_;
  std::ostream* readable_;
  std::vector<Event> events_;
};

}  // namespace sewerplan::executor
