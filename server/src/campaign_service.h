// SPDX-License-Identifier: MIT
// CampaignService: the operator station's fault campaigns (docs/operator-station.md, "Campaigns"),
// one at a time, run in-process by the campaign library (campaign/campaign.h) on the open map and
// mission, as `sewerplan campaign` runs them: guarded children, `jobs` at a time.
//
// start() checks a request (runs, seed, fault rates, jobs, push) and answers a 400 naming the
// field, a 409 while another campaign runs, or a stream of server-sent events: "start", one
// "progress" per finished run (runs done of the total, crashes, our outcomes and tasks so far),
// and "summary" at the end (the summary.json document, from the campaign library's own writer, and
// each run's runs.jsonl line), or "error" if the campaign could not run (a thread that could not
// start, memory). A guarded run still going after the request's timeout_s (default 60, the CLI's
// --timeout) counts as hung. cancel() (or a closed stream, or the server stopping) stops the
// campaign through its stop condition: no run starts after it, and running children are killed.
// The last finished (or cancelled) campaign stays: status() gives its summary, and run_events()
// simulates one of its runs again from its seed (campaign::replay_execution) for the page's
// replay view, without storing every run's log.
//
//   CampaignService campaigns({.max_runs = 10000, .max_jobs = 2});
//   campaigns.start(body, map, "ais", std::move(mission), res);  // POST /api/maps/ID/campaign
//   campaigns.cancel();                                           // POST /api/campaign/cancel
//
// The campaign runs on a thread of its own, started by the stream: the library's progress callback
// (on that thread, under no lock of the library's) only records the event, and the stream's
// thread writes it. A reader that stalls holds up its own stream only (its events queue, the
// newest 256 kept: each carries the totals so far), not the campaign; a cancel stops the campaign
// at once, and its summary (status()) and the station's one slot do not wait for the reader.
//
// Guarded campaigns fork while the stream's thread allocates; with an allocator that is not
// fork-safe (LLVM 14's sanitizer allocators) a child can hang until its timeout, so sanitizer
// builds test the station's campaigns unguarded (CampaignLimits::guard).
//
// Thread safety: every member may be called from any of the server's threads; one mutex guards
// the running and the last campaign, which are shared with the stream and the campaign's thread.
#pragma once

#include <cstddef>
#include <functional>
#include <initializer_list>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/server/documents.h"

#include <httplib.h>

namespace sewerplan::server {

// The fields of a request's body (all but the mission optional); any other is refused, a 400 naming
// it and these (JsonFields::reject_unknown).
std::initializer_list<std::string_view> campaign_fields();

struct CampaignLimits {
  std::size_t max_runs = 10000;
  std::size_t max_jobs = 1;  // the machine's cores
  bool guard = true;         // ServerOptions::campaign_guard
};

class CampaignService {
 public:
  explicit CampaignService(CampaignLimits limits) : limits_(limits) {}

  // `body` is the request's JSON object; its "mission" is `mission`, already read and checked.
  void start(JsonElement body, std::shared_ptr<const SewerMap> map, const std::string& map_id,
             Mission mission, httplib::Response& res);

  // start() in its three steps, for a writer of the events other than httplib's (the tests' reader
  // that stalls). begin() checks the request and takes the station's slot: the campaign, or
  // nullptr with the 4xx in `res`. stream() runs it on its own thread and writes its events
  // through `write` on this one (false: the reader is gone, and the campaign is cancelled);
  // it returns when the campaign has ended and the summary is written. release() ends the
  // stream's hold (it cancels a campaign that never streamed).
  using EventWriter = std::function<bool(std::string_view)>;
  struct Running;
  std::shared_ptr<Running> begin(JsonElement body, std::shared_ptr<const SewerMap> map,
                                 const std::string& map_id, Mission mission,
                                 httplib::Response& res);
  void stream(const std::shared_ptr<Running>& running, const EventWriter& write);
  void release(const std::shared_ptr<Running>& running);
  // 200 {"cancelled": true}, or 409 when no campaign runs.
  void cancel(httplib::Response& res);
  // {"state": "none" | "running" | "done" | "cancelled", ...}: the running campaign's progress,
  // or the last one's summary and runs.
  void status(httplib::Response& res) const;
  // GET /api/campaign/runs/I?policy=ours|baseline|risk_aware: run I of the last campaign simulated
  // again (at most CampaignLimits::max_jobs at once: 409 beyond),
  // {"run": its runs.jsonl line, "policy", "events": [...], "same_as_record": bool}.
  void run_events(const httplib::Request& req, httplib::Response& res) const;
  // Cancels a running campaign and refuses new ones (the server is stopping).
  void shut_down();

  struct Finished;

 private:
  void finish(const std::shared_ptr<Running>& running, std::shared_ptr<const Finished> finished);
  // Why a new campaign cannot start now (the station stops, or one runs), if it cannot.
  std::optional<Error> refusal() const;
  std::optional<Error> refusal_locked() const;  // with mutex_ held

  CampaignLimits limits_;
  mutable std::mutex mutex_;
  bool shut_down_ = false;
  // Runs being simulated again (run_events), at most limits_.max_jobs at once: each is a whole
  // simulation on a request's thread.
  mutable std::size_t replays_ = 0;
  std::shared_ptr<Running> running_;
  std::shared_ptr<const Finished> last_;
};

}  // namespace sewerplan::server
