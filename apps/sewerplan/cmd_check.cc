// SPDX-License-Identifier: MIT
// sewerplan check --map MAP --mission MISSION PLAN [--select-goals] [--json]
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/domain/plan_json.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/executor/replanner.h"

#include "command.h"
#include "json_output.h"
#include "map_input.h"
#include "motion_options.h"

namespace sewerplan::cli {
namespace {

struct CheckOptions {
  std::string map;
  std::string gis_fields;  // --gis-fields
  std::string mission;
  std::string plan;
  bool json = false;
  bool select_goals = false;
  MotionOptions motion;
};

// A failure to load an input: the error object, and for programs that read only the plan JSON's
// fields, "valid": false too.
int failed(const Error& error, const Diagnostics& diagnostics, bool json, Context& c) {
  return fail(c, json, error, diagnostics,
              {{"format", domain::kPlanJsonFormat},
               {"version", domain::kPlanJsonVersion},
               {"valid", false}});
}

int run(const CheckOptions& o, Context& c) {
  Diagnostics diagnostics;
  Result<SewerMap> map = read_input_map({o.map, o.gis_fields}, diagnostics);
  if (!map.has_value()) return failed(map.error(), diagnostics, o.json, c);
  Result<Mission> mission = read_mission(o.mission, *map, diagnostics);
  if (!mission.has_value()) return failed(mission.error(), diagnostics, o.json, c);
  if (auto motion = attach_motion_table(o.motion, o.map, *map, *mission, c.err);
      !motion.has_value()) {
    return failed(motion.error(), {}, o.json, c);
  }
  Result<std::string> text = read_text_file(o.plan);
  if (!text.has_value()) return failed(text.error(), diagnostics, o.json, c);
  Diagnostics plan_diagnostics;
  Result<domain::Plan> plan = domain::parse_plan(*text, o.plan, *map, *mission, plan_diagnostics);
  if (!plan.has_value()) return failed(plan.error(), plan_diagnostics, o.json, c);
  // With --select-goals, as `plan --select-goals` plans: the tasks the plan does not do are left
  // out, and it must still end the mission (at its end point, or at an exit when that was left
  // out too).
  domain::MissionProgress start = domain::initial_progress(*mission, *map);
  std::vector<std::string> left_out;
  if (o.select_goals) {
    domain::PlanReplay probe(*map, *mission, start);
    for (const domain::PlanStep& step : plan->steps) {
      if (!probe.apply(step).has_value()) break;  // validate_plan says why
    }
    for (TaskId t : mission->task_ids()) {
      if (start.done[t.index()] || probe.done(t)) continue;
      start.done[t.index()] = true;
      left_out.push_back(mission->task(t).name);
    }
  }
  const domain::ValidationReport report = domain::validate_plan(*plan, *map, *mission, start);
  if (!o.json) {
    for (const std::string& task : left_out) c.err << "left out: task '" << task << "'\n";
  }
  if (o.json) {
    Json j = plan_verdict_json(*plan, report, *map, *mission);
    // A valid plan, as the Replanner would call it: it does everything asked (follow-plan), or
    // less (degraded: tasks left out). An invalid one has the error instead.
    if (report.valid) {
      j["decision"] =
          executor::to_string(left_out.empty() ? executor::PlanResponse::Decision::kFollowPlan
                                               : executor::PlanResponse::Decision::kDegraded);
    }
    j["left_out"] = left_out;
    print_json(c.out, j);
  } else {
    c.out << report << '\n';
  }
  return report.valid ? kExitOk : kExitInvalidInput;
}

}  // namespace

void add_check_command(CLI::App& app, Context& context) {
  // Shared with the callback, which CLI11 keeps after this function returns.
  auto options = std::make_shared<CheckOptions>();
  CLI::App* cmd = app.add_subcommand(
      "check",
      "Validate a plan (the paper's text, or FF's or Fast Downward's output) on a map and mission");
  cmd->add_option("--map", options->map, "Map file (any format of docs/formats/)")->required();
  add_gis_fields_option(*cmd, options->gis_fields);
  cmd->add_option("--mission", options->mission, "Mission file (.json)")->required();
  cmd->add_option("plan", options->plan, "Plan file, one action a line")->required();
  cmd->add_flag("--json", options->json, "Print the plan, its costs and the verdict as JSON");
  cmd->add_flag("--select-goals", options->select_goals,
                "Tasks the plan does not do count as left out (as plan --select-goals plans)");
  add_motion_options(*cmd, options->motion);
  cmd->callback([options, &context] { context.exit_code = run(*options, context); });
}

}  // namespace sewerplan::cli
