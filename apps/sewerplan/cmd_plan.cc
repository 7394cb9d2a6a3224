// SPDX-License-Identifier: MIT
// sewerplan plan --map MAP --mission MISSION [--algorithm ...] [--json] [-o PLAN]
#include <iomanip>
#include <ostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/domain/plan_json.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/route_risk.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/search/planner.h"

#include "command.h"
#include "condition_options.h"
#include "motion_options.h"

namespace sewerplan::cli {
namespace {

struct PlanOptions {
  std::string map;
  std::string mission;
  std::string algorithm = "auto";
  std::string heuristic;
  double weight = 2.0;
  double time_limit_s = 60;
  std::uint64_t improvement_expansions = 10'000;
  bool select_goals = false;
  std::string out;
  bool json = false;
  bool quiet = false;
  MotionOptions motion;
  std::string condition;
  RiskOptions risk;
};

void print_summary(const search::PlanOutcome& o, const domain::ValidationReport& report,
                   std::ostream& err) {
  err << std::fixed << std::setprecision(1) << "plan: " << o.plan.steps.size() << " steps, "
      << report.total_cost_s << " s, " << std::setprecision(2) << report.energy_wh << " Wh"
      << (o.optimal ? " (optimal)" : "") << "; " << o.algorithm << "; compile "
      << std::setprecision(3) << o.compile.time_s * 1e3 << " ms (" << o.compile.keys
      << " keys), search " << o.search.time_s * 1e3 << " ms (" << o.search.expanded
      << " expanded)\n";
}

// Risk-aware planning: the possible blockages the route passes, and the chance of none.
void print_route_risk(const search::PlanOutcome& o, const SewerMap& map, const Mission& m,
                      std::ostream& err) {
  const domain::RouteRisk risk =
      domain::route_risk(o.plan, map, m, domain::initial_progress(m, map));
  err << std::fixed << std::setprecision(2) << "risk: the route passes " << risk.passed.size()
      << " possible blockages; unobstructed run " << risk.unobstructed << "; expected cost of "
      << "stops " << std::setprecision(1) << o.risk_cost_s << " s";
  if (!o.risk_note.empty()) err << " (" << o.risk_note << ")";
  err << '\n';
  for (const domain::HazardPassed& h : risk.passed) {
    const Hazard& hazard = m.hazards[h.hazard];
    err << "  step " << h.step + 1 << ": pipe " << map.pipe(hazard.pipe).name << " at "
        << std::setprecision(2) << hazard.offset_m << " m, " << hazard.reason << ", p "
        << hazard.probability << '\n';
  }
}

int run(const PlanOptions& o, Context& c) {
  search::PlannerOptions options;
  auto algorithm = search::algorithm_from_string(o.algorithm);
  if (!algorithm) {
    c.err << "--algorithm: unknown '" << o.algorithm
          << "' (auto, ehc, gbfs, wastar, astar, exact)\n";
    return kExitUsage;
  }
  options.algorithm = *algorithm;
  if (!o.heuristic.empty()) {
    options.heuristic = search::heuristic_from_string(o.heuristic);
    if (!options.heuristic) {
      c.err << "--heuristic: unknown '" << o.heuristic << "' (ff, add, max, blind)\n";
      return kExitUsage;
    }
  }
  options.weight = o.weight;
  options.time_limit_s = o.time_limit_s;
  options.improvement_expansions = o.improvement_expansions;
  options.select_goals = o.select_goals;
  Diagnostics diagnostics;
  Result<SewerMap> map = read_map_with_condition(o.map, o.condition, diagnostics);
  std::optional<Result<Mission>> mission;
  if (map.has_value()) mission = read_mission(o.mission, *map, diagnostics);
  std::optional<Error> risk_error;
  if (mission && mission->has_value()) {
    if (Result<void> r = apply_risk(o.risk, *map, **mission, diagnostics, c.err); !r.has_value()) {
      risk_error = r.error();
    }
  }
  options.risk = o.risk.costs();
  print_diagnostics(diagnostics, c.err);
  const Error* load_error = !map.has_value()        ? &map.error()
                            : !mission->has_value() ? &mission->error()
                            : risk_error            ? &*risk_error
                                                    : nullptr;
  if (load_error != nullptr) {
    if (diagnostics.error_count() == 0) c.err << load_error->message << '\n';
    return exit_code_for(*load_error);
  }
  if (int code = attach_motion(o.motion, o.map, *map, **mission, c.err); code != kExitOk) {
    return code;
  }
  const Mission& m = **mission;
  domain::MissionProgress start = domain::initial_progress(m, *map);
  Result<search::PlanOutcome> outcome = search::plan_mission(*map, m, start, options);
  if (!outcome.has_value()) {
    c.err << outcome.error().message << '\n';
    return exit_code_for(outcome.error());
  }
  // Tasks left out by goal selection are not required of the plan.
  for (const auto& d : outcome->dropped) start.done[d.task.index()] = true;
  const domain::ValidationReport report = domain::validate_plan(outcome->plan, *map, m, start);
  if (!report.valid) {  // a planner bug: say so rather than hand out a wrong plan
    c.err << "internal error: the plan found does not validate: " << report << '\n';
    return kExitNoPlan;
  }
  const std::string text = domain::format_plan(outcome->plan, *map, m);
  if (o.json) {
    domain::write_plan_json(outcome->plan, report, *map, m, c.out);
  } else if (!o.out.empty()) {
    if (Result<void> written = write_text_file(o.out, text); !written.has_value()) {
      c.err << written.error().message << '\n';
      return exit_code_for(written.error());
    }
  } else {
    c.out << text;
  }
  if (!o.quiet) {
    print_summary(*outcome, report, c.err);
    for (const auto& d : outcome->dropped) {
      c.err << "dropped task '" << m.task(d.task).name << "': " << d.reason << '\n';
    }
    if (!m.hazards.empty()) print_route_risk(*outcome, *map, m, c.err);
  }
  return kExitOk;
}

}  // namespace

void add_plan_command(CLI::App& app, Context& context) {
  // Shared with the callback, which CLI11 keeps after this function returns.
  auto o = std::make_shared<PlanOptions>();
  CLI::App* cmd = app.add_subcommand(
      "plan", "Plan a mission: the paper's actions, one a line (summary on standard error)");
  cmd->add_option("--map", o->map, "Map file (.json or .sewer)")->required();
  cmd->add_option("--mission", o->mission, "Mission file (.json)")->required();
  cmd->add_option("--algorithm,-a", o->algorithm,
                  "auto (optimal A* for small missions, the tour search otherwise), ehc, gbfs, "
                  "wastar, astar, exact (the proven optimum, up to 20 tasks)")
      ->capture_default_str();
  cmd->add_option("--heuristic", o->heuristic, "ff, add, max or blind (default: per algorithm)");
  cmd->add_option("--weight", o->weight, "Weight of weighted A*")->capture_default_str();
  cmd->add_option("--time-limit", o->time_limit_s, "Seconds before the search gives up")
      ->capture_default_str();
  cmd->add_option("--improve", o->improvement_expansions,
                  "Expansions spent looking for cheaper plans after the first (0: none)")
      ->capture_default_str();
  cmd->add_option("--out,-o", o->out, "Write the plan text to this file");
  cmd->add_flag("--json", o->json, "Print the plan with each action's cost as JSON");
  cmd->add_flag("--select-goals", o->select_goals,
                "Do as many tasks as can be done and still end the mission, rather than fail");
  cmd->add_flag("--quiet,-q", o->quiet, "No summary on standard error");
  add_motion_options(*cmd, o->motion);
  add_condition_option(*cmd, o->condition);
  add_risk_options(*cmd, o->risk);
  cmd->callback([o, &context] { context.exit_code = run(*o, context); });
}

}  // namespace sewerplan::cli
