// SPDX-License-Identifier: MIT
// The JSON documents that the `sewerplan` command prints with --json and that the operator
// station's server (station_server.h) answers with: one schema, written in one place (docs/cli.md
// has every schema, docs/operator-station.md which endpoint answers with which).
//
// A failure has one shape everywhere:
//
//   {"error": {"code": "invalid-map", "exit_code": 1, "message": "...", "file": "map.json",
//              "path": "$.pipes[1].to", "diagnostics": [{"severity", "where", "message"}]}}
//
// "code" is the library's ErrorCode name (core/result.h) or "usage" for a usage error; "exit_code"
// is the CLI's exit code for it (ExitCode), which the server keeps so a client reads one shape.
//
//   Json j = plan_json(*outcome, report, map, mission);
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/search/planner.h"

namespace sewerplan::server {

using Json = nlohmann::ordered_json;

// The CLI's exit codes, part of its interface (docs/cli.md), and the "exit_code" of every error.
enum ExitCode : int {
  kExitOk = 0,
  kExitInvalidInput = 1,
  kExitUsage = 2,
  kExitIo = 3,
  kExitNoPlan = 4,
  kExitSearchLimit = 5,
  kExitCampaignNotClean = 6,
};

// The exit code of a library error (kIo -> 3, kNoPlan -> 4, a bad file -> 1, ...).
int exit_code_for(const Error& error);

// {"code", "exit_code", "message", "file"/"line"/"path", "diagnostics"}: the object under "error".
Json error_object(const Error& error, const Diagnostics& diagnostics, int exit_code);

// The diagnostics of one severity as [{"where", "message"}] (validate --json's lists).
Json diagnostics_json(const Diagnostics& diagnostics, Severity severity);

// A plan and its validation as the plan JSON (domain/plan_json.h, "sewerplan-plan" version 1),
// with an invalid plan's reason in the shared error shape.
Json plan_verdict_json(const domain::Plan& plan, const domain::ValidationReport& report,
                       const SewerMap& map, const Mission& mission);

// [{"task", "reason"}]: the tasks a plan leaves out, by name.
Json dropped_json(const std::vector<domain::DroppedTask>& dropped, const Mission& mission);

// `plan --json`: the plan JSON with the decision, "optimal", "algorithm", "dropped" and the
// planner's "statistics".
Json plan_json(const search::PlanOutcome& outcome, const domain::ValidationReport& report,
               const SewerMap& map, const Mission& mission);

// What `plan --json` adds to a failure: what the Replanner, which always selects goals and heads
// for a reachable exit, would answer at the start (its decision, the tasks it would drop and
// why, within a few seconds), and how long the failed search ran.
Json plan_failure_json(const SewerMap& map, const Mission& mission, search::PlannerOptions options,
                       double search_time_s);

// `simulate --json`: the mission report.
Json report_json(const executor::MissionReport& report);

}  // namespace sewerplan::server
