// SPDX-License-Identifier: MIT
// Campaign figures (summary.h).
#include "sewerplan/campaign/summary.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include <nlohmann/json.hpp>

namespace sewerplan::campaign {
namespace {

using Json = nlohmann::ordered_json;

double share(std::size_t done, std::size_t oracle) {
  if (oracle == 0) return 1.0;
  return static_cast<double>(done) / static_cast<double>(oracle);
}

// Nearest-rank percentile of sorted values.
double percentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0;
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(sorted.size())));
  return sorted[std::min(sorted.size(), std::max<std::size_t>(rank, 1)) - 1];
}

void figures(const std::vector<const RunResult*>& runs, const Execution RunResult::*policy,
             PolicyFigures& f) {
  std::vector<double> planning_ms;
  double tasks = 0;
  double vs = 0;
  double replans = 0;
  std::size_t compared = 0;
  for (const RunResult* r : runs) {
    const Execution& e = r->*policy;
    tasks += static_cast<double>(e.tasks);
    // Compared with the oracle where it can end the mission: elsewhere it does nothing, while a
    // robot may do tasks before it finds itself cut off.
    if (r->oracle_can_end) {
      const double s = share(e.tasks, r->oracle_tasks);
      ++compared;
      vs += s;
      if (s < f.vs_oracle_worst) {
        f.vs_oracle_worst = s;
        f.worst_run = r->index;
      }
      ++f.vs_oracle_histogram[std::min<std::size_t>(10, static_cast<std::size_t>(s * 10 + 1e-9))];
    }
    ++f.outcomes[static_cast<std::size_t>(e.outcome)];
    const auto cause = static_cast<std::size_t>(e.beacon_cause);
    ++(e.outcome == Outcome::kBeacon ? f.beacon_causes : f.ended_otherwise_beacon_causes)[cause];
    if (r->could_reach_exit && e.outcome != Outcome::kExit && e.outcome != Outcome::kEndPoint) {
      ++f.missed_exits;
    }
    if (e.exit_on_reserve) ++f.exits_on_reserve;
    if (!e.reserve_kept && !e.exit_on_reserve) ++f.reserve_violations;
    replans += static_cast<double>(e.replans);
    f.replans_max = std::max(f.replans_max, e.replans);
    for (double t : e.planning_times_s) planning_ms.push_back(t * 1000);
  }
  const double n = std::max<double>(1, static_cast<double>(runs.size()));
  f.tasks_mean = tasks / n;
  f.vs_oracle_mean = compared == 0 ? 0 : vs / static_cast<double>(compared);
  f.replans_mean = replans / n;
  std::sort(planning_ms.begin(), planning_ms.end());
  f.planning_p50_ms = percentile(planning_ms, 0.50);
  f.planning_p99_ms = percentile(planning_ms, 0.99);
}

std::string pct(double v) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << v * 100 << " %";
  return out.str();
}

std::string num(double v, int digits = 2) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << v;
  return out.str();
}

Json policy_json(const PolicyFigures& f) {
  Json outcomes;
  for (std::size_t o = 0; o < f.outcomes.size(); ++o) {
    outcomes[std::string(to_string(static_cast<Outcome>(o)))] = f.outcomes[o];
  }
  Json causes, otherwise_causes;
  for (std::size_t c = 1; c < f.beacon_causes.size(); ++c) {
    const std::string name(
        executor::to_string(static_cast<executor::MissionReport::BeaconCause>(c)));
    causes[name] = f.beacon_causes[c];
    otherwise_causes[name] = f.ended_otherwise_beacon_causes[c];
  }
  return Json{{"tasks_mean", f.tasks_mean},
              {"tasks_vs_oracle_mean", f.vs_oracle_mean},
              {"tasks_vs_oracle_worst", f.vs_oracle_worst},
              {"worst_run", f.worst_run},
              {"outcomes", outcomes},
              {"missed_exits", f.missed_exits},
              {"beacons_by_cause", causes},
              {"beacons_ended_otherwise_by_cause", otherwise_causes},
              {"reserve_violations", f.reserve_violations},
              {"exits_on_reserve", f.exits_on_reserve},
              {"replans_mean", f.replans_mean},
              {"replans_max", f.replans_max},
              {"planning_ms_p50", f.planning_p50_ms},
              {"planning_ms_p99", f.planning_p99_ms},
              {"tasks_vs_oracle_histogram", f.vs_oracle_histogram}};
}

std::string xml_escape(std::string_view s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

bool Summary::clean() const {
  using Cause = executor::MissionReport::BeaconCause;
  return failed.empty() && ours.missed_exits == 0 &&
         ours.beacon_causes[static_cast<std::size_t>(Cause::kLimit)] == 0 &&
         ours.ended_otherwise_beacon_causes[static_cast<std::size_t>(Cause::kLimit)] == 0 &&
         ours.outcomes[static_cast<std::size_t>(Outcome::kStranded)] == 0 &&
         ours.reserve_violations == 0;
}

namespace {

bool ended(const Execution& e) {
  return e.outcome == Outcome::kExit || e.outcome == Outcome::kEndPoint;
}

// Risk-aware planning against ours (risk-blind), on the runs that have it.
void summarize_risk_aware(const std::vector<const RunResult*>& runs, Summary& s) {
  std::vector<RunResult> aware;
  for (const RunResult* r : runs) {
    if (!r->risk_aware) continue;
    const Execution& a = *r->risk_aware;
    if (a.tasks > r->ours.tasks) {
      ++s.risk_aware_better;
    } else if (a.tasks == r->ours.tasks) {
      ++s.risk_aware_equal;
    } else {
      ++s.risk_aware_worse;
    }
    if (ended(a) && !ended(r->ours)) ++s.risk_aware_only_ended;
    if (!ended(a) && ended(r->ours)) ++s.risk_blind_only_ended;
    aware.push_back(*r);
    aware.back().ours = a;
  }
  if (aware.empty()) return;
  std::vector<const RunResult*> pointers;
  for (const RunResult& r : aware) pointers.push_back(&r);
  s.risk_aware.emplace();
  figures(pointers, &RunResult::ours, *s.risk_aware);
}

}  // namespace

Summary summarize(const CampaignSpec& spec, const std::vector<RunRecord>& records) {
  Summary s;
  s.spec = spec;
  s.runs = records.size();
  std::vector<const RunResult*> runs;
  double oracle = 0;
  for (const RunRecord& r : records) {
    s.wall_s += r.wall_s;
    if (!r.result) {
      s.failed.push_back({r.index, r.seed, std::string(to_string(r.status)), r.detail,
                          reproduce_command(spec, r.index)});
      continue;
    }
    const RunResult& x = *r.result;
    runs.push_back(&x);
    oracle += static_cast<double>(x.oracle_tasks);
    if (x.could_reach_exit) ++s.could_reach_exit;
    if (x.oracle_can_end && x.ours.tasks > x.oracle_tasks) ++s.oracle_below_ours;
    if (x.ours.tasks > x.baseline.tasks) {
      ++s.better_than_baseline;
    } else if (x.ours.tasks == x.baseline.tasks) {
      ++s.equal_to_baseline;
    } else {
      ++s.worse_than_baseline;
    }
  }
  s.completed = runs.size();
  s.oracle_tasks_mean = runs.empty() ? 0 : oracle / static_cast<double>(runs.size());
  figures(runs, &RunResult::ours, s.ours);
  figures(runs, &RunResult::baseline, s.baseline);
  summarize_risk_aware(runs, s);
  return s;
}

void write_summary_json(const Summary& s, std::ostream& out) {
  Json failed = Json::array();
  for (const FailedRun& f : s.failed) {
    failed.push_back(Json{{"run", f.run},
                          {"seed", std::to_string(f.seed)},
                          {"status", f.status},
                          {"detail", f.detail},
                          {"command", f.command}});
  }
  Json j{{"map", s.spec.map_name},
         {"mission", s.spec.mission_name},
         {"seed", std::to_string(s.spec.seed)},
         {"fault_rates", format_fault_rates(s.spec.rates)},
         {"runs", s.runs},
         {"completed", s.completed},
         {"crashes", std::count_if(s.failed.begin(), s.failed.end(),
                                   [](const FailedRun& f) { return f.status == "crash"; })},
         {"hangs", std::count_if(s.failed.begin(), s.failed.end(),
                                 [](const FailedRun& f) { return f.status == "hang"; })},
         {"failed_runs", failed},
         {"could_reach_exit", s.could_reach_exit},
         {"oracle_tasks_mean", s.oracle_tasks_mean},
         {"oracle_below_ours", s.oracle_below_ours},
         {"ours", policy_json(s.ours)},
         {"baseline", policy_json(s.baseline)},
         {"vs_baseline", Json{{"better", s.better_than_baseline},
                              {"equal", s.equal_to_baseline},
                              {"worse", s.worse_than_baseline}}},
         {"clean", s.clean()},
         {"measured", Json{{"wall_s_total", s.wall_s}}}};
  if (s.risk_aware) {
    j["risk_aware"] = policy_json(*s.risk_aware);
    j["risk_aware_vs_ours"] = Json{{"better", s.risk_aware_better},
                                   {"equal", s.risk_aware_equal},
                                   {"worse", s.risk_aware_worse},
                                   {"only_risk_aware_ended", s.risk_aware_only_ended},
                                   {"only_ours_ended", s.risk_blind_only_ended}};
  }
  if (!s.spec.condition_name.empty()) j["condition"] = s.spec.condition_name;
  if (s.spec.faults_from_condition) j["faults_from_condition"] = true;
  out << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
}

namespace {

// Risk-aware against risk-blind planning (ours), on the same faults.
void write_risk_aware_markdown(const Summary& s, std::ostream& out) {
  const PolicyFigures& a = *s.risk_aware;
  const auto ended_runs = [](const PolicyFigures& f) {
    return f.outcomes[static_cast<std::size_t>(Outcome::kExit)] +
           f.outcomes[static_cast<std::size_t>(Outcome::kEndPoint)];
  };
  out << "\nRisk-aware planning (--risk expected) against ours, which is risk-blind"
      << (s.spec.faults_from_condition ? ", with obstacles drawn from the condition data" : "")
      << ":\n\n| | risk-blind (ours) | risk-aware |\n|---|---|---|\n";
  out << "| tasks done per run (oracle: " << num(s.oracle_tasks_mean) << ") | "
      << num(s.ours.tasks_mean) << " | " << num(a.tasks_mean) << " |\n";
  out << "| tasks vs oracle, mean | " << pct(s.ours.vs_oracle_mean) << " | "
      << pct(a.vs_oracle_mean) << " |\n";
  out << "| ended at an exit or the end point | " << ended_runs(s.ours) << " | " << ended_runs(a)
      << " |\n";
  out << "| could reach an exit but did not | " << s.ours.missed_exits << " | " << a.missed_exits
      << " |\n";
  out << "| replans per mission, mean | " << num(s.ours.replans_mean) << " | "
      << num(a.replans_mean) << " |\n\n";
  out << "Risk-aware against risk-blind, run by run: " << s.risk_aware_better << " better, "
      << s.risk_aware_equal << " equal, " << s.risk_aware_worse
      << " worse (tasks done); only the risk-aware robot ended: " << s.risk_aware_only_ended
      << " runs, only the risk-blind one: " << s.risk_blind_only_ended << ".\n";
}

}  // namespace

void write_summary_markdown(const Summary& s, std::ostream& out) {
  const auto outcome = [](const PolicyFigures& f, Outcome o) {
    return f.outcomes[static_cast<std::size_t>(o)];
  };
  out << "# Fault campaign: " << s.spec.mission_name << " on " << s.spec.map_name << "\n\n";
  out << "Seed " << s.spec.seed << ", " << s.runs << " runs";
  if (s.spec.shard_count > 1)
    out << " (shard " << s.spec.shard_index << "/" << s.spec.shard_count << ")";
  out << ", fault rates " << format_fault_rates(s.spec.rates)
      << (s.spec.push_allowed ? ", push allowed" : "");
  if (s.spec.planner_time_limit_s > 0) {
    out << ", planner time limit " << s.spec.planner_time_limit_s << " s";
  }
  out << ".\n\n";
  out << "| | ours | baseline |\n|---|---|---|\n";
  out << "| tasks done per run (oracle: " << num(s.oracle_tasks_mean) << ") | "
      << num(s.ours.tasks_mean) << " | " << num(s.baseline.tasks_mean) << " |\n";
  out << "| tasks vs oracle, mean | " << pct(s.ours.vs_oracle_mean) << " | "
      << pct(s.baseline.vs_oracle_mean) << " |\n";
  out << "| tasks vs oracle, worst run | " << pct(s.ours.vs_oracle_worst) << " (run "
      << s.ours.worst_run << ") | " << pct(s.baseline.vs_oracle_worst) << " (run "
      << s.baseline.worst_run << ") |\n";
  for (Outcome o : {Outcome::kExit, Outcome::kEndPoint, Outcome::kBeacon, Outcome::kStranded}) {
    out << "| ended: " << to_string(o) << " | " << outcome(s.ours, o) << " | "
        << outcome(s.baseline, o) << " |\n";
  }
  for (std::size_t c = 1; c < s.ours.beacon_causes.size(); ++c) {
    out << "| beacons: "
        << executor::to_string(static_cast<executor::MissionReport::BeaconCause>(c)) << " | "
        << s.ours.beacon_causes[c] << " | " << s.baseline.beacon_causes[c] << " |\n";
  }
  const auto ended_otherwise = [](const PolicyFigures& f) {
    std::size_t n = 0;
    for (std::size_t c = 1; c < f.ended_otherwise_beacon_causes.size(); ++c)
      n += f.ended_otherwise_beacon_causes[c];
    return n;
  };
  out << "| beacon called, run ended otherwise | " << ended_otherwise(s.ours) << " | "
      << ended_otherwise(s.baseline) << " |\n";
  out << "| could reach an exit but did not | " << s.ours.missed_exits << " | "
      << s.baseline.missed_exits << " |\n";
  out << "| battery-reserve violations | " << s.ours.reserve_violations << " | "
      << s.baseline.reserve_violations << " |\n";
  out << "| sent out on the reserve (no exit above it) | " << s.ours.exits_on_reserve << " | "
      << s.baseline.exits_on_reserve << " |\n";
  out << "| replans per mission, mean / max | " << num(s.ours.replans_mean) << " / "
      << s.ours.replans_max << " | " << num(s.baseline.replans_mean) << " / "
      << s.baseline.replans_max << " |\n";
  out << "| planning time p50 / p99 (measured) | " << num(s.ours.planning_p50_ms, 3) << " / "
      << num(s.ours.planning_p99_ms, 3) << " ms | " << num(s.baseline.planning_p50_ms, 3) << " / "
      << num(s.baseline.planning_p99_ms, 3) << " ms |\n\n";
  out << "Ours against the baseline, run by run: " << s.better_than_baseline << " better, "
      << s.equal_to_baseline << " equal, " << s.worse_than_baseline << " worse (tasks done).\n";
  out << "Runs that could reach an exit (oracle): " << s.could_reach_exit << " of " << s.completed
      << "; runs where ours did more than the oracle's plan: " << s.oracle_below_ours << ".\n";
  if (s.risk_aware) write_risk_aware_markdown(s, out);
  out << "Crashes and hangs: " << s.failed.size() << (s.failed.empty() ? ".\n" : ":\n");
  for (const FailedRun& f : s.failed) {
    out << "- run " << f.run << " (seed " << f.seed << "): " << f.status << ", " << f.detail
        << "; reproduce with `" << f.command << "`\n";
  }
  out << "Verdict: " << (s.clean() ? "clean" : "NOT clean")
      << " (no crash, hang, missed exit, stranded robot, reserve violation or beacon caused by a "
         "limit).\n";
}

void write_summary_svg(const Summary& s, std::ostream& out) {
  constexpr int kWidth = 760;
  constexpr int kHeight = 420;
  constexpr int kLeft = 60;
  constexpr int kBottom = 250;
  constexpr int kTop = 60;
  constexpr int kBinWidth = 42;
  const char* ours_colour = "#1f77b4";
  const char* baseline_colour = "#ff7f0e";
  std::size_t max_bin = 1;
  for (std::size_t b = 0; b < 11; ++b) {
    max_bin = std::max({max_bin, s.ours.vs_oracle_histogram[b], s.baseline.vs_oracle_histogram[b]});
  }
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
      << "\" viewBox=\"0 0 " << kWidth << ' ' << kHeight
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  out << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  const auto file = [](const std::string& path) {
    return std::filesystem::path(path).filename().string();
  };
  out << "<text id=\"title\" x=\"" << kWidth / 2
      << "\" y=\"24\" text-anchor=\"middle\" font-size=\"15\">"
      << xml_escape("Fault campaign: " + file(s.spec.mission_name) + " on " +
                    file(s.spec.map_name) + ", " + std::to_string(s.completed) + " runs, seed " +
                    std::to_string(s.spec.seed))
      << "</text>\n";
  out << "<text x=\"" << kLeft << "\" y=\"" << kTop - 12
      << "\">Runs by tasks done as a share of the oracle's</text>\n";
  out << "<g id=\"histogram\">\n";
  out << "<line x1=\"" << kLeft << "\" y1=\"" << kBottom << "\" x2=\"" << kLeft + 11 * kBinWidth
      << "\" y2=\"" << kBottom << "\" stroke=\"black\"/>\n";
  const double scale = static_cast<double>(kBottom - kTop) / static_cast<double>(max_bin);
  for (std::size_t b = 0; b < 11; ++b) {
    const int x = kLeft + static_cast<int>(b) * kBinWidth;
    const std::size_t counts[2] = {s.ours.vs_oracle_histogram[b],
                                   s.baseline.vs_oracle_histogram[b]};
    for (int k = 0; k < 2; ++k) {
      const double h = static_cast<double>(counts[k]) * scale;
      out << "<rect class=\"" << (k == 0 ? "ours" : "baseline") << "\" x=\"" << x + 3 + k * 18
          << "\" y=\"" << num(kBottom - h, 1) << "\" width=\"17\" height=\"" << num(h, 1)
          << "\" fill=\"" << (k == 0 ? ours_colour : baseline_colour) << "\"><title>" << counts[k]
          << " runs</title></rect>\n";
      if (counts[k] > 0) {
        out << "<text x=\"" << x + 11 + k * 18 << "\" y=\"" << num(kBottom - h - 3, 1)
            << "\" text-anchor=\"middle\" font-size=\"9\">" << counts[k] << "</text>\n";
      }
    }
    out << "<text x=\"" << x + kBinWidth / 2 << "\" y=\"" << kBottom + 14
        << "\" text-anchor=\"middle\" font-size=\"10\">"
        << (b == 10 ? std::string("100%") : std::to_string(b * 10) + "-") << "</text>\n";
  }
  out << "</g>\n";
  // Outcomes: one stacked bar per policy.
  const int ox = kLeft + 11 * kBinWidth + 40;
  const char* colours[4] = {"#2ca02c", "#98df8a", "#d62728", "#7f7f7f"};
  out << "<text x=\"" << ox << "\" y=\"" << kTop - 12
      << "\">Outcomes</text>\n<g id=\"outcomes\">\n";
  const double total = std::max<double>(1, static_cast<double>(s.completed));
  for (int k = 0; k < 2; ++k) {
    const PolicyFigures& f = k == 0 ? s.ours : s.baseline;
    double y = kTop;
    for (std::size_t o = 0; o < 4; ++o) {
      const double h = static_cast<double>(f.outcomes[o]) / total * (kBottom - kTop);
      out << "<rect class=\"outcome-" << to_string(static_cast<Outcome>(o)) << "\" x=\""
          << ox + k * 60 << "\" y=\"" << num(y, 1) << "\" width=\"45\" height=\"" << num(h, 1)
          << "\" fill=\"" << colours[o] << "\"><title>" << to_string(static_cast<Outcome>(o))
          << ": " << f.outcomes[o] << "</title></rect>\n";
      y += h;
    }
    out << "<text x=\"" << ox + k * 60 + 22 << "\" y=\"" << kBottom + 14
        << "\" text-anchor=\"middle\" font-size=\"10\">" << (k == 0 ? "ours" : "baseline")
        << "</text>\n";
  }
  out << "</g>\n<g id=\"legend\">\n";
  int ly = kBottom + 40;
  const auto key = [&](const char* colour, const std::string& text) {
    out << "<rect x=\"" << kLeft << "\" y=\"" << ly - 10 << "\" width=\"12\" height=\"12\" fill=\""
        << colour << "\"/><text x=\"" << kLeft + 18 << "\" y=\"" << ly << "\">" << xml_escape(text)
        << "</text>\n";
    ly += 18;
  };
  key(ours_colour, "ours: tasks vs oracle mean " + pct(s.ours.vs_oracle_mean) + ", worst " +
                       pct(s.ours.vs_oracle_worst));
  key(baseline_colour, "baseline: mean " + pct(s.baseline.vs_oracle_mean) + ", worst " +
                           pct(s.baseline.vs_oracle_worst));
  for (std::size_t o = 0; o < 4; ++o) {
    key(colours[o], std::string("ended: ") + std::string(to_string(static_cast<Outcome>(o))) +
                        " (ours " + std::to_string(s.ours.outcomes[o]) + ", baseline " +
                        std::to_string(s.baseline.outcomes[o]) + ")");
  }
  out << "</g>\n<text x=\"" << kLeft << "\" y=\"" << kHeight - 8 << "\" font-size=\"11\">"
      << xml_escape("crashes and hangs: " + std::to_string(s.failed.size()) +
                    "; reserve violations: " + std::to_string(s.ours.reserve_violations) +
                    "; replanning p50/p99 " + num(s.ours.planning_p50_ms, 2) + "/" +
                    num(s.ours.planning_p99_ms, 2) + " ms (measured)")
      << "</text>\n</svg>\n";
}

}  // namespace sewerplan::campaign
