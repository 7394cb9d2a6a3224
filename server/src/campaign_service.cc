// SPDX-License-Identifier: MIT
#include "campaign_service.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <charconv>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "sewerplan/campaign/campaign.h"
#include "sewerplan/campaign/record.h"
#include "sewerplan/campaign/run.h"
#include "sewerplan/campaign/summary.h"
#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/message_text.h"
#include "sewerplan/core/stop_condition.h"
#include "sewerplan/executor/event_json.h"

#include "http_reply.h"
#include "json_body.h"
#include "plan_route.h"

namespace sewerplan::server {

struct CampaignService::Running {
  std::shared_ptr<const SewerMap> map;  // kept while the campaign runs
  Mission mission;
  campaign::CampaignSpec spec;
  std::size_t jobs = 1;          // asked for
  std::size_t running_jobs = 1;  // run with (campaign::campaign_jobs)
  double timeout_s = 60;         // before a guarded run counts as hung
  std::atomic<bool> cancel{false};
  // Guarded by the service's mutex: what the campaign's thread hands to the stream's.
  Json progress;             // the last "progress" event
  std::deque<Json> pending;  // "progress" events not yet written, the newest kMaxPending
  std::shared_ptr<const Finished> finished;  // set when the campaign has ended
  std::condition_variable changed;           // a progress event, or the end
};

struct CampaignService::Finished {
  std::shared_ptr<const SewerMap> map;
  Mission mission;
  campaign::CampaignSpec spec;
  std::vector<campaign::RunRecord> records;
  Json document;  // {"state", "map", "summary", "runs"}, or {"state": "error", "error"}
};

namespace {

// A stream's reader this many progress events behind misses the oldest (each carries the totals so
// far, so the newest says all): a stalled browser costs bounded memory, and holds up no run.
constexpr std::size_t kMaxPending = 256;

const std::initializer_list<std::string_view> kFields = {"mission",
                                                         "runs",
                                                         "seed",
                                                         "fault_rates",
                                                         "jobs",
                                                         "allow_push",
                                                         "planner_time_limit_s",
                                                         "risk",
                                                         "faults_from_condition",
                                                         "timeout_s"};
constexpr double kMaxPlannerTimeLimitS = 86400;  // as the CLI's --planner-time-limit
constexpr std::array<std::string_view, 6> kRateNames = {"obstacles",    "danger",    "passages",
                                                        "malfunctions", "permanent", "transient"};

// What a request asks beyond its mission; an error names the field that is wrong.
struct CampaignRequest {
  std::size_t runs = 100;
  std::uint64_t seed = 1;
  campaign::FaultRates rates;
  std::size_t jobs = 1;
  bool push_allowed = false;
  double planner_time_limit_s = 0;  // 0: none
  double timeout_s = 60;            // as the CLI's --timeout
  RiskMode risk = RiskMode::kImpassable;
  std::string risk_name = "impassable";
  bool faults_from_condition = false;
};

std::string shortened(std::string_view text) {
  return std::string(text.substr(0, 64)) + (text.size() > 64 ? "..." : "");
}

// A whole number from `min` to `max` (or its decimal text, for seeds beyond 2^53), or nothing.
std::optional<std::uint64_t> whole(JsonElement v, std::uint64_t min, std::uint64_t max) {
  std::uint64_t n = 0;
  std::string_view text;
  if (v.get_string().get(text) == simdjson::SUCCESS) {
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
    if (ec != std::errc{} || end != text.data() + text.size() || text.empty()) return std::nullopt;
  } else if (v.get_uint64().get(n) != simdjson::SUCCESS) {
    return std::nullopt;
  }
  if (n < min || n > max) return std::nullopt;
  return n;
}

// Seconds from `min` (over it, unless `min_included`) to kMaxPlannerTimeLimitS, or nothing.
std::optional<double> seconds(JsonElement v, double min, bool min_included) {
  double s = 0;
  if (!v.is_number() || v.get_double().get(s) != simdjson::SUCCESS) return std::nullopt;
  if (!(min_included ? s >= min : s > min) || !(s <= kMaxPlannerTimeLimitS)) return std::nullopt;
  return s;
}

// "fault_rates" (in `f`): the CLI's text ("obstacles=20,danger=5") or an object of the same names.
std::optional<campaign::FaultRates> read_rates(JsonFields& f) {
  const JsonElement v = *f.member("fault_rates");
  std::string text;
  simdjson::dom::object object;
  std::string_view given;
  if (v.get_string().get(given) == simdjson::SUCCESS) {
    text = given;
  } else if (v.get_object().get(object) == simdjson::SUCCESS) {
    const Diagnostics::Mark before = f.diagnostics().mark();
    JsonFields rates(v, f.path() + ".fault_rates", kBodyFile, f.diagnostics());
    for (const simdjson::dom::key_value_pair rate : object) {
      const std::string_view name = rate.key;
      if (std::find(kRateNames.begin(), kRateNames.end(), name) == kRateNames.end()) {
        rates.error(name, "unknown rate " + input_quoted(name, 64) +
                              " (expected obstacles, danger, passages, malfunctions, permanent, "
                              "transient)");
      } else if (const std::optional<double> value = rates.number(name)) {
        text += (text.empty() ? "" : ",") + std::string(name) + "=" + format_double(*value);
      }
    }
    if (f.diagnostics().has_errors_since(before)) return std::nullopt;
  } else {
    f.error("fault_rates",
            "expected an object {\"obstacles\": 20, ...} or its text, got " + describe_json(v));
    return std::nullopt;
  }
  Result<campaign::FaultRates> rates = campaign::parse_fault_rates(text);
  if (!rates.has_value()) {
    std::string message = rates.error().message;
    if (message.starts_with("--fault-rates: ")) message.erase(0, 15);
    f.error("fault_rates", message);
    return std::nullopt;
  }
  return *rates;
}

// The request's fields beside its mission, read with the file readers' JsonFields: every field
// that is wrong is named at its path ("body:$.runs: error: expected a whole number from 1 to
// 10000 (the station's limit)"), all of them in one 400.
Result<CampaignRequest> read_request(JsonElement body, const CampaignLimits& limits) {
  Diagnostics diagnostics;
  JsonFields f(body, "$", kBodyFile, diagnostics);
  CampaignRequest r;
  f.reject_unknown(kFields);
  using Need = JsonFields::Need;
  // Each optional field, if given, to `read`, which says what was wrong or nothing.
  const auto field = [&](std::string_view key, const auto& read) {
    if (const std::optional<JsonElement> v = f.member(key, Need::kOptional)) {
      if (const std::optional<std::string> wrong = read(*v)) {
        f.error(key, *wrong + ", got " + describe_json(*v));
      }
    }
  };
  using Wrong = std::optional<std::string>;
  field("runs", [&](JsonElement v) -> Wrong {
    const auto runs = whole(v, 1, limits.max_runs);
    if (runs) r.runs = *runs;
    return runs ? Wrong{}
                : "expected a whole number from 1 to " + std::to_string(limits.max_runs) +
                      " (the station's limit)";
  });
  field("seed", [&](JsonElement v) -> Wrong {
    const auto seed = whole(v, 0, UINT64_MAX);
    if (seed) r.seed = *seed;
    return seed ? Wrong{} : "expected a whole number from 0 (or its decimal text)";
  });
  field("jobs", [&](JsonElement v) -> Wrong {
    const auto jobs = whole(v, 1, limits.max_jobs);
    if (jobs) r.jobs = *jobs;
    return jobs ? Wrong{}
                : "expected 1 to " + std::to_string(limits.max_jobs) + " (the machine's cores)";
  });
  if (f.has("fault_rates")) {
    if (const std::optional<campaign::FaultRates> rates = read_rates(f)) r.rates = *rates;
  }
  r.push_allowed = f.boolean("allow_push", Need::kOptional).value_or(false);
  field("planner_time_limit_s", [&](JsonElement v) -> Wrong {
    const std::optional<double> s = seconds(v, 0, true);
    if (s) r.planner_time_limit_s = *s;
    return s ? Wrong{} : "expected seconds from 0 (no limit) to 86400";
  });
  field("timeout_s", [&](JsonElement v) -> Wrong {
    const std::optional<double> s = seconds(v, 0, false);
    if (s) r.timeout_s = *s;
    return s ? Wrong{} : "expected the seconds before a run counts as hung, over 0 up to 86400";
  });
  field("risk", [&](JsonElement v) -> Wrong {
    std::string_view name;
    const std::optional<RiskMode> mode =
        v.get_string().get(name) == simdjson::SUCCESS ? risk_mode_from_string(name) : std::nullopt;
    if (mode) {
      r.risk = *mode;
      r.risk_name = name;
    }
    return mode ? Wrong{} : "expected ignore, impassable, avoid or expected";
  });
  r.faults_from_condition = f.boolean("faults_from_condition", Need::kOptional).value_or(false);
  if (diagnostics.has_errors()) {
    return Error{ErrorCode::kInvalidArgument, diagnostics.error_summary()};
  }
  return r;
}

// The running tallies of a "progress" event: runs done, crashes and hangs, and ours so far.
struct Tally {
  std::array<std::size_t, 4> outcomes{};  // by campaign::Outcome
  std::size_t tasks = 0;
  std::size_t oracle_tasks = 0;

  void add(const campaign::RunRecord& r) {
    if (!r.result) return;
    ++outcomes[static_cast<std::size_t>(r.result->ours.outcome)];
    tasks += r.result->ours.tasks;
    oracle_tasks += r.result->oracle_tasks;
  }
};

Json progress_json(const campaign::Progress& p, const Tally& tally) {
  Json outcomes = Json::object();
  for (std::size_t o = 0; o < tally.outcomes.size(); ++o) {
    outcomes[std::string(campaign::to_string(static_cast<campaign::Outcome>(o)))] =
        tally.outcomes[o];
  }
  return {{"done", p.done},
          {"total", p.total},
          {"failed", p.failed},
          {"elapsed_s", p.elapsed_s},
          {"outcomes", outcomes},
          {"tasks", tally.tasks},
          {"oracle_tasks", tally.oracle_tasks}};
}

// The summary.json document, by the campaign library's own writer, and each run's line.
Json finished_json(const campaign::CampaignSpec& spec,
                   const std::vector<campaign::RunRecord>& records, bool cancelled) {
  std::ostringstream summary;
  campaign::write_summary_json(campaign::summarize(spec, records), summary);
  Json runs = Json::array();
  for (const campaign::RunRecord& r : records) runs.push_back(Json::parse(run_json_line(r)));
  return {{"state", cancelled ? "cancelled" : "done"},
          {"map", spec.map_name},
          {"total", spec.runs},
          {"summary", Json::parse(summary.str())},
          {"runs", std::move(runs)}};
}

// What the library runs a campaign with: its jobs, the guard, and the cancel flag as its stop.
campaign::CampaignOptions campaign_options(CampaignService::Running& running, bool guard) {
  campaign::CampaignOptions options;
  options.jobs = running.jobs;
  options.guard = guard;
  options.timeout_s = running.timeout_s;
  options.stop = StopCondition().with_cancel(running.cancel);
  return options;
}

bool same_but_measured(campaign::Execution a, campaign::Execution b) {
  a.planning_times_s.clear();
  b.planning_times_s.clear();
  return a == b;
}

}  // namespace

std::initializer_list<std::string_view> campaign_fields() { return kFields; }

void CampaignService::start(JsonElement body, std::shared_ptr<const SewerMap> map,
                            const std::string& map_id, Mission mission, httplib::Response& res) {
  std::shared_ptr<Running> running = begin(body, std::move(map), map_id, std::move(mission), res);
  if (!running) return;
  res.set_header("Cache-Control", "no-cache");
  res.set_chunked_content_provider(
      "text/event-stream",
      [this, running](std::size_t, httplib::DataSink& sink) {
        stream(running,
               [&sink](std::string_view text) { return sink.write(text.data(), text.size()); });
        sink.done();
        return true;
      },
      [this, running](bool) { release(running); });
}

std::shared_ptr<CampaignService::Running> CampaignService::begin(
    JsonElement body, std::shared_ptr<const SewerMap> map, const std::string& map_id,
    Mission mission, httplib::Response& res) {
  Result<CampaignRequest> request = read_request(body, limits_);
  if (!request.has_value()) {
    bad_request(res, request.error().message);
    return nullptr;
  }
  // Refused before the findings are weighed (a pass over the whole map), and again below when
  // the slot is taken.
  if (const std::optional<Error> busy = refusal(); busy) {
    send_error(res, kConflict, *busy);
    return nullptr;
  }
  // As `sewerplan campaign`: every policy plans with what the map's findings close; drawing
  // obstacles from the condition data needs its possible blockages (as hazards).
  const RiskMode planning = request->faults_from_condition && request->risk != RiskMode::kAvoid
                                ? RiskMode::kExpected
                                : request->risk;
  close_findings(*map, mission, planning, default_risk_table());
  if (request->faults_from_condition && mission.hazards.empty()) {
    bad_request(res,
                "campaign: faults_from_condition: the map's condition data has no possible "
                "blockage (upload its ISYBAU Zustandsdaten, POST /api/maps/ID/condition; risk "
                "avoid closes them all)");
    return nullptr;
  }
  auto running = std::make_shared<Running>();
  running->map = std::move(map);
  running->jobs = request->jobs;
  running->timeout_s = request->timeout_s;
  campaign::CampaignSpec& spec = running->spec;
  spec.map_name = map_id;
  spec.mission_name = mission.name;
  // Identities for merging shards, which the station does not write: the map's ID and the mission.
  spec.map_fingerprint = campaign::fingerprint(map_id);
  spec.mission_fingerprint = campaign::fingerprint(simdjson::minify(body["mission"]));
  spec.seed = request->seed;
  spec.runs = request->runs;
  spec.rates = request->rates;
  spec.push_allowed = request->push_allowed;
  spec.planner_time_limit_s = request->planner_time_limit_s;
  spec.risk = request->risk_name;
  spec.faults_from_condition = request->faults_from_condition;
  running->mission = std::move(mission);
  running->running_jobs = campaign::campaign_jobs(spec, campaign_options(*running, limits_.guard));
  {
    const std::lock_guard lock(mutex_);
    if (const std::optional<Error> busy = refusal_locked(); busy) {
      send_error(res, kConflict, *busy);
      return nullptr;
    }
    running_ = running;
    running->progress = {{"done", 0}, {"total", spec.runs}};
  }
  return running;
}

// The campaign runs on a thread of its own, whose progress callback only records (Running); this
// thread, the stream's, writes. A reader that stalls holds up only its own stream: the campaign
// goes on, a cancel stops it at once, and the station's slot is free when it ends.
void CampaignService::stream(const std::shared_ptr<Running>& running,
                             const std::function<bool(std::string_view)>& write) {
  bool reading = true;  // the reader is there: once a write fails, the campaign is cancelled
  const auto send = [&](std::string_view type, const Json& data) {
    if (!reading) return;
    const std::string message = "event: " + std::string(type) + "\ndata: " + dump(data) + "\n\n";
    if (!write(message)) {
      reading = false;
      running->cancel = true;
    }
  };
  // First, so that a reader that stalls on the first event holds up no run.
  std::thread campaign_thread([this, running] {
    Tally tally;
    campaign::CampaignOptions options = campaign_options(*running, limits_.guard);
    // On this thread, under no lock of the campaign library's (campaign.h): records only.
    options.progress = [&](const campaign::Progress& p) {
      if (p.last != nullptr) tally.add(*p.last);
      Json j = progress_json(p, tally);
      const std::lock_guard lock(mutex_);
      running->progress = j;
      if (running->pending.size() == kMaxPending) running->pending.pop_front();
      running->pending.push_back(std::move(j));
      running->changed.notify_all();
    };
    auto finished = std::make_shared<Finished>();
    finished->map = running->map;
    finished->mission = running->mission;
    finished->spec = running->spec;
    // Nothing thrown here may end the station (a thread that cannot be started, memory): the
    // stream ends with the error instead of waiting for a summary that never comes.
    try {
      std::vector<campaign::RunRecord> records =
          campaign::run_campaign(*running->map, running->mission, running->spec, options);
      finished->document = finished_json(running->spec, records, running->cancel.load());
      finished->records = std::move(records);
    } catch (const std::exception& e) {
      finished->document = {{"state", "error"},
                            {"map", running->spec.map_name},
                            {"total", running->spec.runs},
                            {"error", {{"message", std::string("campaign failed: ") + e.what()}}}};
    }
    finish(running, std::move(finished));
  });
  const campaign::CampaignSpec& spec = running->spec;
  send("start", {{"total", spec.runs},
                 {"jobs", running->running_jobs},
                 {"jobs_requested", running->jobs},
                 {"seed", std::to_string(spec.seed)},
                 {"fault_rates", campaign::format_fault_rates(spec.rates)},
                 {"planner_time_limit_s", spec.planner_time_limit_s},
                 {"risk", spec.risk},
                 {"faults_from_condition", spec.faults_from_condition},
                 {"timeout_s", running->timeout_s}});
  std::shared_ptr<const Finished> finished;
  while (!finished) {
    std::deque<Json> events;
    {
      std::unique_lock lock(mutex_);
      running->changed.wait(lock, [&] { return !running->pending.empty() || running->finished; });
      events.swap(running->pending);
      // Set after the campaign's last progress event: all of them are in `events` now.
      finished = running->finished;
    }
    for (const Json& e : events) send("progress", e);
  }
  campaign_thread.join();
  send(finished->document["state"] == "error" ? "error" : "summary", finished->document);
}

std::optional<Error> CampaignService::refusal() const {
  const std::lock_guard lock(mutex_);
  return refusal_locked();
}

std::optional<Error> CampaignService::refusal_locked() const {
  if (shut_down_) return Error{ErrorCode::kInvalidArgument, "the station is stopping"};
  if (running_) {
    return Error{ErrorCode::kInvalidArgument,
                 "a campaign is running (one at a time): cancel it (POST /api/campaign/cancel) "
                 "or wait for its summary"};
  }
  return std::nullopt;
}

void CampaignService::finish(const std::shared_ptr<Running>& running,
                             std::shared_ptr<const Finished> finished) {
  const std::lock_guard lock(mutex_);
  last_ = finished;
  running->finished = std::move(finished);
  running->changed.notify_all();
  if (running_ == running) running_ = nullptr;
}

// The stream is gone (or never started): its campaign no longer holds the station's one slot.
void CampaignService::release(const std::shared_ptr<Running>& running) {
  const std::lock_guard lock(mutex_);
  running->cancel = true;
  if (running_ == running) running_ = nullptr;
}

void CampaignService::cancel(httplib::Response& res) {
  const std::lock_guard lock(mutex_);
  if (!running_) {
    return send_error(res, kConflict, Error{ErrorCode::kInvalidArgument, "no campaign is running"});
  }
  running_->cancel = true;
  send_json(res, {{"cancelled", true}});
}

void CampaignService::status(httplib::Response& res) const {
  const std::lock_guard lock(mutex_);
  if (running_) {
    return send_json(
        res,
        {{"state", "running"}, {"map", running_->spec.map_name}, {"progress", running_->progress}});
  }
  if (last_) return send_json(res, last_->document);
  send_json(res, {{"state", "none"}});
}

void CampaignService::run_events(const httplib::Request& req, httplib::Response& res) const {
  const std::string text = req.matches[1];
  std::size_t index = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), index);
  if (ec != std::errc{} || end != text.data() + text.size()) {
    return bad_request(res, "run: expected a run's index, got '" + shortened(text) + "'");
  }
  const std::string policy_name =
      req.has_param("policy") ? req.get_param_value("policy") : std::string("ours");
  const std::optional<campaign::Policy> policy = campaign::policy_from_string(policy_name);
  if (!policy) return bad_request(res, "policy: expected one of " + campaign::policy_names());
  std::shared_ptr<const Finished> last;
  {
    const std::lock_guard lock(mutex_);
    if (replays_ >= std::max<std::size_t>(1, limits_.max_jobs)) {
      return send_error(res, kConflict,
                        Error{ErrorCode::kInvalidArgument,
                              "run: " + std::to_string(replays_) +
                                  " runs are being simulated again already; try when they end"});
    }
    ++replays_;
    last = last_;
  }
  // Counts this replay until the request ends, however it ends.
  struct Replaying {
    const CampaignService& service;
    ~Replaying() {
      const std::lock_guard lock(service.mutex_);
      --service.replays_;
    }
  } const replaying{*this};
  if (!last) {
    return send_error(res, kNotFound,
                      Error{ErrorCode::kInvalidArgument, "no campaign has finished yet"});
  }
  const auto record = std::find_if(last->records.begin(), last->records.end(),
                                   [&](const campaign::RunRecord& r) { return r.index == index; });
  if (record == last->records.end()) {
    return send_error(
        res, kNotFound,
        Error{ErrorCode::kInvalidArgument, "run " + std::to_string(index) + ": not among the " +
                                               std::to_string(last->records.size()) +
                                               " finished runs of the last campaign"});
  }
  if (!record->result) {
    // A run that crashed or hung in its guarded child would do so here, in the server.
    return send_error(res, kUnprocessable,
                      Error{ErrorCode::kInvalidArgument,
                            "run " + std::to_string(index) + ": " +
                                std::string(to_string(record->status)) + " (" + record->detail +
                                "); not simulated again in the station: reproduce it with `" +
                                campaign::reproduce_command(last->spec, index) + "`"});
  }
  Json events = Json::array();
  campaign::ExecutionObservers observers;
  observers.on_event = [&](const executor::Event& e) {
    events.push_back(Json::parse(executor::to_json_line(e)));
  };
  observers.on_plan = [&](const executor::PlanResponse& response) {
    Json route = plan_route_json(response.plan, *last->map, last->mission);
    route["type"] = "route";
    events.push_back(std::move(route));
  };
  Result<campaign::Execution> replayed = campaign::replay_execution(
      *last->map, last->mission, campaign::run_settings(last->spec), index, *policy, observers);
  if (!replayed.has_value()) return bad_request(res, replayed.error().message);
  const campaign::RunResult& result = *record->result;
  const campaign::Execution* recorded = *policy == campaign::Policy::kOurs       ? &result.ours
                                        : *policy == campaign::Policy::kBaseline ? &result.baseline
                                        : result.risk_aware ? &*result.risk_aware
                                                            : nullptr;
  send_json(res,
            {{"run", Json::parse(run_json_line(*record))},
             {"policy", campaign::to_string(*policy)},
             {"events", std::move(events)},
             {"same_as_record", recorded != nullptr && same_but_measured(*replayed, *recorded)}});
}

void CampaignService::shut_down() {
  const std::lock_guard lock(mutex_);
  shut_down_ = true;
  if (running_) running_->cancel = true;
}

}  // namespace sewerplan::server
