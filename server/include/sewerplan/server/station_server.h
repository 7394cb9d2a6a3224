// SPDX-License-Identifier: MIT
// The operator station's server: the HTTP side of `sewerplan serve` (docs/operator-station.md). It
// holds the maps it was started with and those uploaded, and answers the browser page (web/) with
// the library called in-process, the same functions and the same JSON documents (documents.h) as
// the CLI's commands:
//
//   GET  /api/maps                          the maps: id, name, counts
//   POST /api/maps?name=FILE[&format=F]     a map file (any format read_map reads): its new ID
//   POST /api/maps/ID/condition?name=FILE   the map's inspection findings (ISYBAU Zustandsdaten)
//   GET  /api/maps/ID                       one map's geometry, in its own coordinates
//   GET  /api/maps/ID/driveability?profile= what a built-in profile cannot drive, and why, as
//                                           `info --profile` (the motion table unless ?motion=0)
//   POST /api/maps/ID/validate              a mission (the CLI's JSON): the CLI's messages
//   POST /api/maps/ID/plan?time_limit=S     a mission: `plan --json`, plus the fused actions
//   POST /api/maps/ID/simulate              {"mission", "faults" | "random_faults"}: the
//                                           executor's events as server-sent events (each plan
//                                           followed by its route), then the report
//   POST /api/maps/ID/replay                an event log (JSON lines) read back as events
//   POST /api/maps/ID/campaign              {"mission", "runs", "seed", "fault_rates", "jobs",
//   ...}: a
//                                           fault campaign, its progress as server-sent events,
//                                           then its summary (one campaign at a time)
//   GET  /api/maps/ID/basemap?x0=&y0=&x1=&y1=&mpp=  the basemap's tiles for a view (basemap.h)
//   GET  /api/tiles/Z/X/Y.png               a tile of a `--tiles DIR` source
//   GET  /api/campaign                      the running campaign's progress, or the last summary
//   POST /api/campaign/cancel               stops the running campaign
//   GET  /api/campaign/runs/I               run I of the last campaign simulated again: its events
//
// and the page's files from `web_root` on every other GET. Maps are named by their ID (the file's
// stem), never by a path, so a request reaches no file but the page's own. Every bad request gets
// a 4xx status with {"error": {...}} (documents.h); with a token, every /api/ request needs
// "Authorization: Bearer TOKEN" (a ?token= in the URL is a 401: URLs end up in logs). Whatever
// the token, a request under another Host, from another Origin or a POST of a type a page may send
// unasked is refused (server/src/request_guard.h).
//
//   Result<std::unique_ptr<StationServer>> s = StationServer::create(options);
//   Result<int> port = (*s)->bind();   // port 0: any free port
//   (*s)->run();                       // until stop(), from another thread or a signal
//
// or, as `sewerplan serve` does (through the server module, sewerplan/modules/server_table.h), all
// of it until SIGINT or SIGTERM: serve_until_signal(options, on_listening).
//
// Thread safety: a map is read-only once loaded, and the list of maps is guarded (uploads come
// while other requests read); each request plans or simulates on its own copies, on the server's
// worker threads. stop() may be called from any thread.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/server/station_gis.h"

namespace sewerplan::server {

// How the server reads a map file; the CLI passes its own, which also reads GIS sources.
using MapReader = std::function<Result<SewerMap>(const std::filesystem::path&, Diagnostics&)>;

struct ServerOptions {
  std::vector<std::filesystem::path> maps;  // any format read_map (or read_map_with) reads
  MapReader read_map_with;                  // empty: core's read_map
  std::string host = "127.0.0.1";
  int port = 8080;    // 0: any free port (bind() says which)
  std::string token;  // empty: no token asked; else the API's bearer token
  // Names (besides IP addresses, "localhost" and `host`) the page may be opened under: a request
  // with another Host is refused (DNS rebinding; docs/operator-station.md). `serve --allow-host`.
  std::vector<std::string> allowed_hosts;
  std::filesystem::path web_root;  // the built page (share/sewerplan/web); empty: API only
  // The basemap's tile source (`serve --tiles`, basemap.h): an XYZ URL template, or a directory
  // of Z/X/Y.png tiles served at /api/tiles/. Empty: no basemap.
  std::string tiles;
  // GDAL and PROJ for the basemap and the GeoJSON export (station_gis.h), given by the program:
  // the command's load the GIS module when first called. Empty: those requests say there is no
  // GIS.
  StationGis gis;
  std::size_t max_body_bytes = 16u << 20;  // in any transfer or content encoding
  // Connections served at once, each on a worker thread started when needed; more wait their
  // turn. A connection serves one request; one that sends nothing is closed after 5 s.
  std::size_t max_connections = 256;
  // A connection whose request's headers have not come whole this long after it was opened, or
  // its whole request (a POST's body too) this long, is closed, however it trickles: else
  // max_connections of them, each sending a byte every few seconds, held every worker
  // (server/src/request_deadline.h).
  double headers_deadline_s = 10;
  double request_deadline_s = 60;
  double max_plan_time_s = 60;            // a request's time_limit is capped at this
  std::size_t max_maps = 64;              // the maps given and uploaded (POST /api/maps) at most
  std::size_t max_campaign_runs = 10000;  // a campaign's runs at most
  std::size_t max_campaign_jobs = 0;      // a campaign's jobs at most; 0: the machine's cores
  // Each campaign run in a forked child (campaign.h), so that a crash or a hang is counted and
  // never takes the server down. false: in the server's threads, one at a time, a stop honoured
  // between runs; for an allocator that is not safe to fork under while other threads allocate
  // (ASan before LLVM 17, campaign.h), as the sanitizer build's tests have.
  bool campaign_guard = true;
  // Called on an upload's thread (POST /api/maps) when the uploaded map's geometry is built, before
  // the map is listed under `id`; the maps are not locked then, so other requests are answered
  // meanwhile (a test holds an upload here and asks for another map). Empty: nothing.
  std::function<void(const std::string& id)> on_geometry_built;
};

class StationServer {
 public:
  // Reads every map (an error names the file that failed). IDs are the files' stems, made unique.
  static Result<std::unique_ptr<StationServer>> create(const ServerOptions& options);
  ~StationServer();
  StationServer(const StationServer&) = delete;
  StationServer& operator=(const StationServer&) = delete;

  // Binds host:port; returns the port bound (kIo if it cannot).
  Result<int> bind();
  // Serves until stop(). Precondition: bind() succeeded.
  void run();
  void stop();

 private:
  struct Impl;
  explicit StationServer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// Creates the station of `options`, binds it, calls on_listening with the port bound, and serves
// until the process gets SIGINT or SIGTERM; then returns. An error if the station cannot be created
// (a map that does not read) or bind (kIo). Blocks SIGINT and SIGTERM in the calling thread (the
// threads it starts inherit that) and waits for them in a thread of its own, never in a signal
// handler. Call it from the main thread, before any other thread is started, or with both signals
// blocked in every thread; it is meant to be the whole of a program's run.
Result<void> serve_until_signal(const ServerOptions& options,
                                const std::function<void(int port)>& on_listening);

}  // namespace sewerplan::server
