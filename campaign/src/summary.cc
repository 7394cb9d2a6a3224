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
  double strand_risk = 0;
  for (const RunResult* r : runs) {
    const Execution& e = r->*policy;
    tasks += static_cast<double>(e.tasks);
    // Compared with the oracle where it can end the mission: elsewhere it does nothing, while a
    // robot may do tasks before it finds itself cut off.
    if (r->oracle_can_end) {
      const double s = share(e.tasks, r->oracle_tasks);
      ++f.compared;
      vs += s;
      if (f.compared == 1 || s < f.vs_oracle_worst) {
        f.vs_oracle_worst = s;
        f.worst_run = r->index;
      }
      std::size_t bin = std::min<std::size_t>(10, static_cast<std::size_t>(s * 10 + 1e-9));
      if (e.tasks > r->oracle_tasks) {
        ++f.above_oracle;
        bin = 11;
      }
      ++f.vs_oracle_histogram[bin];
    }
    ++f.outcomes[static_cast<std::size_t>(e.outcome)];
    const auto cause = static_cast<std::size_t>(e.beacon_cause);
    ++(e.outcome == Outcome::kBeacon ? f.beacon_causes : f.ended_otherwise_beacon_causes)[cause];
    // Each policy's own robot: a permanent malfunction that stopped the baseline's robot is no
    // missed exit of the baseline's, whatever ours met.
    if (r->oracle_can_end && !e.disabled) {
      ++f.could_reach_exit;
      if (e.outcome != Outcome::kExit && e.outcome != Outcome::kEndPoint) ++f.missed_exits;
    }
    if (e.exit_on_reserve) ++f.exits_on_reserve;
    if (!e.reserve_kept && !e.exit_on_reserve) ++f.reserve_violations;
    for (std::size_t k = 0; k < f.rungs.size(); ++k) f.rungs[k] += e.rungs[k];
    replans += static_cast<double>(e.replans);
    strand_risk += e.strand_risk;
    f.replans_max = std::max(f.replans_max, e.replans);
    for (double t : e.planning_times_s) planning_ms.push_back(t * 1000);
  }
  const double n = std::max<double>(1, static_cast<double>(runs.size()));
  f.tasks_mean = tasks / n;
  f.vs_oracle_mean = f.compared == 0 ? 0 : vs / static_cast<double>(f.compared);
  f.replans_mean = replans / n;
  f.strand_risk_mean = strand_risk / n;
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

constexpr std::string_view kNoneCompared = "none: the oracle could end no run";

// "99.1 %", or that no run could be compared.
std::string vs_mean(const PolicyFigures& f) {
  return f.compared == 0 ? std::string(kNoneCompared) : pct(f.vs_oracle_mean);
}

// "0.0 % (run 337)", or that no run could be compared.
std::string vs_worst(const PolicyFigures& f) {
  if (f.compared == 0) return std::string(kNoneCompared);
  return pct(f.vs_oracle_worst) + " (run " + std::to_string(f.worst_run) + ")";
}

// Every kind by name, with its shares (null: nothing to share).
Json by_kind_json(const ScoresByKind& by_kind) {
  const auto share = [](std::size_t part, std::size_t whole) {
    const std::optional<double> p = percent(part, whole);
    return p ? Json(*p) : Json();
  };
  Json j = Json::object();
  for (std::size_t i = 0; i < by_kind.size(); ++i) {
    const KindScore& k = by_kind[i];
    j[std::string(to_string(static_cast<Discrepancy::Kind>(i)))] =
        Json{{"found_pct", share(k.found, k.in_reach)},
             {"false_reports_pct", share(k.false_reports, k.reported)},
             {"in_reach", k.in_reach},
             {"found", k.found},
             {"reported", k.reported},
             {"false_reports", k.false_reports}};
  }
  return j;
}

// A share k of n with its 95 % Wilson score interval (Wilson 1927): sound near 0, where the
// normal approximation would give a negative bound.
struct Interval {
  double share = 0;
  double low = 0;
  double high = 0;
};
Interval wilson(std::size_t k, std::size_t n) {
  if (n == 0) return {};
  constexpr double z = 1.959964;
  const double total = static_cast<double>(n);
  const double p = static_cast<double>(k) / total;
  const double centre = (p + z * z / (2 * total)) / (1 + z * z / total);
  const double half =
      z * std::sqrt(p * (1 - p) / total + z * z / (4 * total * total)) / (1 + z * z / total);
  return {p, std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

Json policy_json(const PolicyFigures& f) {
  const Interval missed = wilson(f.missed_exits, f.could_reach_exit);
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
  Json rungs;
  for (std::size_t k = 0; k < f.rungs.size(); ++k) {
    rungs[std::string(executor::to_string(static_cast<executor::PlanResponse::Rung>(k)))] =
        f.rungs[k];
  }
  // Nothing to compare when the oracle can end no run: no mean, no worst run (null).
  const bool compared = f.compared > 0;
  return Json{{"tasks_mean", f.tasks_mean},
              {"compared_with_oracle", f.compared},
              {"tasks_vs_oracle_mean", compared ? Json(f.vs_oracle_mean) : Json()},
              {"tasks_vs_oracle_worst", compared ? Json(f.vs_oracle_worst) : Json()},
              {"worst_run", compared ? Json(f.worst_run) : Json()},
              {"runs_above_oracle", f.above_oracle},
              {"outcomes", outcomes},
              {"could_reach_exit", f.could_reach_exit},
              {"missed_exits", f.missed_exits},
              {"missed_exit_share", missed.share},
              {"missed_exit_share_95", Json::array({missed.low, missed.high})},
              {"strand_risk_mean", f.strand_risk_mean},
              {"beacons_by_cause", causes},
              {"beacons_ended_otherwise_by_cause", otherwise_causes},
              {"reserve_violations", f.reserve_violations},
              {"exits_on_reserve", f.exits_on_reserve},
              {"replans_mean", f.replans_mean},
              {"replans_max", f.replans_max},
              {"rungs", rungs},
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

// The failed runs (FailedRun) with `status`.
std::size_t count_failed(const Summary& s, RunRecord::Status status) {
  return static_cast<std::size_t>(std::count_if(
      s.failed.begin(), s.failed.end(), [&](const FailedRun& f) { return f.status == status; }));
}

}  // namespace

std::vector<std::string> verdict_faults(const Summary& s) {
  using Cause = executor::MissionReport::BeaconCause;
  std::vector<std::string> faults;
  const auto add = [&](std::size_t n, const std::string& what) {
    if (n > 0) faults.push_back(std::to_string(n) + " " + what);
  };
  const std::size_t crashes = count_failed(s, RunRecord::Status::kCrash);
  add(crashes, crashes == 1 ? "crash" : "crashes");
  add(s.failed.size() - crashes, s.failed.size() - crashes == 1 ? "hang" : "hangs");
  add(s.ours.missed_exits, s.ours.missed_exits == 1 ? "missed exit" : "missed exits");
  const std::size_t stranded = s.ours.outcomes[static_cast<std::size_t>(Outcome::kStranded)];
  add(stranded, stranded == 1 ? "stranded robot" : "stranded robots");
  add(s.ours.reserve_violations,
      s.ours.reserve_violations == 1 ? "reserve violation" : "reserve violations");
  const auto limit = static_cast<std::size_t>(Cause::kLimit);
  const std::size_t limits =
      s.ours.beacon_causes[limit] + s.ours.ended_otherwise_beacon_causes[limit];
  add(limits, limits == 1 ? "beacon caused by a limit" : "beacons caused by a limit");
  return faults;
}

bool Summary::clean() const { return verdict_faults(*this).empty(); }

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

std::optional<double> WorldFigures::correct_arrivals_pct() const {
  return percent(total.correct_arrivals, total.arrivals);
}
std::optional<double> WorldFigures::length_rms_pct() const {
  if (total.pipes_measured == 0) return std::nullopt;
  return total.length_rms_pct;
}
std::optional<double> WorldFigures::discrepancies_found_pct() const {
  return percent(total.found, total.seeded_in_reach);
}
std::optional<double> WorldFigures::false_reports_pct() const {
  return percent(total.false_reports, total.reported);
}

std::optional<WorldFigures> pool_world_scores(const std::vector<const RunResult*>& runs) {
  WorldFigures f;
  double squares = 0;  // sum over every measured pipe of (error in %)^2
  for (const RunResult* r : runs) {
    if (!r->ours.world) continue;
    const WorldScore& w = *r->ours.world;
    ++f.runs;
    f.total.arrivals += w.arrivals;
    f.total.correct_arrivals += w.correct_arrivals;
    f.total.pipes_measured += w.pipes_measured;
    squares += static_cast<double>(w.pipes_measured) * w.length_rms_pct * w.length_rms_pct;
    f.total.seeded_in_reach += w.seeded_in_reach;
    f.total.found += w.found;
    f.total.reported += w.reported;
    f.total.false_reports += w.false_reports;
    for (std::size_t i = 0; i < w.by_kind.size(); ++i) {
      KindScore& k = f.total.by_kind[i];
      k.in_reach += w.by_kind[i].in_reach;
      k.found += w.by_kind[i].found;
      k.reported += w.by_kind[i].reported;
      k.false_reports += w.by_kind[i].false_reports;
    }
  }
  if (f.runs == 0) return std::nullopt;
  if (f.total.pipes_measured > 0) {
    f.total.length_rms_pct = std::sqrt(squares / static_cast<double>(f.total.pipes_measured));
  }
  return f;
}

Summary summarize(const CampaignSpec& spec, const std::vector<RunRecord>& records) {
  Summary s;
  s.spec = spec;
  s.runs = records.size();
  std::vector<const RunResult*> runs;
  double oracle = 0;
  for (const RunRecord& r : records) {
    s.wall_s += r.wall_s;
    if (!r.result) {
      s.failed.push_back({r.index, r.seed, r.status, r.detail, reproduce_command(spec, r.index)});
      continue;
    }
    const RunResult& x = *r.result;
    runs.push_back(&x);
    oracle += static_cast<double>(x.oracle_tasks);
    if (x.could_reach_exit) ++s.could_reach_exit;
    if (x.oracle_can_end) ++s.oracle_can_end;
    if (x.oracle_can_end ? x.ours.tasks > x.oracle_tasks : ended(x.ours)) ++s.oracle_below_ours;
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
  s.world = pool_world_scores(runs);
  return s;
}

void write_summary_json(const Summary& s, std::ostream& out) {
  Json failed = Json::array();
  for (const FailedRun& f : s.failed) {
    failed.push_back(Json{{"run", f.run},
                          {"seed", std::to_string(f.seed)},
                          {"status", std::string(to_string(f.status))},
                          {"detail", f.detail},
                          {"command", f.command}});
  }
  Json j{{"map", s.spec.map_name},
         {"mission", s.spec.mission_name},
         {"seed", std::to_string(s.spec.seed)},
         {"fault_rates", format_fault_rates(s.spec.rates)},
         {"runs", s.runs},
         {"completed", s.completed},
         {"crashes", count_failed(s, RunRecord::Status::kCrash)},
         {"hangs", count_failed(s, RunRecord::Status::kHang)},
         {"failed_runs", failed},
         {"could_reach_exit", s.could_reach_exit},
         {"oracle_can_end", s.oracle_can_end},
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
  // Ours against the true world: null without world errors (docs/campaign.md).
  const auto or_null = [](const std::optional<double>& v) { return v ? Json(*v) : Json(); };
  if (s.world) {
    const WorldFigures& w = *s.world;
    j["localisation"] = Json{{"correct_arrivals_pct", or_null(w.correct_arrivals_pct())},
                             {"arrivals", w.total.arrivals},
                             {"correct_arrivals", w.total.correct_arrivals},
                             {"runs", w.runs}};
    j["corrected_map"] = Json{{"length_rms_pct", or_null(w.length_rms_pct())},
                              {"discrepancies_found_pct", or_null(w.discrepancies_found_pct())},
                              {"false_reports_pct", or_null(w.false_reports_pct())},
                              {"pipes_measured", w.total.pipes_measured},
                              {"seeded_in_reach", w.total.seeded_in_reach},
                              {"found", w.total.found},
                              {"reported", w.total.reported},
                              {"false_reports", w.total.false_reports},
                              {"by_kind", by_kind_json(w.total.by_kind)},
                              {"runs", w.runs}};
  } else {
    j["localisation"] = nullptr;
    j["corrected_map"] = nullptr;
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
  out << "| tasks vs oracle, mean | " << vs_mean(s.ours) << " | " << vs_mean(a) << " |\n";
  out << "| ended at an exit or the end point | " << ended_runs(s.ours) << " | " << ended_runs(a)
      << " |\n";
  out << "| could reach an exit but did not | " << s.ours.missed_exits << " | " << a.missed_exits
      << " |\n";
  // The bound's check: the stranding risk the first plans computed beside what was observed.
  const auto observed = [](const PolicyFigures& f) {
    const Interval i = wilson(f.missed_exits, f.could_reach_exit);
    std::ostringstream text;
    text << std::fixed << std::setprecision(4) << i.share << " [" << i.low << ", " << i.high << "]";
    return text.str();
  };
  out << "| missed exits, share [95 %] | " << observed(s.ours) << " | " << observed(a) << " |\n";
  out << "| stranding risk the first plans computed, mean | " << num(s.ours.strand_risk_mean, 4)
      << " | " << num(a.strand_risk_mean, 4) << " |\n";
  out << "| replans per mission, mean | " << num(s.ours.replans_mean) << " | "
      << num(a.replans_mean) << " |\n\n";
  out << "Risk-aware against risk-blind, run by run: " << s.risk_aware_better << " better, "
      << s.risk_aware_equal << " equal, " << s.risk_aware_worse
      << " worse (tasks done); only the risk-aware robot ended: " << s.risk_aware_only_ended
      << " runs, only the risk-blind one: " << s.risk_blind_only_ended << ".\n";
}

// "12.3 % (45 of 366)", or "none (no ...)".
std::string share_of(const std::optional<double>& v, std::size_t part, std::size_t whole,
                     std::string_view none) {
  if (!v) return "none (" + std::string(none) + ")";
  return num(*v, 1) + " % (" + std::to_string(part) + " of " + std::to_string(whole) + ")";
}

// Ours against the true world (world errors only).
void write_world_markdown(const WorldFigures& w, std::ostream& out) {
  const WorldScore& t = w.total;
  out << "\nOurs against the true world (" << w.runs << " runs):\n\n| | |\n|---|---|\n";
  out << "| arrivals at the true manhole (localisation.correct_arrivals_pct) | "
      << share_of(w.correct_arrivals_pct(), t.correct_arrivals, t.arrivals, "no arrival") << " |\n";
  out << "| measured lengths, RMS error (corrected_map.length_rms_pct) | "
      << (w.length_rms_pct() ? num(*w.length_rms_pct(), 2) + " % over " +
                                   std::to_string(t.pipes_measured) + " pipes"
                             : std::string("none (no pipe measured)"))
      << " |\n";
  out << "| seeded discrepancies within reach reported (corrected_map.discrepancies_found_pct) | "
      << share_of(w.discrepancies_found_pct(), t.found, t.seeded_in_reach, "none within reach")
      << " |\n";
  out << "| reports matching no seeded discrepancy (corrected_map.false_reports_pct) | "
      << share_of(w.false_reports_pct(), t.false_reports, t.reported, "none reported") << " |\n\n";
  // Kind by kind (corrected_map.by_kind), the kinds seeded within reach or reported.
  bool any = false;
  for (std::size_t i = 0; i < t.by_kind.size(); ++i) {
    const KindScore& k = t.by_kind[i];
    if (k.in_reach == 0 && k.reported == 0) continue;
    if (!any) {
      out << "| discrepancy kind | seeded within reach, reported | reports matching none |\n"
          << "|---|---|---|\n";
      any = true;
    }
    out << "| " << to_string(static_cast<Discrepancy::Kind>(i)) << " | "
        << share_of(percent(k.found, k.in_reach), k.found, k.in_reach, "none within reach") << " | "
        << share_of(percent(k.false_reports, k.reported), k.false_reports, k.reported,
                    "none reported")
        << " |\n";
  }
  if (any) out << "\n";
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
  out << "| tasks vs oracle, mean | " << vs_mean(s.ours) << " | " << vs_mean(s.baseline) << " |\n";
  out << "| tasks vs oracle, worst run | " << vs_worst(s.ours) << " | " << vs_worst(s.baseline)
      << " |\n";
  out << "| runs with more tasks than the oracle | " << s.ours.above_oracle << " | "
      << s.baseline.above_oracle << " |\n";
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
  out << "| could reach an exit (oracle can end, robot could move) | " << s.ours.could_reach_exit
      << " | " << s.baseline.could_reach_exit << " |\n";
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
  out << "Runs the oracle can end: " << s.oracle_can_end << " of " << s.completed;
  if (s.oracle_can_end == 0 && s.completed > 0) {
    out << " (the oracle could end no run: no policy could reach an exit, and there are no tasks "
           "to compare)";
  }
  out << "; runs that could reach an exit (ours): " << s.could_reach_exit
      << "; runs where ours did more than the oracle (more tasks than its plan, or ended a "
         "mission it could not end): "
      << s.oracle_below_ours << ".\n";
  if (s.risk_aware) write_risk_aware_markdown(s, out);
  if (s.world) write_world_markdown(*s.world, out);
  out << "Crashes and hangs: " << s.failed.size() << (s.failed.empty() ? ".\n" : ":\n");
  for (const FailedRun& f : s.failed) {
    out << "- run " << f.run << " (seed " << f.seed << "): " << to_string(f.status) << ", "
        << f.detail << "; reproduce with `" << f.command << "`\n";
  }
  const std::vector<std::string> faults = verdict_faults(s);
  if (faults.empty()) {
    out << "Verdict: clean (no crash, hang, missed exit, stranded robot, reserve violation or "
           "beacon caused by a limit).\n";
    return;
  }
  out << "Verdict: NOT clean:";
  for (std::size_t i = 0; i < faults.size(); ++i) out << (i == 0 ? " " : ", ") << faults[i];
  out << ".\n";
}

namespace {

// What the campaign is run with: the fault rates, the push setting and the planner's limit.
std::string settings_text(const CampaignSpec& spec) {
  std::string text = "fault rates " + format_fault_rates(spec.rates) + "; push " +
                     (spec.push_allowed ? "allowed" : "not allowed") + "; planner time limit ";
  if (spec.planner_time_limit_s > 0) {
    std::ostringstream limit;
    limit << spec.planner_time_limit_s << " s";
    text += limit.str();
  } else {
    text += "none";
  }
  return text;
}

// The SVG's histogram of tasks against the oracle, over the runs it can end.
void write_histogram_svg(const Summary& s, std::ostream& out) {
  constexpr int kLeft = 60;
  constexpr int kBottom = 290;
  constexpr int kTop = 100;
  constexpr int kBinWidth = 40;
  constexpr std::size_t kBins = 12;
  std::size_t max_bin = 1;
  for (std::size_t b = 0; b < kBins; ++b) {
    max_bin = std::max({max_bin, s.ours.vs_oracle_histogram[b], s.baseline.vs_oracle_histogram[b]});
  }
  out << "<text x=\"" << kLeft << "\" y=\"" << kTop - 12
      << "\">Runs by tasks done as a share of the oracle's (the " << s.oracle_can_end
      << " runs it can end)</text>\n";
  out << "<g id=\"histogram\">\n";
  out << "<line x1=\"" << kLeft << "\" y1=\"" << kBottom << "\" x2=\"" << kLeft + 12 * kBinWidth
      << "\" y2=\"" << kBottom << "\" stroke=\"black\"/>\n";
  if (s.oracle_can_end == 0) {
    out << "<text id=\"no-oracle\" x=\"" << kLeft + 6 * kBinWidth << "\" y=\""
        << (kTop + kBottom) / 2 << "\" text-anchor=\"middle\">"
        << xml_escape("The oracle could end no run: nothing to compare") << "</text>\n";
  }
  const double scale = static_cast<double>(kBottom - kTop) / static_cast<double>(max_bin);
  for (std::size_t b = 0; b < kBins; ++b) {
    const int x = kLeft + static_cast<int>(b) * kBinWidth;
    const std::size_t counts[2] = {s.ours.vs_oracle_histogram[b],
                                   s.baseline.vs_oracle_histogram[b]};
    for (int k = 0; k < 2; ++k) {
      if (counts[k] == 0) continue;
      const double h = static_cast<double>(counts[k]) * scale;
      out << "<rect class=\"" << (k == 0 ? "ours" : "baseline") << "\" x=\"" << x + 3 + k * 17
          << "\" y=\"" << num(kBottom - h, 1) << "\" width=\"16\" height=\"" << num(h, 1)
          << "\" fill=\"" << (k == 0 ? "#1f77b4" : "#ff7f0e") << "\"><title>" << counts[k]
          << " runs</title></rect>\n";
      out << "<text x=\"" << x + 11 + k * 17 << "\" y=\"" << num(kBottom - h - 3, 1)
          << "\" text-anchor=\"middle\" font-size=\"9\">" << counts[k] << "</text>\n";
    }
    const std::string label =
        b == 11 ? "more" : (b == 10 ? std::string("100%") : std::to_string(b * 10) + "-");
    out << "<text x=\"" << x + kBinWidth / 2 << "\" y=\"" << kBottom + 14
        << "\" text-anchor=\"middle\" font-size=\"10\">" << label << "</text>\n";
  }
  out << "</g>\n";
}

}  // namespace

void write_summary_svg(const Summary& s, std::ostream& out) {
  constexpr int kWidth = 800;
  constexpr int kHeight = 500;
  constexpr int kLeft = 60;
  constexpr int kBottom = 290;
  constexpr int kTop = 100;
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
  out << "<text id=\"settings\" x=\"" << kWidth / 2
      << "\" y=\"44\" text-anchor=\"middle\" font-size=\"11\">" << xml_escape(settings_text(s.spec))
      << "</text>\n";
  const std::vector<std::string> faults = verdict_faults(s);
  std::string verdict = "Verdict: clean";
  if (!faults.empty()) {
    verdict = "Verdict: NOT clean:";
    for (std::size_t i = 0; i < faults.size(); ++i) verdict += (i == 0 ? " " : ", ") + faults[i];
  }
  out << "<text id=\"verdict\" x=\"" << kWidth / 2
      << "\" y=\"66\" text-anchor=\"middle\" font-size=\"14\" font-weight=\"bold\" fill=\""
      << (faults.empty() ? "#2ca02c" : "#d62728") << "\">" << xml_escape(verdict) << "</text>\n";
  write_histogram_svg(s, out);
  // Outcomes: one stacked bar per policy.
  const int ox = kLeft + 12 * 40 + 50;
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
  const auto policy_key = [&](const char* colour, const char* name, const PolicyFigures& f) {
    key(colour, std::string(name) + ": tasks vs oracle mean " + vs_mean(f) + ", worst " +
                    vs_worst(f) + "; more than the oracle " + std::to_string(f.above_oracle) +
                    "; missed exits " + std::to_string(f.missed_exits) + " of " +
                    std::to_string(f.could_reach_exit));
  };
  policy_key("#1f77b4", "ours", s.ours);
  policy_key("#ff7f0e", "baseline", s.baseline);
  for (std::size_t o = 0; o < 4; ++o) {
    key(colours[o], std::string("ended: ") + std::string(to_string(static_cast<Outcome>(o))) +
                        " (ours " + std::to_string(s.ours.outcomes[o]) + ", baseline " +
                        std::to_string(s.baseline.outcomes[o]) + ")");
  }
  out << "</g>\n<text id=\"footer\" x=\"" << kLeft << "\" y=\"" << kHeight - 8
      << "\" font-size=\"11\">"
      << xml_escape("runs the oracle could not end (not drawn): " +
                    std::to_string(s.completed - s.oracle_can_end) +
                    "; crashes and hangs: " + std::to_string(s.failed.size()) +
                    "; reserve violations: " + std::to_string(s.ours.reserve_violations) +
                    "; replanning p50/p99 " + num(s.ours.planning_p50_ms, 2) + "/" +
                    num(s.ours.planning_p99_ms, 2) + " ms (measured)")
      << "</text>\n</svg>\n";
}

}  // namespace sewerplan::campaign
