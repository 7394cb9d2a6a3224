// SPDX-License-Identifier: MIT
#include "planners.h"

#include <chrono>
#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "sewerplan/core/map_io.h"
#include "sewerplan/core/output_file.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/domain/pddl.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/search/planner.h"

namespace sewerplan::compare {
namespace {

namespace fs = std::filesystem;

// Through core/output_file.h: checked, atomic; the error names the file.
Result<void> write_text(const fs::path& path, const std::string& text) {
  return write_text_file(path, text);
}

// Fills status and detail from how the process ended, when it did not produce a plan.
void classify_failure(const RunResult& run, Outcome& o) {
  if (!run.started) {
    o.status = "not run";
    o.detail = run.error;
  } else if (run.timed_out) {
    o.status = "timeout";
  } else if (run.signal != 0) {
    o.status = "crashed";
    o.detail = "signal " + std::to_string(run.signal);
  } else {
    o.status = "failed";
    o.detail = "exit " + std::to_string(run.exit_code);
  }
}

// The last two non-empty lines of a planner's output, on one line.
std::string last_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
  }
  std::string out;
  for (std::size_t i = lines.size() > 2 ? lines.size() - 2 : 0; i < lines.size(); ++i) {
    out += (out.empty() ? "" : " / ") + lines[i].substr(0, 100);
  }
  return out;
}

// Reads a plan file in `format` (nullopt: sewerplan's text) and validates it.
void check_plan(const Instance& instance, const fs::path& file,
                std::optional<domain::PddlPlanFormat> format, Outcome& o) {
  Result<std::string> text = read_text_file(file);
  if (!text.has_value()) {
    o.status = "failed";
    o.detail = "no plan file";
    return;
  }
  Diagnostics diagnostics;
  Result<domain::Plan> plan =
      format
          ? domain::import_pddl_plan(*text, file.string(), *format, instance.map, instance.mission,
                                     diagnostics)
          : domain::parse_plan(*text, file.string(), instance.map, instance.mission, diagnostics);
  if (!plan.has_value()) {
    const bool no_plan = plan.error().message.find("found no plan") != std::string::npos;
    o.status = no_plan ? "no plan" : "unreadable plan";
    o.detail = plan.error().message.substr(0, 160);
    return;
  }
  const domain::ValidationReport report =
      domain::validate_plan(*plan, instance.map, instance.mission);
  o.steps = plan->steps.size();
  o.cost_s = report.total_cost_s;
  if (report.valid) {
    o.status = "solved";
  } else {
    o.status = "invalid plan";
    o.detail = report.error.substr(0, 160);
  }
}

// Writes the PDDL export into `dir` (once per instance and variant).
bool export_to(const Instance& instance, const fs::path& dir, bool action_costs, Outcome& o) {
  if (fs::exists(dir / "problem.pddl")) return true;
  Result<void> written = create_output_directory(dir);
  Result<domain::PddlFiles> files =
      domain::export_pddl(instance.map, instance.mission, {.action_costs = action_costs});
  if (written.has_value()) written = files.has_value() ? Result<void>() : files.error();
  if (written.has_value()) written = write_text(dir / "domain.pddl", files->domain);
  if (written.has_value()) written = write_text(dir / "problem.pddl", files->problem);
  if (!written.has_value()) {
    o.status = "failed";
    o.detail = "PDDL export failed: " + written.error().message;
    return false;
  }
  return true;
}

// Labels a failed sewerplan run by what it said (native_child's {"error": {"code", "message"}}):
// "no plan" when it proved none, "timeout" at its time limit, "no plan found" when it stopped
// without a plan and without a proof.
void label_planner_error(const std::string& said, Outcome& o) {
  const nlohmann::json doc = nlohmann::json::parse(said, nullptr, false);
  if (doc.is_discarded() || !doc.contains("error") || !doc["error"].is_object()) return;
  const nlohmann::json& error = doc["error"];
  const std::string code = error.value("code", "");
  const std::string message = error.value("message", "");
  if (code == "no-plan") {
    o.status = "no plan";
  } else if (code == "search-limit") {
    o.status = message.find("time limit") != std::string::npos ? "timeout" : "no plan found";
  } else {
    o.status = "failed";
  }
  std::string detail = code + ": " + message;
  for (char& c : detail) c = c == '\n' ? ' ' : c;
  o.detail = detail.substr(0, 160);
}

}  // namespace

Outcome run_sewerplan(const Instance& instance, const PlannerPaths& paths,
                      const RunLimits& limits) {
  Outcome o{.planner = "sewerplan"};
  const fs::path plan = instance.directory / "sewerplan.plan";
  fs::remove(plan);
  RunLimits l = limits;
  l.stdout_path = (instance.directory / "sewerplan.out").string();
  l.stderr_path = (instance.directory / "sewerplan.err").string();
  std::ostringstream time_limit;
  time_limit << limits.time_limit_s;
  const RunResult run =
      run_process({paths.self, "--native-run", (instance.directory / "map.json").string(),
                   (instance.directory / "mission.json").string(), plan.string(), time_limit.str()},
                  l);
  o.wall_s = run.wall_s;
  o.peak_mb = run.peak_mb;
  if (!run.started || run.timed_out || run.signal != 0 || run.exit_code != 0) {
    classify_failure(run, o);
    // What the planner said, not its exit code: exit 5 is a search that stopped at its time limit
    // as well as one that found no plan and proved none (the tour search's battery check).
    Result<std::string> said = read_text_file(l.stdout_path);
    if (run.started && !run.timed_out && run.signal == 0 && said.has_value()) {
      label_planner_error(*said, o);
    }
    return o;
  }
  std::ifstream out(l.stdout_path);
  double inside = 0;
  if (out >> inside) o.load_and_plan_s = inside;
  check_plan(instance, plan, std::nullopt, o);
  return o;
}

Outcome run_ff(const Instance& instance, const PlannerPaths& paths, const RunLimits& limits) {
  Outcome o{.planner = "ff"};
  const fs::path dir = instance.directory / "strips";
  if (!export_to(instance, dir, false, o)) return o;
  RunLimits l = limits;
  l.directory = dir.string();
  l.stdout_path = (dir / "ff.out").string();
  l.stderr_path = (dir / "ff.err").string();
  const RunResult run = run_process({paths.ff, "-o", "domain.pddl", "-f", "problem.pddl"}, l);
  o.wall_s = run.wall_s;
  o.peak_mb = run.peak_mb;
  if (!run.started || run.timed_out || run.signal != 0) {
    classify_failure(run, o);
    return o;
  }
  // FF prints its plan after "found legal plan"; without it, its last words say what failed
  // (a parse error where its fixed-size tables or parser stack overflow, "proven unsolvable").
  Result<std::string> ff_out = read_text_file(dir / "ff.out");
  const std::string out = ff_out.has_value() ? *ff_out : std::string();
  if (out.find("found legal plan") == std::string::npos &&
      out.find("simplified to TRUE") == std::string::npos) {
    classify_failure(run, o);
    o.status = out.find("unsolvable") != std::string::npos ||
                       out.find("simplified to FALSE") != std::string::npos
                   ? "no plan"
                   : "failed";
    o.detail = last_lines(out);
    return o;
  }
  check_plan(instance, dir / "ff.out", domain::PddlPlanFormat::kFf, o);
  return o;
}

Outcome run_fd(const Instance& instance, const PlannerPaths& paths, const RunLimits& limits) {
  Outcome o{.planner = "fd " + paths.fd_alias};
  const fs::path dir = instance.directory / "costs";
  if (!export_to(instance, dir, true, o)) return o;
  fs::remove(dir / "sas_plan");
  RunLimits l = limits;
  l.directory = dir.string();
  l.stdout_path = (dir / "fd.out").string();
  l.stderr_path = (dir / "fd.err").string();
  const RunResult run = run_process({paths.fd, "--alias", paths.fd_alias, "--plan-file", "sas_plan",
                                     "domain.pddl", "problem.pddl"},
                                    l);
  o.wall_s = run.wall_s;
  o.peak_mb = run.peak_mb;
  if (!run.started || run.timed_out || run.signal != 0 || !fs::exists(dir / "sas_plan")) {
    classify_failure(run, o);
    // Fast Downward's exit codes (driver/returncodes.py): 12 unsolvable, 22 out of memory,
    // 23 out of time.
    if (run.exit_code == 11 || run.exit_code == 12) o.status = "no plan";
    if (run.exit_code == 22 || run.exit_code == 24) o.status = "out of memory";
    if (run.exit_code == 23) o.status = "timeout";
    return o;
  }
  check_plan(instance, dir / "sas_plan", domain::PddlPlanFormat::kFastDownward, o);
  return o;
}

int native_child(const std::string& map_path, const std::string& mission_path,
                 const std::string& plan_out, double time_limit_s) {
  const auto start = std::chrono::steady_clock::now();
  Diagnostics diagnostics;
  Result<SewerMap> map = read_map(map_path, diagnostics);
  if (!map.has_value()) return 1;
  Result<Mission> mission = read_mission(mission_path, *map, diagnostics);
  if (!mission.has_value()) return 1;
  auto outcome = search::plan_mission(*map, *mission, domain::initial_progress(*mission, *map),
                                      {.time_limit_s = time_limit_s});
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!outcome.has_value()) {
    // As the CLI's plan --json says it (docs/cli.md), for label_planner_error.
    std::cout << nlohmann::json{{"error",
                                 {{"code", to_string(outcome.error().code)},
                                  {"message", outcome.error().message}}}}
              << '\n';
    return outcome.error().code == ErrorCode::kNoPlan ? 4 : 5;
  }
  if (Result<void> w = write_text(plan_out, domain::format_plan(outcome->plan, *map, *mission));
      !w.has_value()) {
    std::cerr << w.error().message << '\n';
    return 3;
  }
  std::cout << elapsed << ' ' << outcome->cost_s << '\n';
  return 0;
}

}  // namespace sewerplan::compare
