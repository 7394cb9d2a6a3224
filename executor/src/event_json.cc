// SPDX-License-Identifier: MIT
// The event log as JSON lines (event_json.h).
#include "sewerplan/executor/event_json.h"

#include <cmath>
#include <functional>
#include <limits>
#include <optional>

#include <nlohmann/json.hpp>

#include "sewerplan/core/json_fields.h"

#include "event_fields.h"

namespace sewerplan::executor {
namespace {

// Mission times beyond this (about 31,700 years) are no robot's: errors.
constexpr double kMaxTime_s = 1e12;

// Decision names of the first logs, before the Replanner's decisions had stable names.
std::optional<PlanResponse::Decision> parse_logged_decision(std::string_view name) {
  if (name == "follow") return PlanResponse::Decision::kFollowPlan;
  if (name == "call for recovery") return PlanResponse::Decision::kCallForRecovery;
  return parse_decision(name);
}

std::optional<RecoveryPhase> parse_phase(std::string_view name) {
  for (const RecoveryManoeuvre& m : kRecoveryManoeuvres) {
    if (m.logged == name) return m.phase;
  }
  return std::nullopt;
}

// The fields of one line's object, read through the one JSON reader (JsonFields): a field that is
// missing keeps its value (older logs lack newer fields); one of the wrong type, out of range or
// with a name not ours is an error at "file:line:$.field".
class FieldReader {
 public:
  explicit FieldReader(JsonFields& fields) : f_(fields) {}

  bool has(std::string_view key) const { return f_.has(key); }
  void error(std::string_view key, const std::string& message) { f_.error(key, message); }

  void get(std::string_view key, std::string& out) {
    if (auto v = f_.string(key, kOptional)) out = std::move(*v);
  }
  void get(std::string_view key, double& out) {
    if (auto v = f_.number(key, kOptional)) out = *v;
  }
  void get(std::string_view key, bool& out) {
    if (auto v = f_.boolean(key, kOptional)) out = *v;
  }
  void get(std::string_view key, std::size_t& out) {
    if (auto v = f_.count(key, kMaxCount, kOptional)) out = static_cast<std::size_t>(*v);
  }
  void get(std::string_view key, int& out) {
    if (auto v = f_.count(key, std::numeric_limits<int>::max(), kOptional)) {
      out = static_cast<int>(*v);
    }
  }
  void get(std::string_view key, std::vector<std::string>& out) {
    const std::optional<JsonArray> items = f_.array(key, kOptional);
    if (!items) return;
    out.clear();
    std::size_t i = 0;
    for (JsonElement item : *items) {
      if (auto name = string_element(item, indexed(f_.where(key), i++), f_.diagnostics())) {
        out.push_back(std::move(*name));
      }
    }
  }
  // A name of ours, read with `parse`.
  template <class Enum>
  void get(std::string_view key, Enum& out,
           const std::function<std::optional<Enum>(std::string_view)>& parse) {
    const std::optional<std::string> name = f_.string(key, kOptional);
    if (!name) return;
    if (std::optional<Enum> value = parse(*name)) {
      out = *value;
    } else {
      f_.error(key, "unknown " + std::string(key) + " '" + *name + "'");
    }
  }

 private:
  static constexpr JsonFields::Need kOptional = JsonFields::Need::kOptional;
  // Counts beyond this are no run's (and a double holds every whole number up to it exactly).
  static constexpr std::uint64_t kMaxCount = std::uint64_t{1} << 53;

  JsonFields& f_;
};

// The event of one object of a known type; empty for another type.
std::optional<Event> event_of(const std::string& type, FieldReader& r) {
  Event e;
  r.get("t_s", e.t_s);
  if (std::abs(e.t_s) > kMaxTime_s) {
    r.error("t_s", "out of range: a mission time within " + format_double(kMaxTime_s) + " s");
  }
  e.t_s = std::round(e.t_s * 1000) / 1000;  // as written: to the millisecond
  const std::optional<detail::EventType> kind = detail::parse_event_type(type);
  if (!kind) return std::nullopt;
  using detail::EventType;
  switch (*kind) {
    case EventType::kPlan:
    case EventType::kReplan: {
      PlanEvent p{.replan = *kind == EventType::kReplan};
      r.get("reason", p.reason);
      r.get("planning_ms", p.planning_ms);
      r.get<PlanResponse::Decision>("decision", p.decision, parse_logged_decision);
      r.get("goals", p.goals);
      r.get("dropped", p.dropped);
      r.get("end", p.end);
      r.get("steps", p.steps);
      r.get("cost_s", p.cost_s);
      r.get<PlanResponse::Rung>("rung", p.rung, parse_rung);
      r.get("strand_probability", p.strand_probability);
      e.what = std::move(p);
      break;
    }
    case EventType::kAction: {
      ActionEvent a;
      r.get("step", a.step);
      r.get("kind", a.kind);
      r.get("duration_s", a.duration_s);
      r.get("parameters", a.parameters);
      e.what = std::move(a);
      break;
    }
    case EventType::kJob: {
      JobEvent j;
      r.get("job", j.job);
      r.get("progress_m", j.progress_m);
      r.get("ok", j.ok);
      e.what = std::move(j);
      break;
    }
    case EventType::kError: {
      ErrorEvent x;
      r.get<hal::RobotErrorKind>("kind", x.kind, hal::parse_robot_error_kind);
      r.get("reason", x.reason);
      r.get("where", x.where);
      e.what = std::move(x);
      break;
    }
    case EventType::kRecovery: {
      RecoveryEvent x;
      r.get<RecoveryPhase>("phase", x.phase, parse_phase);
      r.get("ok", x.ok);
      e.what = x;
      break;
    }
    case EventType::kFailure: {
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
      break;
    }
    case EventType::kTaskDone: {
      TaskDoneEvent t;
      r.get("task", t.task);
      e.what = std::move(t);
      break;
    }
    case EventType::kTaskDropped: {
      TaskDroppedEvent t;
      r.get("task", t.task);
      r.get("reason", t.reason);
      e.what = std::move(t);
      break;
    }
    case EventType::kReserve: {
      ReserveEvent x;
      r.get("end", x.end);
      r.get("energy_wh", x.energy_wh);
      r.get("left_wh", x.left_wh);
      r.get("reserve_wh", x.reserve_wh);
      e.what = std::move(x);
      break;
    }
    case EventType::kArrival: {
      ArrivalEvent a;
      r.get("expected", a.expected);
      r.get("check", a.check);
      r.get("probability", a.probability);
      r.get("believed", a.believed);
      r.get("manhole", a.manhole);
      r.get("observed", a.observed);
      r.get("reason", a.reason);
      e.what = std::move(a);
      break;
    }
    case EventType::kHazard: {
      HazardEvent h;
      r.get("pipe", h.pipe);
      r.get("offset_m", h.offset_m);
      r.get("reason", h.reason);
      r.get<HazardEvent::Observed>("observed", h.observed, parse_hazard_observed);
      r.get("probability_before", h.probability_before);
      r.get("probability", h.probability);
      r.get("passes", h.passes);
      e.what = std::move(h);
      break;
    }
    case EventType::kBeacon: {
      BeaconEvent b;
      r.get("reason", b.reason);
      r.get<hal::BeaconState>("state", b.state, hal::parse_beacon_state);
      e.what = std::move(b);
      break;
    }
    case EventType::kMissionEnd: {
      MissionEndEvent m;
      r.get<MissionOutcome>("outcome", m.outcome, parse_mission_outcome);
      r.get("end", m.end);
      r.get("tasks_done", m.tasks_done);
      r.get("energy_wh", m.energy_wh);
      r.get("replans", m.replans);
      r.get<PlanResponse::Decision>("decision", m.decision, parse_logged_decision);
      r.get<BeaconCause>("beacon_cause", m.beacon_cause, parse_beacon_cause);
      r.get<hal::BeaconState>("beacon", m.beacon, hal::parse_beacon_state);
      e.what = std::move(m);
      break;
    }
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
  JsonLineParser parser;
  while (!text.empty()) {
    ++line_number;
    const std::size_t newline = text.find('\n');
    const std::string_view line = text.substr(0, newline);
    text = newline == std::string_view::npos ? std::string_view{} : text.substr(newline + 1);
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    const std::string where = file_name + ":" + std::to_string(line_number);
    const std::optional<JsonElement> j = parser.parse(line);
    if (!j || !j->is_object()) {
      diagnostics.error(where, "not a JSON object");
      continue;
    }
    const std::size_t errors_before = diagnostics.error_count();
    JsonFields fields(*j, "$", where, diagnostics);
    if (!fields.has("type")) {
      diagnostics.error(where, "no \"type\"");
      continue;
    }
    const std::optional<std::string> type = fields.string("type");
    if (!type) continue;
    FieldReader reader(fields);
    std::optional<Event> event = event_of(*type, reader);
    if (diagnostics.error_count() > errors_before) continue;
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
