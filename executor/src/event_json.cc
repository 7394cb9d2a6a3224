// SPDX-License-Identifier: MIT
// The event log as JSON lines (event_json.h).
#include "sewerplan/executor/event_json.h"

#include <cmath>
#include <functional>
#include <limits>
#include <optional>

#include <nlohmann/json.hpp>

#include "event_fields.h"

namespace sewerplan::executor {
namespace {

using Json = nlohmann::json;

// Mission times beyond this (about 31,700 years) are no robot's: errors.
constexpr double kMaxTime_s = 1e12;

// Decision names of the first logs, before the Replanner's decisions had stable names.
std::optional<PlanResponse::Decision> parse_logged_decision(std::string_view name) {
  if (name == "follow") return PlanResponse::Decision::kFollowPlan;
  if (name == "call for recovery") return PlanResponse::Decision::kCallForRecovery;
  return parse_decision(name);
}

std::optional<hal::RobotErrorKind> parse_error_kind(std::string_view name) {
  for (auto k : {hal::RobotErrorKind::kBlockage, hal::RobotErrorKind::kDanger,
                 hal::RobotErrorKind::kMalfunction}) {
    if (hal::to_string(k) == name) return k;
  }
  return std::nullopt;
}

std::optional<Failure::Kind> parse_failure_kind(std::string_view name) {
  for (auto k : {Failure::Kind::kBlockage, Failure::Kind::kDangerInPipe,
                 Failure::Kind::kDangerousPassage, Failure::Kind::kStuck}) {
    if (to_string(k) == name) return k;
  }
  return std::nullopt;
}

std::optional<RecoveryPhase> parse_phase(std::string_view name) {
  for (const RecoveryStage& stage : kRecoveryTable) {
    if (stage.logged == name) return stage.phase;
  }
  return std::nullopt;
}

// Reads the fields of one line's object; a field that is missing keeps its value, one of the wrong
// type or with a name not ours sets `error` (the first only).
class FieldReader {
 public:
  explicit FieldReader(const Json& object) : j_(object) {}

  bool has(const char* key) const { return j_.contains(key); }
  const std::optional<std::string>& error() const { return error_; }
  void fail(std::string what) {
    if (!error_) error_ = std::move(what);
  }

  void get(const char* key, std::string& out) {
    if (const Json* v = field(key, &Json::is_string, "a string")) out = v->get<std::string>();
  }
  void get(const char* key, double& out) {
    const Json* v = field(key, &Json::is_number, "a number");
    if (v == nullptr) return;
    const auto d = v->get<double>();
    if (!std::isfinite(d)) {
      fail(std::string("\"") + key + "\" is out of range");
      return;
    }
    out = d;
  }
  void get(const char* key, bool& out) {
    if (const Json* v = field(key, &Json::is_boolean, "true or false")) out = v->get<bool>();
  }
  void get(const char* key, std::size_t& out) {
    const Json* v = field(key, &Json::is_number_unsigned, "a count");
    if (v == nullptr) return;
    const auto n = v->get<std::uint64_t>();
    if (n > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
      fail(std::string("\"") + key + "\" is out of range");
      return;
    }
    out = static_cast<std::size_t>(n);
  }
  void get(const char* key, int& out) {
    const Json* v = field(key, &Json::is_number_integer, "a whole number");
    if (v == nullptr) return;
    const auto i = v->get<std::int64_t>();
    if (i < 0 || i > std::numeric_limits<int>::max()) {
      fail(std::string("\"") + key + "\" is out of range");
      return;
    }
    out = static_cast<int>(i);
  }
  void get(const char* key, std::vector<std::string>& out) {
    const Json* v = field(key, &Json::is_array, "a list of strings");
    if (v == nullptr) return;
    out.clear();
    for (const Json& item : *v) {
      if (!item.is_string()) {
        fail(std::string("\"") + key + "\" is not a list of strings");
        return;
      }
      out.push_back(item.get<std::string>());
    }
  }
  // A name of ours, read with `parse`.
  template <class Enum>
  void get(const char* key, Enum& out,
           const std::function<std::optional<Enum>(std::string_view)>& parse) {
    std::string name;
    if (!has(key)) return;
    get(key, name);
    if (error_) return;
    if (std::optional<Enum> value = parse(name)) {
      out = *value;
    } else {
      fail(std::string("\"") + key + "\": unknown '" + name + "'");
    }
  }

 private:
  const Json* field(const char* key, bool (Json::*is)() const noexcept, const char* what) {
    const auto it = j_.find(key);
    if (it == j_.end()) return nullptr;
    if (!((*it).*is)()) {
      fail(std::string("\"") + key + "\" is not " + what);
      return nullptr;
    }
    return &*it;
  }

  const Json& j_;
  std::optional<std::string> error_;
};

// The event of one object of a known type; empty for another type.
std::optional<Event> event_of(const std::string& type, FieldReader& r) {
  Event e;
  r.get("t_s", e.t_s);
  if (std::abs(e.t_s) > kMaxTime_s) r.fail("\"t_s\" is out of range");
  e.t_s = std::round(e.t_s * 1000) / 1000;  // as written: to the millisecond
  if (type == "plan" || type == "replan") {
    PlanEvent p{.replan = type == "replan"};
    r.get("reason", p.reason);
    r.get("planning_ms", p.planning_ms);
    r.get<PlanResponse::Decision>("decision", p.decision, parse_logged_decision);
    r.get("goals", p.goals);
    r.get("dropped", p.dropped);
    r.get("end", p.end);
    r.get("steps", p.steps);
    r.get("cost_s", p.cost_s);
    e.what = std::move(p);
  } else if (type == "action") {
    ActionEvent a;
    r.get("step", a.step);
    r.get("kind", a.kind);
    r.get("duration_s", a.duration_s);
    r.get("parameters", a.parameters);
    e.what = std::move(a);
  } else if (type == "job") {
    JobEvent j;
    r.get("job", j.job);
    r.get("progress_m", j.progress_m);
    r.get("ok", j.ok);
    e.what = std::move(j);
  } else if (type == "error") {
    ErrorEvent x;
    r.get<hal::RobotErrorKind>("kind", x.kind, parse_error_kind);
    r.get("reason", x.reason);
    r.get("where", x.where);
    e.what = std::move(x);
  } else if (type == "recovery") {
    RecoveryEvent x;
    r.get<RecoveryPhase>("phase", x.phase, parse_phase);
    r.get("ok", x.ok);
    e.what = x;
  } else if (type == "failure") {
    FailureEvent f;
    r.get<Failure::Kind>("kind", f.kind, parse_failure_kind);
    if (r.has("pipe")) {
      FailureEvent::InPipe in;
      r.get("pipe", in.pipe);
      r.get("offset_m", in.offset_m);
      f.where = std::move(in);
    } else if (r.has("manhole")) {
      FailureEvent::Passage p;
      r.get("manhole", p.manhole);
      r.get("from_slot", p.from_slot);
      r.get("to_slot", p.to_slot);
      f.where = std::move(p);
    }
    r.get("detail", f.detail);
    e.what = std::move(f);
  } else if (type == "task_done") {
    TaskDoneEvent t;
    r.get("task", t.task);
    e.what = std::move(t);
  } else if (type == "task_dropped") {
    TaskDroppedEvent t;
    r.get("task", t.task);
    r.get("reason", t.reason);
    e.what = std::move(t);
  } else if (type == "beacon") {
    BeaconEvent b;
    r.get("reason", b.reason);
    e.what = std::move(b);
  } else if (type == "mission_end") {
    MissionEndEvent m;
    r.get<MissionOutcome>("outcome", m.outcome, parse_mission_outcome);
    r.get("end", m.end);
    r.get("tasks_done", m.tasks_done);
    r.get("energy_wh", m.energy_wh);
    r.get("replans", m.replans);
    r.get<PlanResponse::Decision>("decision", m.decision, parse_logged_decision);
    r.get<BeaconCause>("beacon_cause", m.beacon_cause, parse_beacon_cause);
    e.what = std::move(m);
  } else {
    return std::nullopt;
  }
  return e;
}

}  // namespace

std::string to_json_line(const Event& event) {
  nlohmann::ordered_json j;
  j["t_s"] = std::round(event.t_s * 1000) / 1000;
  j["type"] = type_name(event);
  for (const auto& [key, value] : detail::fields_of(event)) {
    std::visit([&, &k = key](const auto& v) { j[std::string(k)] = v; }, value);
  }
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

EventObserver json_lines_writer(std::ostream& out) {
  return [&out](const Event& event) {
    out << to_json_line(event) << '\n';
    out.flush();  // a watcher (tail -f, a test) sees each event as it happens
  };
}

std::vector<LoggedEvent> read_event_log_lines(std::string_view text, const std::string& file_name,
                                              Diagnostics& diagnostics) {
  std::vector<LoggedEvent> events;
  std::size_t line_number = 0;
  while (!text.empty()) {
    ++line_number;
    const std::size_t newline = text.find('\n');
    const std::string_view line = text.substr(0, newline);
    text = newline == std::string_view::npos ? std::string_view{} : text.substr(newline + 1);
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    const std::string where = file_name + ":" + std::to_string(line_number);
    const Json j = Json::parse(line, nullptr, false);
    if (j.is_discarded() || !j.is_object()) {
      diagnostics.error(where, "not a JSON object");
      continue;
    }
    const auto type = j.find("type");
    if (type == j.end() || !type->is_string()) {
      diagnostics.error(where, "no \"type\"");
      continue;
    }
    FieldReader reader(j);
    std::optional<Event> event = event_of(type->get<std::string>(), reader);
    if (reader.error()) {
      diagnostics.error(where, type->get<std::string>() + ": " + *reader.error());
      continue;
    }
    if (event) events.push_back({std::move(*event), line_number});
  }
  return events;
}

Result<std::vector<Event>> read_event_log(std::string_view text, const std::string& file_name,
                                          Diagnostics& diagnostics) {
  const std::size_t errors_before = diagnostics.error_count();
  std::vector<LoggedEvent> lines = read_event_log_lines(text, file_name, diagnostics);
  if (diagnostics.error_count() > errors_before) {
    return Error{ErrorCode::kParse, file_name + ": not an event log"};
  }
  std::vector<Event> events;
  events.reserve(lines.size());
  for (LoggedEvent& e : lines) events.push_back(std::move(e.event));
  return events;
}

}  // namespace sewerplan::executor
