// SPDX-License-Identifier: MIT
// sewerplan plan --map MAP --mission MISSION [--algorithm ...] [--json] [-o PLAN]
#include <algorithm>
#include <ostream>

#include <CLI/CLI.hpp>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/domain/plan_json.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/route_risk.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/executor/replanner.h"
#include "sewerplan/search/planner.h"

#include "command.h"
#include "condition_options.h"
#include "crs_option.h"
#include "json_output.h"
#include "map_input.h"
#include "motion_options.h"
#include "route_index_options.h"
#include "text_format.h"

namespace sewerplan::cli {
namespace {

struct PlanOptions {
  std::string map;
  std::string gis_fields;  // --gis-fields
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
  RouteIndexOptions route_index;
  std::string condition;
  RiskOptions risk;
  std::string crs;
};

void print_summary(const search::PlanOutcome& o, const domain::ValidationReport& report,
                   std::ostream& err) {
  err << "plan: " << o.plan.steps.size() << " steps, " << seconds(report.total_cost_s) << ", "
      << watt_hours(report.energy_wh) << (o.optimal ? " (optimal)" : "") << "; " << o.algorithm
      << "; compile " << milliseconds(o.compile.time_s) << " (" << o.compile.keys
      << " keys), search " << milliseconds(o.search.time_s) << " (" << o.search.expanded
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
  // The chance of a blockage at a hazard whose reserve the plan does not keep.
  err << std::setprecision(4) << "stranding risk " << o.strand_probability << " ("
      << o.uninsured.size() << (o.uninsured.size() == 1 ? " hazard" : " hazards")
      << " passed without the battery to back out and reach an exit another way)";
  if (!o.strand_note.empty()) err << "; " << o.strand_note;
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
    return usage_error(
        c, o.json,
        "--algorithm: unknown '" + o.algorithm + "' (" + search::algorithm_names() + ")");
  }
  options.algorithm = *algorithm;
  if (!o.heuristic.empty()) {
    options.heuristic = search::heuristic_from_string(o.heuristic);
    if (!options.heuristic) {
      return usage_error(
          c, o.json,
          "--heuristic: unknown '" + o.heuristic + "' (" + search::heuristic_names() + ")");
    }
  }
  options.weight = o.weight;
  options.time_limit_s = o.time_limit_s;
  options.improvement_expansions = o.improvement_expansions;
  options.select_goals = o.select_goals;
  if (std::string why = o.risk.strand_risk_error(); !why.empty())
    return usage_error(c, o.json, why);
  options.max_strand_risk = o.risk.max_strand_risk;
  Diagnostics diagnostics;
  Result<SewerMap> map = read_map_with_condition({o.map, o.gis_fields}, o.condition, diagnostics);
  if (map.has_value()) map = apply_crs_option(std::move(*map), o.crs);
  std::optional<Result<Mission>> mission;
  if (map.has_value()) mission = read_mission(o.mission, *map, diagnostics);
  std::optional<Error> risk_error;
  if (mission && mission->has_value()) {
    if (Result<void> r = apply_risk(o.risk, *map, **mission, diagnostics, c.err); !r.has_value()) {
      risk_error = r.error();
    }
  }
  options.risk = o.risk.costs();
  if (!map.has_value()) return fail(c, o.json, map.error(), diagnostics);
  if (!mission->has_value()) return fail(c, o.json, mission->error(), diagnostics);
  if (risk_error) return fail(c, o.json, *risk_error, diagnostics);
  print_diagnostics(diagnostics, c.err);  // warnings
  if (auto motion = attach_motion_table(o.motion, o.map, *map, **mission, c.err);
      !motion.has_value()) {
    return fail(c, o.json, motion.error());
  }
  const Mission& m = **mission;
  // The routes from the map's routing index, when one is kept beside it (issue 35).
  domain::CompileCache compile_cache;
  const auto use_index = [&](const domain::RouteIndex& index) {
    Result<void> used = compile_cache.use_route_index(index, *map, m.profile, m.passage_motion);
    if (used.has_value()) options.compile_cache = &compile_cache;
    return used;
  };
  if (auto index = attach_route_index(o.route_index, o.map, c.err, use_index); !index.has_value()) {
    return fail(c, o.json, index.error());
  }
  domain::MissionProgress start = domain::initial_progress(m, *map);
  const SteadyClock clock;
  const double started_s = clock.now_s();
  Result<search::PlanOutcome> outcome = search::plan_mission(*map, m, start, options);
  if (!outcome.has_value()) {
    return fail(c, o.json, outcome.error(), {},
                o.json ? plan_failure_json(*map, m, options, clock.now_s() - started_s) : Json());
  }
  // Tasks left out by goal selection are not required of the plan.
  for (const auto& d : outcome->dropped) start.done[d.task.index()] = true;
  const domain::ValidationReport report = domain::validate_plan(outcome->plan, *map, m, start);
  if (!report.valid) {  // a planner bug: say so rather than hand out a wrong plan
    return fail(c, o.json,
                Error{ErrorCode::kNoPlan,
                      "internal error: the plan found does not validate: " + report.error});
  }
  const std::string text = domain::format_plan(outcome->plan, *map, m);
  if (!o.out.empty()) {
    if (Result<void> written = write_text_file(o.out, text); !written.has_value()) {
      return fail(c, o.json, written.error());
    }
  }
  if (o.json) {
    print_json(c.out, plan_json(*outcome, report, *map, m));
  } else if (o.out.empty()) {
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
  cmd->add_option("--map", o->map, "Map file (any format of docs/formats/)")->required();
  add_gis_fields_option(*cmd, o->gis_fields);
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
  cmd->add_flag("--json", o->json,
                "Print the plan, its costs, decision, dropped tasks and planner statistics as "
                "JSON (or the error, the Replanner's decision and the tasks it would drop)");
  cmd->add_flag("--select-goals", o->select_goals,
                "Do as many tasks as can be done and still end the mission, rather than fail");
  cmd->add_flag("--quiet,-q", o->quiet, "No summary on standard error");
  add_motion_options(*cmd, o->motion);
  add_route_index_options(*cmd, o->route_index);
  add_condition_option(*cmd, o->condition);
  add_risk_options(*cmd, o->risk);
  add_crs_option(*cmd, o->crs);
  cmd->callback([o, &context] { context.exit_code = run(*o, context); });
}

}  // namespace sewerplan::cli
