// SPDX-License-Identifier: MIT
#include "sewerplan/server/documents.h"

#include <algorithm>
#include <cctype>
#include <sstream>
#include <string>

#include "sewerplan/domain/plan_json.h"
#include "sewerplan/executor/replanner.h"

namespace sewerplan::server {
namespace {

// "FILE:LINE", "FILE:$.json.path" or "FILE:/xml/path" into file and line or path.
void add_where(Json& j, const std::string& where) {
  const auto colon = where.rfind(':');
  if (colon == std::string::npos || colon == 0) return;
  const std::string file = where.substr(0, colon);
  const std::string rest = where.substr(colon + 1);
  if (rest.empty()) return;
  j["file"] = file;
  const bool digits =
      std::all_of(rest.begin(), rest.end(), [](unsigned char ch) { return std::isdigit(ch); });
  if (digits && rest.size() < 10) {
    j["line"] = std::stoi(rest);
  } else {
    j["path"] = rest;
  }
}

std::string_view severity_name(Severity s) {
  switch (s) {
    case Severity::kError:
      return "error";
    case Severity::kWarning:
      return "warning";
  }
  return "error";
}

}  // namespace

int exit_code_for(const Error& error) {
  switch (error.code) {
    case ErrorCode::kIo:
    case ErrorCode::kCanTimeout:
    case ErrorCode::kBusError:
      return kExitIo;
    case ErrorCode::kInvalidArgument:
      return kExitUsage;
    case ErrorCode::kNoPlan:
      return kExitNoPlan;
    case ErrorCode::kSearchLimit:
    case ErrorCode::kCancelled:
      return kExitSearchLimit;
    case ErrorCode::kParse:
    case ErrorCode::kInvalidMap:
    case ErrorCode::kInvalidMission:
    case ErrorCode::kInvalidProfile:
    case ErrorCode::kUnsupportedFormat:
      return kExitInvalidInput;
  }
  return kExitInvalidInput;
}

Json error_object(const Error& error, const Diagnostics& diagnostics, int exit_code) {
  Json j = {{"code", exit_code == kExitUsage && error.code == ErrorCode::kInvalidArgument
                         ? std::string("usage")
                         : std::string(to_string(error.code))},
            {"exit_code", exit_code},
            {"message", error.message}};
  Json list = Json::array();
  bool located = false;
  for (const Diagnostic& d : diagnostics.all()) {
    if (!located && d.severity == Severity::kError) {
      add_where(j, d.where);
      located = true;
    }
    list.push_back(
        {{"severity", severity_name(d.severity)}, {"where", d.where}, {"message", d.message}});
  }
  j["diagnostics"] = std::move(list);
  return j;
}

Json diagnostics_json(const Diagnostics& diagnostics, Severity severity) {
  Json list = Json::array();
  for (const Diagnostic& d : diagnostics.all()) {
    if (d.severity == severity) list.push_back({{"where", d.where}, {"message", d.message}});
  }
  return list;
}

Json plan_verdict_json(const domain::Plan& plan, const domain::ValidationReport& report,
                       const SewerMap& map, const Mission& mission) {
  std::ostringstream text;
  domain::write_plan_json(plan, report, map, mission, text);
  Json j = Json::parse(text.str());
  if (!report.valid) {
    j["error"] = {{"code", "invalid-plan"},
                  {"exit_code", kExitInvalidInput},
                  {"message", report.error},
                  {"diagnostics", Json::array()}};
  }
  return j;
}

Json dropped_json(const std::vector<domain::DroppedTask>& dropped, const Mission& m) {
  Json list = Json::array();
  for (const auto& d : dropped)
    list.push_back({{"task", m.task(d.task).name}, {"reason", d.reason}});
  return list;
}

Json statistics_json(const search::PlanOutcome& o) {
  const domain::CompileStatistics& c = o.compile;
  const search::SearchStatistics& s = o.search;
  return {{"compile",
           {{"time_s", c.time_s},
            {"keys", c.keys},
            {"graph_nodes", c.graph_nodes},
            {"settled_nodes", c.settled_nodes},
            {"route_searches", c.route_searches},
            {"reused_searches", c.reused_searches},
            {"index_rows", c.index_rows},
            {"guided_searches", c.guided_searches},
            {"actions", c.actions}}},
          {"search",
           {{"time_s", s.time_s},
            {"expanded", s.expanded},
            {"generated", s.generated},
            {"evaluated", s.evaluated},
            {"reopened", s.reopened},
            {"dead_ends", s.dead_ends},
            {"stored", s.stored},
            {"peak_memory_bytes", s.peak_memory_bytes}}},
          {"improvements", o.improvements}};
}

Json plan_json(const search::PlanOutcome& outcome, const domain::ValidationReport& report,
               const SewerMap& map, const Mission& m) {
  Json j = plan_verdict_json(outcome.plan, report, map, m);
  j["decision"] =
      executor::to_string(outcome.dropped.empty() ? executor::PlanResponse::Decision::kFollowPlan
                                                  : executor::PlanResponse::Decision::kDegraded);
  j["optimal"] = outcome.optimal;
  j["algorithm"] = outcome.algorithm;
  j["dropped"] = dropped_json(outcome.dropped, m);
  j["statistics"] = statistics_json(outcome);
  if (j.contains("risk")) {
    // Risk-aware planning: beside the route's unobstructed probability (plan_json.h), the expected
    // cost of stops the planner chose the plan with, and why it took the risk-blind plan, if so.
    j["risk"]["expected_cost_s"] = outcome.risk_cost_s;
    if (!outcome.risk_note.empty()) j["risk"]["note"] = outcome.risk_note;
    // The plan's computed stranding risk (docs/planning.md, issue 34): the hazards it passes
    // without the battery kept to back out and reach an exit another way.
    j["risk"]["strand_probability"] = outcome.strand_probability;
    Json uninsured = Json::array();
    for (std::size_t h : outcome.uninsured) {
      const Hazard& hazard = m.hazards[h];
      uninsured.push_back({{"pipe", map.pipe(hazard.pipe).name},
                           {"offset_m", hazard.offset_m},
                           {"probability", hazard.probability},
                           {"reason", hazard.reason}});
    }
    j["risk"]["uninsured"] = std::move(uninsured);
    if (!outcome.strand_note.empty()) j["risk"]["strand_note"] = outcome.strand_note;
  }
  return j;
}

// What `plan --json` adds to a failure: what the Replanner, which always selects goals and heads
// for a reachable exit, would answer at the start (its decision, the tasks it would drop and why,
// within kFallbackLimit_s), and how long the failed search ran.
constexpr double kFallbackLimit_s = 5;
Json plan_failure_json(const SewerMap& map, const Mission& m, search::PlannerOptions options,
                       double search_time_s) {
  options.time_limit_s = options.time_limit_s > 0 ? std::min(options.time_limit_s, kFallbackLimit_s)
                                                  : kFallbackLimit_s;
  options.improvement_expansions = 0;
  executor::Replanner replanner(map, m, {.planner = options});
  const executor::PlanResponse r = replanner.plan();
  Json goals = Json::array();
  for (TaskId t : r.goals) goals.push_back(m.task(t).name);
  return {{"decision", executor::to_string(r.decision)},
          {"dropped", dropped_json(r.newly_dropped, m)},
          {"fallback",
           {{"tasks", goals},
            {"end", r.end},
            {"cost_s", r.cost_s},
            {"energy_wh", r.energy_wh},
            {"planning_time_s", r.planning_time_s}}},
          {"statistics", {{"time_s", search_time_s}}}};
}

Json report_json(const executor::MissionReport& r) {
  Json dropped = Json::array();
  for (const auto& [task, reason] : r.dropped)
    dropped.push_back({{"task", task}, {"reason", reason}});
  return {{"outcome", executor::to_string(r.outcome)},
          {"decision", executor::to_string(r.decision)},
          {"beacon_cause", executor::to_string(r.beacon_cause)},
          {"beacon", hal::to_string(r.beacon)},
          {"end", r.end},
          {"tasks_done", r.tasks_done},
          {"dropped", dropped},
          {"time_s", r.time_s},
          {"energy_wh", r.energy_wh},
          {"replans", r.replans},
          {"planning_times_s", r.planning_times_s},
          {"jobs", r.jobs},
          {"recoveries", r.recoveries},
          {"battery_reserve_kept", r.battery_reserve_kept},
          {"log_errors", r.log_errors},
          {"exit_on_reserve", r.exit_on_reserve}};
}

}  // namespace sewerplan::server
