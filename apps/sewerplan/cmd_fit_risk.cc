// SPDX-License-Identifier: MIT
// sewerplan fit-risk [--campaign DIR]... [--log EVENTS]... [--map MAP --condition FILE]
//   [--risk-table PRIOR] [--prior-strength K] [--level L] -o FITTED.json [--json]
//
// Fits the risk table from what robots met at the findings (core/risk_fit.h, issue 34): each
// hazard a mission drove past safely or was stopped by is one observation of its finding's rule.
// The observations come from campaign directories (runs.jsonl's "hazards" of each execution; the
// executions of one run share its faults, so a hazard counts once a run) and from mission event
// logs (`simulate --log`: the "hazard" events; once a log). A hazard is matched to the finding of
// the condition data at its pipe and offset; a hazard no finding explains is an error naming the
// file and line. Writes the fitted table (docs/formats/risk-table.md, with each rule's "fit") for
// `--risk-table`, and prints what it fitted.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "sewerplan/campaign/merge.h"
#include "sewerplan/core/map_json.h"
#include "sewerplan/core/output_file.h"
#include "sewerplan/core/risk_fit.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/executor/event_json.h"

#include "command.h"
#include "condition_options.h"
#include "json_output.h"
#include "map_input.h"

namespace sewerplan::cli {
namespace {

struct FitOptions {
  std::vector<std::string> campaigns;
  std::vector<std::string> logs;
  std::string map;
  std::string gis_fields;
  std::string condition;
  std::string risk_table;  // the prior; empty: the built-in table
  double prior_strength = 2;
  double level = 0.9;
  std::string output;
  bool json = false;
};

// One hazard as one mission saw it: where, which finding, and whether it stopped the robot.
struct Seen {
  PipeId pipe{0};
  double offset_m = 0;
  std::string reason;
  bool blocked = false;
};

// Several sightings of one hazard in one mission (or one run's executions, which share its
// faults) are one observation: blocked if any of them was.
void add_seen(std::vector<Seen>& mission, const Seen& s) {
  const auto same = std::find_if(mission.begin(), mission.end(), [&](const Seen& x) {
    return x.pipe == s.pipe && x.offset_m == s.offset_m && x.reason == s.reason;
  });
  if (same == mission.end()) {
    mission.push_back(s);
  } else {
    same->blocked = same->blocked || s.blocked;
  }
}

// The finding of `map` a hazard was made from (blockage_hazards: its pipe, its offset, a reason
// that starts with its code), or an error naming `where`.
Result<Finding> finding_of(const SewerMap& map, const Seen& s, const std::string& where) {
  for (const Finding& f : map.findings()) {
    if (f.pipe == s.pipe && std::abs(f.offset_m - s.offset_m) <= 1e-6 &&
        s.reason.starts_with(f.code)) {
      return f;
    }
  }
  std::ostringstream out;
  out << where << ": the hazard in pipe " << map.pipe(s.pipe).name << " at " << s.offset_m << " m ("
      << s.reason
      << ") is no finding of the condition data; give the map and --condition the mission used";
  return Error{ErrorCode::kParse, out.str()};
}

Result<SewerMap> read_map(const FitOptions& o, const std::string& map_path,
                          const std::string& condition, Diagnostics& diagnostics) {
  return read_map_with_condition({map_path, o.gis_fields}, condition, diagnostics);
}

// The observations of one campaign directory, each run's hazards once.
Result<void> campaign_observations(const FitOptions& o, const std::string& dir,
                                   std::vector<RiskObservation>& out, Diagnostics& diagnostics,
                                   std::size_t& missions) {
  Result<campaign::MergedCampaign> c = campaign::read_campaign_dir(dir);
  if (!c.has_value()) return c.error();
  const std::string map_path = o.map.empty() ? c->spec.map_name : o.map;
  const std::string condition = o.condition.empty() ? c->spec.condition_name : o.condition;
  Result<SewerMap> map = read_map(o, map_path, condition, diagnostics);
  if (!map.has_value()) {
    if (map.error().code != ErrorCode::kIo || (!o.map.empty() && !o.condition.empty())) {
      return map.error();
    }
    // campaign.json keeps the files as given, relative to where the campaign ran.
    return Error{ErrorCode::kIo, dir + "/campaign.json: " + map.error().message +
                                     " (the files as the campaign was given them; give --map "
                                     "and --condition)"};
  }
  std::ostringstream map_json;
  write_map_json(*map, map_json);
  if (campaign::fingerprint(map_json.str()) != c->spec.map_fingerprint) {
    return Error{ErrorCode::kInvalidMap,
                 dir + "/campaign.json: the map " + map_path +
                     (condition.empty() ? "" : " with " + condition) +
                     " is not the campaign's (its fingerprint differs); give --map and "
                     "--condition as the campaign was run"};
  }
  const std::string runs = dir + "/runs.jsonl";
  for (std::size_t i = 0; i < c->records.size(); ++i) {
    const campaign::RunRecord& r = c->records[i];
    if (!r.result) continue;  // a crash or hang: what it saw is not known
    ++missions;
    std::vector<Seen> run;
    const campaign::RunResult& x = *r.result;
    for (const campaign::Execution* e : {&x.ours, &x.baseline}) {
      for (const executor::HazardBelief& h : e->hazards) {
        add_seen(run, {h.pipe, h.offset_m, h.reason, h.blocked});
      }
    }
    if (x.risk_aware) {
      for (const executor::HazardBelief& h : x.risk_aware->hazards) {
        add_seen(run, {h.pipe, h.offset_m, h.reason, h.blocked});
      }
    }
    for (const Seen& s : run) {
      if (s.pipe.index() >= map->pipe_count()) {
        return Error{ErrorCode::kParse, runs + ":" + std::to_string(i + 1) + ": pipe #" +
                                            std::to_string(s.pipe.index()) + " is not in the map " +
                                            map_path};
      }
      Result<Finding> f = finding_of(*map, s, runs + ":" + std::to_string(i + 1));
      if (!f.has_value()) return f.error();
      out.push_back({.finding = std::move(*f), .blocked = s.blocked});
    }
  }
  return {};
}

// The observations of one mission's event log, each hazard once.
Result<void> log_observations(const SewerMap& map, const std::string& file,
                              std::vector<RiskObservation>& out, Diagnostics& diagnostics) {
  Result<std::string> text = read_text_file(file);
  if (!text.has_value()) return text.error();
  const Diagnostics::Mark before = diagnostics.mark();
  const std::vector<executor::LoggedEvent> events =
      executor::read_event_log_lines(*text, file, diagnostics);
  if (diagnostics.has_errors_since(before)) {
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  }
  std::vector<Seen> mission;
  std::vector<std::size_t> lines;
  for (const executor::LoggedEvent& e : events) {
    const auto* h = std::get_if<executor::HazardEvent>(&e.event.what);
    if (h == nullptr) continue;
    const std::string where = file + ":" + std::to_string(e.line);
    const std::optional<PipeId> pipe = map.find_pipe(h->pipe);
    if (!pipe) {
      return Error{ErrorCode::kParse, where + ": hazard in pipe '" + h->pipe +
                                          "', which the map has not (give the mission's map)"};
    }
    const Seen s{*pipe, h->offset_m, h->reason,
                 h->observed == executor::HazardEvent::Observed::kBlocked};
    // Checked at its line, so that a hazard no finding explains is named where it is.
    if (Result<Finding> f = finding_of(map, s, where); !f.has_value()) return f.error();
    add_seen(mission, s);
  }
  for (const Seen& s : mission) {
    Result<Finding> f = finding_of(map, s, file);
    if (!f.has_value()) return f.error();
    out.push_back({.finding = std::move(*f), .blocked = s.blocked});
  }
  return {};
}

// A probability for the summary: two decimals, three below 0.1.
std::string probability_text(double p) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(p < 0.1 ? 3 : 2) << p;
  return out.str();
}

int run(const FitOptions& o, Context& c) {
  if (o.campaigns.empty() && o.logs.empty()) {
    return usage_error(c, o.json, "fit-risk: give at least one --campaign DIR or --log EVENTS");
  }
  if (!o.logs.empty() && o.map.empty()) {
    return usage_error(c, o.json, "fit-risk: --log needs --map (and --condition) of its mission");
  }
  if (!(o.level > 0 && o.level < 1)) {
    return usage_error(c, o.json, "fit-risk: --level must be between 0 and 1");
  }
  if (!(o.prior_strength > 0)) {
    return usage_error(c, o.json, "fit-risk: --prior-strength must be more than 0");
  }
  Diagnostics diagnostics;
  RiskOptions risk;
  risk.table = o.risk_table;
  Result<RiskTable> prior = risk_table(risk, diagnostics);
  if (!prior.has_value()) return fail(c, o.json, prior.error(), diagnostics);
  std::vector<RiskObservation> seen;
  std::size_t missions = 0;
  for (const std::string& dir : o.campaigns) {
    if (Result<void> r = campaign_observations(o, dir, seen, diagnostics, missions);
        !r.has_value()) {
      return fail(c, o.json, r.error(), diagnostics);
    }
  }
  if (!o.logs.empty()) {
    Result<SewerMap> map = read_map(o, o.map, o.condition, diagnostics);
    if (!map.has_value()) return fail(c, o.json, map.error(), diagnostics);
    for (const std::string& log : o.logs) {
      if (Result<void> r = log_observations(*map, log, seen, diagnostics); !r.has_value()) {
        return fail(c, o.json, r.error(), diagnostics);
      }
      ++missions;
    }
  }
  Result<RiskTableFit> fit =
      fit_risk_table(*prior, seen, {.prior_strength = o.prior_strength, .level = o.level});
  if (!fit.has_value()) return fail(c, o.json, fit.error(), diagnostics);
  print_diagnostics(diagnostics, c.err);
  std::ostringstream table;
  write_risk_table_json(fit->table, table);
  if (Result<void> w = write_text_file(o.output, table.str()); !w.has_value()) {
    return fail(c, o.json, w.error());
  }
  std::ostream& text = o.json ? c.err : c.out;
  text << "fitted " << o.output << " from " << fit->observations << " observations in " << missions
       << " missions (prior strength " << o.prior_strength << ", " << std::lround(o.level * 100)
       << " % intervals)";
  if (fit->unfitted > 0) {
    text << "; " << fit->unfitted
         << " of findings the prior table does not rate as a possible blockage, not fitted";
  }
  text << "\n";
  Json rules = Json::array();
  for (const RiskRule& r : fit->table.rules) {
    if (!r.fit) continue;
    const RiskRuleFit& f = *r.fit;
    const std::string name = r.code + (r.characterisation.empty() ? "" : "/" + r.characterisation);
    text << "  " << std::left << std::setw(7) << name << std::setw(28) << r.meaning;
    if (f.observations == 0) {
      text << "no observations: the prior, probability " << probability_text(r.probability) << "\n";
    } else {
      text << f.blockages << " blocked of " << f.observations << ": probability "
           << probability_text(f.prior_probability) << " -> " << probability_text(r.probability)
           << " (the findings seen: " << probability_text(f.mean_prior) << " -> "
           << probability_text(f.mean) << ", interval " << probability_text(f.mean_low) << " to "
           << probability_text(f.mean_high) << ")\n";
    }
    rules.push_back(Json{{"code", r.code},
                         {"characterisation", r.characterisation},
                         {"meaning", r.meaning},
                         {"observations", f.observations},
                         {"blockages", f.blockages},
                         {"prior_probability", f.prior_probability},
                         {"probability", r.probability},
                         {"probability_per_percent", r.probability_per_percent},
                         {"mean_prior", f.mean_prior},
                         {"mean", f.mean},
                         {"mean_low", f.mean_low},
                         {"mean_high", f.mean_high}});
  }
  if (o.json) {
    Json j = Json::object();
    j["output"] = o.output;
    j["missions"] = missions;
    j["observations"] = fit->observations;
    j["unfitted"] = fit->unfitted;
    j["prior_strength"] = o.prior_strength;
    j["level"] = o.level;
    j["rules"] = std::move(rules);
    print_json(c.out, j);
  }
  return kExitOk;
}

}  // namespace

void add_fit_risk_command(CLI::App& app, Context& context) {
  auto options = std::make_shared<FitOptions>();
  CLI::App* cmd = app.add_subcommand(
      "fit-risk",
      "Fit the risk table from what robots met at the findings (campaigns, mission logs)");
  cmd->add_option("--campaign", options->campaigns,
                  "A campaign directory (campaign --out DIR); may be given more than once");
  cmd->add_option("--log", options->logs,
                  "A mission's event log (simulate --log); may be given more than once");
  cmd->add_option(
      "--map", options->map,
      "The map the logs are of (for campaigns: instead of the one campaign.json names)");
  add_gis_fields_option(*cmd, options->gis_fields);
  cmd->add_option(
      "--condition", options->condition,
      "The condition data the missions used (for campaigns: instead of campaign.json's)");
  cmd->add_option("--risk-table", options->risk_table,
                  "The prior table (docs/formats/risk-table.md); default: the built-in one");
  cmd->add_option("--prior-strength", options->prior_strength,
                  "How many observations the prior table weighs (default 2)");
  cmd->add_option("--level", options->level, "Of the credible intervals (default 0.9)");
  cmd->add_option("-o,--output", options->output, "The fitted risk table (JSON)")->required();
  cmd->add_flag("--json", options->json, "Print a JSON summary (docs/cli.md)");
  cmd->callback([options, &context] { context.exit_code = run(*options, context); });
}

}  // namespace sewerplan::cli
