// SPDX-License-Identifier: MIT
// Run records and campaign specs as JSON (record.h).
#include "sewerplan/campaign/record.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

namespace sewerplan::campaign {
namespace {

using Json = nlohmann::ordered_json;

double ms(double seconds) { return std::round(seconds * 1e6) / 1e3; }

Json execution_json(const Execution& e) {
  return Json{{"tasks", e.tasks},
              {"outcome", std::string(to_string(e.outcome))},
              {"end", e.end},
              {"reserve_kept", e.reserve_kept},
              {"replans", e.replans},
              {"time_s", e.time_s},
              {"energy_wh", e.energy_wh},
              {"disabled", e.disabled},
              {"beacon_cause", std::string(executor::to_string(e.beacon_cause))}};
}

Json planning_json(const Execution& e) {
  Json list = Json::array();
  for (double t : e.planning_times_s) list.push_back(ms(t));
  return list;
}

// Field access that reports the path of what is missing or of the wrong type.
class Reader {
 public:
  Reader(std::string where) : where_(std::move(where)) {}

  const Json& at(const Json& j, const char* key, const std::string& path) {
    if (!j.is_object() || !j.contains(key))
      throw Bad{where_ + ": " + path + "." + key + ": missing"};
    return j.at(key);
  }
  template <class T>
  T get(const Json& j, const char* key, const std::string& path) {
    const Json& v = at(j, key, path);
    bool ok = false;
    if constexpr (std::is_same_v<T, std::size_t>) {
      ok = v.is_number_unsigned();
    } else if constexpr (std::is_same_v<T, double>) {
      ok = v.is_number();
    } else if constexpr (std::is_same_v<T, bool>) {
      ok = v.is_boolean();
    } else {
      ok = v.is_string();
    }
    if (!ok) throw Bad{where_ + ": " + path + "." + key + ": wrong type"};
    return v.get<T>();
  }
  std::uint64_t seed(const Json& j, const std::string& path) {
    const std::string text = get<std::string>(j, "seed", path);
    std::uint64_t v = 0;
    std::size_t used = 0;
    try {
      v = std::stoull(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != text.size() || text[0] == '-') {
      throw Bad{where_ + ": " + path + ".seed: not an unsigned integer"};
    }
    return v;
  }
  Execution execution(const Json& j, const char* key) {
    const Json& e = at(j, key, "$");
    const std::string path = std::string("$.") + key;
    Execution x;
    x.tasks = get<std::size_t>(e, "tasks", path);
    const auto outcome = outcome_from_string(get<std::string>(e, "outcome", path));
    if (!outcome) throw Bad{where_ + ": " + path + ".outcome: unknown outcome"};
    x.outcome = *outcome;
    x.end = get<std::string>(e, "end", path);
    x.reserve_kept = get<bool>(e, "reserve_kept", path);
    x.replans = get<std::size_t>(e, "replans", path);
    x.time_s = get<double>(e, "time_s", path);
    x.energy_wh = get<double>(e, "energy_wh", path);
    x.disabled = get<bool>(e, "disabled", path);
    // Records written before beacons had causes have none.
    if (e.contains("beacon_cause")) {
      const auto cause = executor::parse_beacon_cause(get<std::string>(e, "beacon_cause", path));
      if (!cause) throw Bad{where_ + ": " + path + ".beacon_cause: unknown cause"};
      x.beacon_cause = *cause;
    }
    return x;
  }
  std::vector<double> times(const Json& j, const char* key) {
    const Json& list = at(j, key, "$.measured");
    if (!list.is_array()) throw Bad{where_ + ": $.measured." + key + ": not a list"};
    std::vector<double> out;
    for (const Json& v : list) {
      if (!v.is_number()) throw Bad{where_ + ": $.measured." + key + ": not a number"};
      out.push_back(v.get<double>() / 1e3);
    }
    return out;
  }

  struct Bad {
    std::string message;
  };

 private:
  std::string where_;
};

}  // namespace

std::string_view to_string(RunRecord::Status status) {
  switch (status) {
    case RunRecord::Status::kOk:
      return "ok";
    case RunRecord::Status::kCrash:
      return "crash";
    case RunRecord::Status::kHang:
      return "hang";
  }
  return "crash";
}

std::string run_json_line(const RunRecord& record) {
  Json j;
  j["run"] = record.index;
  j["seed"] = std::to_string(record.seed);
  j["status"] = std::string(to_string(record.status));
  if (!record.detail.empty()) j["detail"] = record.detail;
  Json measured{{"wall_s", std::round(record.wall_s * 1e4) / 1e4}};
  if (const RunResult* r = record.result ? &*record.result : nullptr) {
    j["tasks"] = r->tasks;
    const FaultCounts& f = r->faults;
    j["faults"] = Json{
        {"obstacles", f.obstacles},       {"permanent_obstacles", f.permanent_obstacles},
        {"danger_spots", f.danger_spots}, {"dangerous_passages", f.dangerous_passages},
        {"malfunctions", f.malfunctions}, {"permanent_malfunctions", f.permanent_malfunctions}};
    j["oracle"] = Json{{"tasks", r->oracle_tasks}, {"can_end", r->oracle_can_end}};
    j["could_reach_exit"] = r->could_reach_exit;
    j["ours"] = execution_json(r->ours);
    j["baseline"] = execution_json(r->baseline);
    measured["planning_ms"] = planning_json(r->ours);
    measured["baseline_planning_ms"] = planning_json(r->baseline);
    if (r->risk_aware) {
      j["risk_aware"] = execution_json(*r->risk_aware);
      measured["risk_aware_planning_ms"] = planning_json(*r->risk_aware);
    }
  }
  j["measured"] = measured;
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

Result<RunRecord> parse_run_line(std::string_view line, const std::string& file_name,
                                 std::size_t line_number) {
  const std::string where = file_name + ":" + std::to_string(line_number);
  const Json j = Json::parse(line, nullptr, false);
  if (j.is_discarded() || !j.is_object()) {
    return Error{ErrorCode::kParse, where + ": not a JSON object"};
  }
  Reader in(where);
  try {
    RunRecord r;
    r.index = in.get<std::size_t>(j, "run", "$");
    r.seed = in.seed(j, "$");
    const std::string status = in.get<std::string>(j, "status", "$");
    if (status == "ok") {
      r.status = RunRecord::Status::kOk;
    } else if (status == "crash") {
      r.status = RunRecord::Status::kCrash;
    } else if (status == "hang") {
      r.status = RunRecord::Status::kHang;
    } else {
      throw Reader::Bad{where + ": $.status: unknown status '" + status + "'"};
    }
    if (j.contains("detail")) r.detail = in.get<std::string>(j, "detail", "$");
    const Json& measured = in.at(j, "measured", "$");
    r.wall_s = in.get<double>(measured, "wall_s", "$.measured");
    if (r.status == RunRecord::Status::kOk) {
      RunResult x;
      x.index = r.index;
      x.seed = r.seed;
      x.wall_s = r.wall_s;
      x.tasks = in.get<std::size_t>(j, "tasks", "$");
      const Json& f = in.at(j, "faults", "$");
      x.faults.obstacles = in.get<std::size_t>(f, "obstacles", "$.faults");
      x.faults.permanent_obstacles = in.get<std::size_t>(f, "permanent_obstacles", "$.faults");
      x.faults.danger_spots = in.get<std::size_t>(f, "danger_spots", "$.faults");
      x.faults.dangerous_passages = in.get<std::size_t>(f, "dangerous_passages", "$.faults");
      x.faults.malfunctions = in.get<std::size_t>(f, "malfunctions", "$.faults");
      x.faults.permanent_malfunctions =
          in.get<std::size_t>(f, "permanent_malfunctions", "$.faults");
      const Json& o = in.at(j, "oracle", "$");
      x.oracle_tasks = in.get<std::size_t>(o, "tasks", "$.oracle");
      x.oracle_can_end = in.get<bool>(o, "can_end", "$.oracle");
      x.could_reach_exit = in.get<bool>(j, "could_reach_exit", "$");
      x.ours = in.execution(j, "ours");
      x.baseline = in.execution(j, "baseline");
      x.ours.planning_times_s = in.times(measured, "planning_ms");
      x.baseline.planning_times_s = in.times(measured, "baseline_planning_ms");
      if (j.contains("risk_aware")) {
        x.risk_aware = in.execution(j, "risk_aware");
        x.risk_aware->planning_times_s = in.times(measured, "risk_aware_planning_ms");
      }
      r.result = std::move(x);
    }
    return r;
  } catch (const Reader::Bad& bad) {
    return Error{ErrorCode::kParse, bad.message};
  }
}

bool CampaignSpec::same_campaign(const CampaignSpec& o) const {
  return map_fingerprint == o.map_fingerprint && mission_fingerprint == o.mission_fingerprint &&
         seed == o.seed && runs == o.runs && rates == o.rates && push_allowed == o.push_allowed &&
         planner_time_limit_s == o.planner_time_limit_s && shard_count == o.shard_count &&
         condition_fingerprint == o.condition_fingerprint && risk == o.risk &&
         faults_from_condition == o.faults_from_condition;
}

std::string fingerprint(std::string_view bytes) {
  std::uint64_t h = 0xCBF29CE484222325ULL;
  for (char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001B3ULL;
  }
  char out[17];
  std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
  return out;
}

std::string campaign_json(const CampaignSpec& s) {
  Json j;
  j["format"] = std::string(kCampaignJsonFormat);
  j["version"] = kCampaignJsonVersion;
  j["map"] = s.map_name;
  j["mission"] = s.mission_name;
  j["map_fingerprint"] = s.map_fingerprint;
  j["mission_fingerprint"] = s.mission_fingerprint;
  j["seed"] = std::to_string(s.seed);
  j["runs"] = s.runs;
  j["fault_rates"] =
      Json{{"obstacles", s.rates.obstacles_per_km}, {"danger", s.rates.danger_per_km},
           {"passages", s.rates.passage_share},     {"malfunctions", s.rates.malfunctions_per_hour},
           {"permanent", s.rates.permanent_share},  {"transient", s.rates.transient_share}};
  j["push_allowed"] = s.push_allowed;
  if (s.planner_time_limit_s > 0) j["planner_time_limit_s"] = s.planner_time_limit_s;
  if (!s.condition_name.empty()) {
    j["condition"] = s.condition_name;
    j["condition_fingerprint"] = s.condition_fingerprint;
  }
  if (s.risk != "impassable") j["risk"] = s.risk;
  if (s.faults_from_condition) j["faults_from_condition"] = true;
  j["shard"] = Json{{"index", s.shard_index}, {"count", s.shard_count}};
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

Result<CampaignSpec> parse_campaign_json(std::string_view text, const std::string& file_name) {
  const Json j = Json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) {
    return Error{ErrorCode::kParse, file_name + ": not a JSON object"};
  }
  Reader in(file_name);
  try {
    if (in.get<std::string>(j, "format", "$") != kCampaignJsonFormat) {
      throw Reader::Bad{file_name + ": $.format: not '" + std::string(kCampaignJsonFormat) + "'"};
    }
    if (in.get<std::size_t>(j, "version", "$") != kCampaignJsonVersion) {
      throw Reader::Bad{file_name + ": $.version: unsupported version"};
    }
    CampaignSpec s;
    s.map_name = in.get<std::string>(j, "map", "$");
    s.mission_name = in.get<std::string>(j, "mission", "$");
    s.map_fingerprint = in.get<std::string>(j, "map_fingerprint", "$");
    s.mission_fingerprint = in.get<std::string>(j, "mission_fingerprint", "$");
    s.seed = in.seed(j, "$");
    s.runs = in.get<std::size_t>(j, "runs", "$");
    const Json& r = in.at(j, "fault_rates", "$");
    s.rates.obstacles_per_km = in.get<double>(r, "obstacles", "$.fault_rates");
    s.rates.danger_per_km = in.get<double>(r, "danger", "$.fault_rates");
    s.rates.passage_share = in.get<double>(r, "passages", "$.fault_rates");
    s.rates.malfunctions_per_hour = in.get<double>(r, "malfunctions", "$.fault_rates");
    s.rates.permanent_share = in.get<double>(r, "permanent", "$.fault_rates");
    s.rates.transient_share = in.get<double>(r, "transient", "$.fault_rates");
    s.push_allowed = in.get<bool>(j, "push_allowed", "$");
    if (j.contains("planner_time_limit_s")) {
      s.planner_time_limit_s = in.get<double>(j, "planner_time_limit_s", "$");
    }
    if (j.contains("condition")) {
      s.condition_name = in.get<std::string>(j, "condition", "$");
      s.condition_fingerprint = in.get<std::string>(j, "condition_fingerprint", "$");
    }
    if (j.contains("risk")) s.risk = in.get<std::string>(j, "risk", "$");
    if (j.contains("faults_from_condition")) {
      s.faults_from_condition = in.get<bool>(j, "faults_from_condition", "$");
    }
    const Json& shard = in.at(j, "shard", "$");
    s.shard_index = in.get<std::size_t>(shard, "index", "$.shard");
    s.shard_count = in.get<std::size_t>(shard, "count", "$.shard");
    if (s.shard_count == 0 || s.shard_index >= s.shard_count) {
      throw Reader::Bad{file_name + ": $.shard: index must be below count"};
    }
    return s;
  } catch (const Reader::Bad& bad) {
    return Error{ErrorCode::kParse, bad.message};
  }
}

Result<std::pair<std::size_t, std::size_t>> parse_shard(std::string_view text) {
  const std::size_t slash = text.find('/');
  auto number = [](std::string_view s) -> std::optional<std::size_t> {
    if (s.empty() || s.size() > 9) return std::nullopt;
    std::size_t v = 0;
    for (char c : s) {
      if (c < '0' || c > '9') return std::nullopt;
      v = v * 10 + static_cast<std::size_t>(c - '0');
    }
    return v;
  };
  const auto i = slash == std::string_view::npos ? std::nullopt : number(text.substr(0, slash));
  const auto n = slash == std::string_view::npos ? std::nullopt : number(text.substr(slash + 1));
  if (!i || !n || *n == 0 || *i >= *n) {
    return Error{ErrorCode::kInvalidArgument,
                 "--shard: expected I/N with 0 <= I < N, got '" + std::string(text) + "'"};
  }
  return std::pair{*i, *n};
}

std::string reproduce_command(const CampaignSpec& s, std::size_t run) {
  std::ostringstream out;
  out << "sewerplan campaign --map " << s.map_name << " --mission " << s.mission_name << " --runs "
      << s.runs << " --seed " << s.seed << " --fault-rates " << format_fault_rates(s.rates)
      << (s.push_allowed ? " --allow-push" : "");
  if (s.planner_time_limit_s > 0) out << " --planner-time-limit " << s.planner_time_limit_s;
  if (!s.condition_name.empty()) out << " --condition " << s.condition_name;
  if (s.risk != "impassable") out << " --risk " << s.risk;
  if (s.faults_from_condition) out << " --faults-from-condition";
  out << " --only " << run;
  return out.str();
}

}  // namespace sewerplan::campaign
