// SPDX-License-Identifier: MIT
// Run records and campaign specs as JSON (record.h).
#include "sewerplan/campaign/record.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "sewerplan/core/enum_names.h"
#include "sewerplan/core/json_fields.h"

namespace sewerplan::campaign {
namespace {

// A run's "status" in runs.jsonl, written and read here.
constexpr detail::EnumNames<RunRecord::Status, 3> kStatuses{{
    {RunRecord::Status::kOk, "ok"},
    {RunRecord::Status::kCrash, "crash"},
    {RunRecord::Status::kHang, "hang"},
}};
static_assert(detail::distinct(kStatuses));

using Json = nlohmann::ordered_json;

double ms(double seconds) { return std::round(seconds * 1e6) / 1e3; }

// The kinds with anything to count, by name (read_by_kind reads it back).
Json by_kind_json(const ScoresByKind& by_kind) {
  Json j = Json::object();
  for (std::size_t i = 0; i < by_kind.size(); ++i) {
    const KindScore& k = by_kind[i];
    if (k == KindScore{}) continue;
    j[std::string(to_string(static_cast<Discrepancy::Kind>(i)))] =
        Json{{"in_reach", k.in_reach},
             {"found", k.found},
             {"reported", k.reported},
             {"false_reports", k.false_reports}};
  }
  return j;
}

Json execution_json(const Execution& e) {
  Json j{{"tasks", e.tasks},
         {"outcome", std::string(to_string(e.outcome))},
         {"end", e.end},
         {"reserve_kept", e.reserve_kept}};
  // Only when true, so records of runs that never needed it stay as they were.
  if (e.exit_on_reserve) j["exit_on_reserve"] = true;
  j["replans"] = e.replans;
  if (e.strand_risk > 0) j["strand_risk"] = e.strand_risk;
  j["time_s"] = e.time_s;
  j["energy_wh"] = e.energy_wh;
  j["disabled"] = e.disabled;
  j["beacon_cause"] = std::string(executor::to_string(e.beacon_cause));
  // The rungs that answered (issue 34), by name; those that never did are left out.
  Json rungs = Json::object();
  for (std::size_t r = 0; r < e.rungs.size(); ++r) {
    if (e.rungs[r] == 0) continue;
    rungs[std::string(executor::to_string(static_cast<executor::PlanResponse::Rung>(r)))] =
        e.rungs[r];
  }
  j["rungs"] = std::move(rungs);
  // The hazards observed (issue 34), pipes by index as in "world"; only when there were any, so
  // records of campaigns without condition data stay as they were.
  if (!e.hazards.empty()) {
    Json hazards = Json::array();
    for (const executor::HazardBelief& h : e.hazards) {
      hazards.push_back(Json{{"pipe", h.pipe.value()},
                             {"offset_m", h.offset_m},
                             {"reason", h.reason},
                             {"passes", h.passes},
                             {"blocked", h.blocked},
                             {"probability", h.probability}});
    }
    j["hazards"] = std::move(hazards);
  }
  if (e.world) {
    // The counts are read back; the shares are written for a reader (null: nothing to share).
    const WorldScore& w = *e.world;
    const auto share = [](std::size_t part, std::size_t whole) {
      const std::optional<double> p = percent(part, whole);
      return p ? Json(*p) : Json();
    };
    j["localisation"] = Json{{"arrivals", w.arrivals},
                             {"correct_arrivals", w.correct_arrivals},
                             {"correct_arrivals_pct", share(w.correct_arrivals, w.arrivals)}};
    j["corrected_map"] =
        Json{{"pipes_measured", w.pipes_measured},
             {"length_rms_pct", w.pipes_measured > 0 ? Json(w.length_rms_pct) : Json()},
             {"seeded_in_reach", w.seeded_in_reach},
             {"found", w.found},
             {"discrepancies_found_pct", share(w.found, w.seeded_in_reach)},
             {"reported", w.reported},
             {"false_reports", w.false_reports},
             {"false_reports_pct", share(w.false_reports, w.reported)},
             {"by_kind", by_kind_json(w.by_kind)}};
  }
  return j;
}

Json planning_json(const Execution& e) {
  Json list = Json::array();
  for (double t : e.planning_times_s) list.push_back(ms(t));
  return list;
}

constexpr auto kOptional = JsonFields::Need::kOptional;
// Durations beyond this (about 31,700 years) are no run's: errors, also so that the writer's
// rounding (x 1e4, x 1e6) stays finite and a record reads back as written.
constexpr double kMaxDuration_s = 1e12;

// A duration in seconds, 0 to kMaxDuration_s.
std::optional<double> read_duration(JsonFields& f, std::string_view key) {
  const std::optional<double> v = f.number(key);
  if (!v) return std::nullopt;
  if (!(*v >= 0 && *v <= kMaxDuration_s)) {
    f.error(key, "out of range: a duration of 0 to 1e12 s, got " + format_double(*v));
    return std::nullopt;
  }
  return *v;
}
// Counts beyond this are no campaign's (a double holds every whole number up to it exactly).
constexpr std::uint64_t kMaxCount = std::uint64_t{1} << 53;

// The fields of an object inside `parent`, reported under its JSON path; nullopt if it is missing
// or not an object (reported).
std::optional<JsonFields> object_in(JsonFields& parent, std::string_view key,
                                    std::string_view file) {
  const std::optional<JsonElement> e = parent.member(key);
  if (!e) return std::nullopt;
  JsonFields f(*e, parent.path() + "." + std::string(key), file, parent.diagnostics());
  if (!f.is_object()) return std::nullopt;
  return f;
}

// Seeds are written as text: JSON numbers lose digits past 2^53.
std::uint64_t read_seed(JsonFields& f) {
  const std::optional<std::string> text = f.string("seed");
  if (!text) return 0;
  std::uint64_t v = 0;
  const char* end = text->data() + text->size();
  const auto [stop, ec] = std::from_chars(text->data(), end, v);
  if (text->empty() || ec != std::errc{} || stop != end) {
    f.error("seed", "expected an unsigned integer (as text), got '" + *text + "'");
  }
  return v;
}

// "localisation" and "corrected_map" of an execution (execution_json); the shares are derived.
void read_by_kind(JsonFields& kinds, WorldScore& w, std::string_view file) {
  kinds.warn_unknown(
      [](std::string_view name) { return parse_discrepancy_kind(name).has_value(); });
  for (std::size_t i = 0; i < w.by_kind.size(); ++i) {
    const std::string_view name = to_string(static_cast<Discrepancy::Kind>(i));
    if (!kinds.has(name)) continue;
    std::optional<JsonFields> f = object_in(kinds, name, file);
    if (!f) continue;
    KindScore& k = w.by_kind[i];
    k.in_reach = f->count("in_reach", kMaxCount).value_or(0);
    k.found = f->count("found", kMaxCount).value_or(0);
    k.reported = f->count("reported", kMaxCount).value_or(0);
    k.false_reports = f->count("false_reports", kMaxCount).value_or(0);
    if (k.found > k.in_reach) {
      f->error("found", "more than in_reach (" + std::to_string(k.in_reach) + ")");
    }
    if (k.false_reports > k.reported) {
      f->error("false_reports", "more than reported (" + std::to_string(k.reported) + ")");
    }
  }
}

WorldScore read_world_score(JsonFields& execution, std::string_view file) {
  WorldScore w;
  if (std::optional<JsonFields> l = object_in(execution, "localisation", file)) {
    w.arrivals = l->count("arrivals", kMaxCount).value_or(0);
    w.correct_arrivals = l->count("correct_arrivals", kMaxCount).value_or(0);
    if (w.correct_arrivals > w.arrivals) {
      l->error("correct_arrivals", "more than the arrivals (" + std::to_string(w.arrivals) + ")");
    }
  }
  if (std::optional<JsonFields> c = object_in(execution, "corrected_map", file)) {
    w.pipes_measured = c->count("pipes_measured", kMaxCount).value_or(0);
    if (w.pipes_measured > 0) {
      w.length_rms_pct = c->number("length_rms_pct").value_or(0);
      if (!(w.length_rms_pct >= 0 && w.length_rms_pct <= 1e9)) {
        c->error("length_rms_pct",
                 "out of range: 0 to 1e9, got " + format_double(w.length_rms_pct));
      }
    }
    w.seeded_in_reach = c->count("seeded_in_reach", kMaxCount).value_or(0);
    w.found = c->count("found", kMaxCount).value_or(0);
    w.reported = c->count("reported", kMaxCount).value_or(0);
    w.false_reports = c->count("false_reports", kMaxCount).value_or(0);
    if (w.found > w.seeded_in_reach) {
      c->error("found", "more than seeded_in_reach (" + std::to_string(w.seeded_in_reach) + ")");
    }
    if (w.false_reports > w.reported) {
      c->error("false_reports", "more than reported (" + std::to_string(w.reported) + ")");
    }
    // Lines written before the kinds were counted have none: their kinds stay at zero.
    if (c->has("by_kind")) {
      if (std::optional<JsonFields> kinds = object_in(*c, "by_kind", file)) {
        read_by_kind(*kinds, w, file);
      }
    }
  }
  return w;
}

Execution read_execution(JsonFields& run, std::string_view key, std::string_view file) {
  Execution x;
  std::optional<JsonFields> f = object_in(run, key, file);
  if (!f) return x;
  x.tasks = f->count("tasks", kMaxCount).value_or(0);
  if (const std::optional<std::string> name = f->string("outcome")) {
    if (const std::optional<Outcome> outcome = outcome_from_string(*name)) {
      x.outcome = *outcome;
    } else {
      f->error("outcome", "unknown outcome '" + *name + "'");
    }
  }
  x.end = f->string("end").value_or("");
  x.reserve_kept = f->boolean("reserve_kept").value_or(false);
  x.exit_on_reserve = f->boolean("exit_on_reserve", kOptional).value_or(false);
  x.replans = f->count("replans", kMaxCount).value_or(0);
  x.strand_risk = f->number("strand_risk", kOptional).value_or(0);
  x.time_s = f->number("time_s").value_or(0);
  x.energy_wh = f->number("energy_wh").value_or(0);
  x.disabled = f->boolean("disabled").value_or(false);
  // Only ours with world errors is scored (world_score.h); records without have neither object.
  if (f->has("localisation") || f->has("corrected_map")) x.world = read_world_score(*f, file);
  // Records written before the rungs were counted have none (all 0).
  if (std::optional<JsonFields> rungs =
          f->has("rungs") ? object_in(*f, "rungs", file) : std::nullopt) {
    for (std::size_t r = 0; r < x.rungs.size(); ++r) {
      const std::string name(executor::to_string(static_cast<executor::PlanResponse::Rung>(r)));
      x.rungs[r] = rungs->count(name, kMaxCount, kOptional).value_or(0);
    }
    rungs->reject_unknown(
        {"search", "best-so-far", "current-plan", "repaired-plan", "greedy", "nearest-exit"});
  }
  // Records written before hazards were recorded, or of campaigns without any, have none.
  if (const std::optional<JsonArray> list = f->array("hazards", kOptional)) {
    std::size_t i = 0;
    for (JsonElement e : *list) {
      JsonFields h(e, indexed(f->path() + ".hazards", i++), file, f->diagnostics());
      h.reject_unknown({"pipe", "offset_m", "reason", "passes", "blocked", "probability"});
      executor::HazardBelief b;
      b.pipe = PipeId{static_cast<std::uint32_t>(h.count("pipe", 0xffffffffU).value_or(0))};
      b.offset_m = h.number("offset_m").value_or(0);
      b.reason = h.string("reason").value_or("");
      b.passes = h.count("passes", kMaxCount).value_or(0);
      b.blocked = h.boolean("blocked").value_or(false);
      b.probability = h.number("probability").value_or(0);
      if (!(b.offset_m >= 0))
        h.error("offset_m", "must be 0 or more, got " + format_double(b.offset_m));
      if (!(b.probability >= 0 && b.probability <= 1)) {
        h.error("probability",
                "must be a probability from 0 to 1, got " + format_double(b.probability));
      }
      x.hazards.push_back(std::move(b));
    }
  }
  // Records written before beacons had causes have none.
  if (const std::optional<std::string> name = f->string("beacon_cause", kOptional)) {
    if (const auto cause = executor::parse_beacon_cause(*name)) {
      x.beacon_cause = *cause;
    } else {
      f->error("beacon_cause", "unknown cause '" + *name + "'");
    }
  }
  return x;
}

// Planning times, written in milliseconds.
std::vector<double> read_times_s(JsonFields& measured, std::string_view key) {
  std::vector<double> out;
  const std::optional<JsonArray> list = measured.array(key);
  if (!list) return out;
  std::size_t i = 0;
  for (JsonElement v : *list) {
    double ms_value = 0;
    if (v.get_double().get(ms_value) != simdjson::SUCCESS) {
      measured.diagnostics().error(indexed(measured.where(key), i),
                                   "expected a number, got " + describe_json(v));
    } else if (!(ms_value >= 0 && ms_value / 1e3 <= kMaxDuration_s)) {
      measured.diagnostics().error(
          indexed(measured.where(key), i),
          "out of range: a duration of 0 to 1e15 ms, got " + format_double(ms_value));
    }
    out.push_back(ms_value / 1e3);
    ++i;
  }
  return out;
}

// The seeded discrepancies of a run's true world ("world": {"seeded": [...]}, run_json_line).
std::vector<Discrepancy> read_seeded(JsonFields& f, std::string_view file) {
  std::vector<Discrepancy> out;
  std::optional<JsonFields> world = object_in(f, "world", file);
  if (!world) return out;
  const std::optional<JsonArray> list = world->array("seeded");
  if (!list) return out;
  std::size_t i = 0;
  for (JsonElement e : *list) {
    JsonFields d(e, world->path() + ".seeded[" + std::to_string(i++) + "]", file, f.diagnostics());
    Discrepancy x;
    if (const std::optional<std::string> kind = d.string("kind")) {
      if (const auto k = parse_discrepancy_kind(*kind)) {
        x.kind = *k;
      } else {
        d.error("kind", "unknown discrepancy '" + *kind + "'");
      }
    }
    if (const auto p = d.count("pipe", 0xffffffffU, kOptional)) {
      x.pipe = PipeId{static_cast<std::uint32_t>(*p)};
    }
    if (const auto m = d.count("manhole", 0xffffffffU, kOptional)) {
      x.manhole = ManholeId{static_cast<std::uint32_t>(*m)};
    }
    if (const auto s = d.count("slot", 0xffffU, kOptional)) {
      x.slot = SlotIndex{static_cast<std::uint16_t>(*s)};
    }
    x.offset_m = d.number("offset_m", kOptional).value_or(0);
    x.map_value = d.number("map_value", kOptional).value_or(0);
    x.value = d.number("value", kOptional).value_or(0);
    out.push_back(x);
  }
  return out;
}

RunResult read_result(const RunRecord& r, JsonFields& f, JsonFields& measured,
                      std::string_view file) {
  RunResult x;
  x.index = r.index;
  x.seed = r.seed;
  x.wall_s = r.wall_s;
  x.tasks = f.count("tasks", kMaxCount).value_or(0);
  if (std::optional<JsonFields> faults = object_in(f, "faults", file)) {
    FaultCounts& c = x.faults;
    for (auto [key, field] : {std::pair{"obstacles", &c.obstacles},
                              {"permanent_obstacles", &c.permanent_obstacles},
                              {"danger_spots", &c.danger_spots},
                              {"dangerous_passages", &c.dangerous_passages},
                              {"malfunctions", &c.malfunctions},
                              {"permanent_malfunctions", &c.permanent_malfunctions}}) {
      *field = faults->count(key, kMaxCount).value_or(0);
    }
  }
  if (std::optional<JsonFields> oracle = object_in(f, "oracle", file)) {
    x.oracle_tasks = oracle->count("tasks", kMaxCount).value_or(0);
    x.oracle_can_end = oracle->boolean("can_end").value_or(false);
  }
  x.could_reach_exit = f.boolean("could_reach_exit").value_or(false);
  x.ours = read_execution(f, "ours", file);
  x.baseline = read_execution(f, "baseline", file);
  x.ours.planning_times_s = read_times_s(measured, "planning_ms");
  x.baseline.planning_times_s = read_times_s(measured, "baseline_planning_ms");
  if (f.has("risk_aware")) {
    x.risk_aware = read_execution(f, "risk_aware", file);
    x.risk_aware->planning_times_s = read_times_s(measured, "risk_aware_planning_ms");
  }
  if (f.has("world")) x.seeded = read_seeded(f, file);
  return x;
}

}  // namespace

std::string_view to_string(RunRecord::Status status) { return detail::name_of(kStatuses, status); }

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
    // How the run's true world differs from its map, by the map's object indices (0-based), for a
    // scorer of the robot's reports (docs/campaign.md). Only with world errors.
    if (!r->seeded.empty()) {
      Json seeded = Json::array();
      for (const Discrepancy& d : r->seeded) {
        Json one{{"kind", std::string(to_string(d.kind))}};
        if (d.pipe) one["pipe"] = d.pipe->value();
        if (d.manhole) one["manhole"] = d.manhole->value();
        if (d.slot) one["slot"] = d.slot->value();
        if (d.kind == Discrepancy::Kind::kUnmappedJunction) one["offset_m"] = d.offset_m;
        if (d.map_value != 0) one["map_value"] = d.map_value;
        if (d.value != 0) one["value"] = d.value;
        seeded.push_back(std::move(one));
      }
      j["world"] = Json{{"seeded", std::move(seeded)}};
    }
  }
  j["measured"] = measured;
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

Result<RunRecord> parse_run_line(std::string_view line, const std::string& file_name,
                                 std::size_t line_number) {
  JsonLineParser parser;
  return parse_run_line(line, file_name, line_number, parser);
}

Result<RunRecord> parse_run_line(std::string_view line, const std::string& file_name,
                                 std::size_t line_number, JsonLineParser& parser) {
  const std::string where = file_name + ":" + std::to_string(line_number);
  const std::optional<JsonElement> j = parser.parse(line);
  if (!j || !j->is_object()) return Error{ErrorCode::kParse, where + ": not a JSON object"};
  Diagnostics d;
  JsonFields f(*j, "$", where, d);
  RunRecord r;
  r.index = f.count("run", kMaxCount).value_or(0);
  r.seed = read_seed(f);
  if (const std::optional<std::string> status = f.string("status")) {
    if (const std::optional<RunRecord::Status> s = detail::value_of(kStatuses, *status)) {
      r.status = *s;
    } else {
      f.error("status", "unknown status '" + *status + "'");
    }
  }
  r.detail = f.string("detail", kOptional).value_or("");
  if (std::optional<JsonFields> measured = object_in(f, "measured", where)) {
    r.wall_s = read_duration(*measured, "wall_s").value_or(0);
    if (r.status == RunRecord::Status::kOk) r.result = read_result(r, f, *measured, where);
  }
  if (d.has_errors()) return Error{ErrorCode::kParse, d.error_summary()};
  return r;
}

bool CampaignSpec::same_campaign(const CampaignSpec& o) const {
  return map_fingerprint == o.map_fingerprint && mission_fingerprint == o.mission_fingerprint &&
         seed == o.seed && runs == o.runs && rates == o.rates && push_allowed == o.push_allowed &&
         planner_time_limit_s == o.planner_time_limit_s && max_strand_risk == o.max_strand_risk &&
         shard_count == o.shard_count && condition_fingerprint == o.condition_fingerprint &&
         risk == o.risk && faults_from_condition == o.faults_from_condition &&
         world_errors == o.world_errors;
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
  if (s.max_strand_risk > 0) j["max_strand_risk"] = s.max_strand_risk;
  if (!s.condition_name.empty()) {
    j["condition"] = s.condition_name;
    j["condition_fingerprint"] = s.condition_fingerprint;
  }
  if (s.risk != "impassable") j["risk"] = s.risk;
  if (s.faults_from_condition) j["faults_from_condition"] = true;
  if (s.world_errors != "none") j["world_errors"] = s.world_errors;
  j["shard"] = Json{{"index", s.shard_index}, {"count", s.shard_count}};
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

Result<CampaignSpec> parse_campaign_json(std::string_view text, const std::string& file_name) {
  Diagnostics d;
  std::optional<JsonDocument> doc = JsonDocument::parse(text, file_name, d);
  if (!doc) return Error{ErrorCode::kParse, d.error_summary()};
  JsonFields f(doc->root(), "$", file_name, d);
  if (!f.is_object()) return Error{ErrorCode::kParse, d.error_summary()};
  if (const auto format = f.string("format"); format && *format != kCampaignJsonFormat) {
    f.error("format", "expected '" + std::string(kCampaignJsonFormat) + "', got '" + *format + "'");
  }
  if (const auto version = f.count("version", kMaxCount);
      version && *version != kCampaignJsonVersion) {
    f.error("version", "unsupported version " + std::to_string(*version) +
                           " (this sewerplan reads " + std::to_string(kCampaignJsonVersion) + ")");
  }
  if (d.has_errors()) return Error{ErrorCode::kParse, d.error_summary()};
  CampaignSpec s;
  s.map_name = f.string("map").value_or("");
  s.mission_name = f.string("mission").value_or("");
  s.map_fingerprint = f.string("map_fingerprint").value_or("");
  s.mission_fingerprint = f.string("mission_fingerprint").value_or("");
  s.seed = read_seed(f);
  s.runs = f.count("runs", kMaxCount).value_or(0);
  if (std::optional<JsonFields> r = object_in(f, "fault_rates", file_name)) {
    FaultRates& rates = s.rates;
    for (auto [key, field] : {std::pair{"obstacles", &rates.obstacles_per_km},
                              {"danger", &rates.danger_per_km},
                              {"passages", &rates.passage_share},
                              {"malfunctions", &rates.malfunctions_per_hour},
                              {"permanent", &rates.permanent_share},
                              {"transient", &rates.transient_share}}) {
      *field = r->number(key).value_or(0);
    }
  }
  s.push_allowed = f.boolean("push_allowed").value_or(false);
  s.planner_time_limit_s = f.number("planner_time_limit_s", kOptional).value_or(0);
  s.max_strand_risk = f.number("max_strand_risk", kOptional).value_or(0);
  if (!(s.max_strand_risk >= 0 && s.max_strand_risk <= 1)) {
    f.error("max_strand_risk", "not a probability: a number from 0 to 1");
  }
  if (f.has("condition")) {
    s.condition_name = f.string("condition").value_or("");
    s.condition_fingerprint = f.string("condition_fingerprint").value_or("");
  }
  if (const auto risk = f.string("risk", kOptional)) s.risk = *risk;
  s.faults_from_condition = f.boolean("faults_from_condition", kOptional).value_or(false);
  if (const auto world = f.string("world_errors", kOptional)) {
    s.world_errors = *world;
    if (Result<hal::WorldErrorProfile> p = hal::parse_world_errors(*world); !p.has_value()) {
      f.error("world_errors", p.error().message);
    }
  }
  if (std::optional<JsonFields> shard = object_in(f, "shard", file_name)) {
    const std::optional<std::uint64_t> index = shard->count("index", kMaxCount);
    const std::optional<std::uint64_t> count = shard->count("count", kMaxCount);
    if (index && count && (*count == 0 || *index >= *count)) {
      f.error("shard", "index must be below count");
    }
    s.shard_index = index.value_or(0);
    s.shard_count = count.value_or(1);
  }
  if (d.has_errors()) return Error{ErrorCode::kParse, d.error_summary()};
  return s;
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
  if (s.max_strand_risk > 0) out << " --max-strand-risk " << s.max_strand_risk;
  if (!s.condition_name.empty()) out << " --condition " << s.condition_name;
  if (s.risk != "impassable") out << " --risk " << s.risk;
  if (s.faults_from_condition) out << " --faults-from-condition";
  if (s.world_errors != "none") out << " --world-errors " << s.world_errors;
  out << " --only " << run;
  return out.str();
}

}  // namespace sewerplan::campaign
