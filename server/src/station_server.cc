// SPDX-License-Identifier: MIT
#include "sewerplan/server/station_server.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <exception>
#include <initializer_list>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string_view>
#include <thread>
#include <type_traits>
#include <utility>
#include <variant>

#include "sewerplan/core/clock.h"
#include "sewerplan/core/condition.h"
#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/passage_motion.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/driveability.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/executor/event_json.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/executor/measuring.h"
#include "sewerplan/fusion/action_json.h"
#include "sewerplan/fusion/action_text.h"
#include "sewerplan/fusion/fuse.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"
#include "sewerplan/search/planner.h"
#include "sewerplan/server/basemap.h"
#include "sewerplan/server/documents.h"
#include "sewerplan/server/driveability_output.h"
#include "sewerplan/server/findings_output.h"
#include "sewerplan/server/geojson_export.h"
#include "sewerplan/server/sim_setup.h"

#include "campaign_service.h"
#include "http_reply.h"
#include "json_body.h"
#include "map_geometry.h"
#include "plan_route.h"
#include "request_deadline.h"
#include "request_guard.h"
#include "worker_pool.h"
#include <httplib.h>
#include <sys/socket.h>

namespace sewerplan::server {
namespace {

// httplib's server with room for many connections arriving at once: httplib listens with a backlog
// of 5, and a connection beyond it waits for its client to try again (after 1 s, 3 s, 7 s, ...):
// 100 connections opened at once took 11 s to be accepted.
class HttpServer : public httplib::Server {
 public:
  // After a bind: listen() again, with the system's largest backlog.
  void widen_backlog() { ::listen(svr_sock_, SOMAXCONN); }
};

// How long a connection may send nothing: before its request, or between two reads of it.
constexpr time_t kIdleTimeoutS = 5;
// The fields of the bodies of /simulate and /geojson (the mission required, the rest optional); any
// other is refused, as /campaign's (campaign_fields()).
const std::initializer_list<std::string_view> kSimulateFields = {"mission", "faults",
                                                                 "random_faults"};
const std::initializer_list<std::string_view> kGeojsonFields = {"mission", "plan", "log"};

// A map's geometry as the page reads it (map_geometry.h), built once from the map as given: every
// request sends these bytes without a copy, and the map with condition data joined shares them
// (findings change no geometry).
struct Geometry {
  std::string json;    // map_geometry_json
  std::string binary;  // map_geometry_binary
};

// The geometry of `map` under `id`, or the reason the compact form cannot hold it.
Result<std::shared_ptr<const Geometry>> build_geometry(const SewerMap& map, const std::string& id) {
  Result<std::string> binary = map_geometry_binary(map);
  if (!binary.has_value()) return binary.error();
  return std::make_shared<const Geometry>(Geometry{map_geometry_json(map, id), std::move(*binary)});
}

// One map of the station. Its parts are immutable and shared: a condition upload makes a new
// LoadedMap that shares the map as given and the geometry with the one it replaces, and a request
// that started on the old one keeps it.
struct LoadedMap {
  std::string id;
  std::shared_ptr<const SewerMap> given;  // the map as given
  // What requests plan on: `given`, or a copy of it with an uploaded condition joined (a later
  // upload joins to `given` again, replacing it).
  std::shared_ptr<const SewerMap> map;
  std::shared_ptr<const Geometry> geometry;
  std::filesystem::path motion_table;  // MAP.motion.json beside the map, if there is one
  std::string condition_name;          // the uploaded condition file's name
  // The reader's warnings of the map and of its condition data ({where, message} each), for the
  // page to show beside the map (GET /api/maps).
  Json warnings = Json::array();
  Json condition_warnings = Json::array();
};

// Answers with `body`, an immutable part of `owner`, without copying it: httplib reads it while it
// writes the response, and the response holds `owner` until then.
void send_shared(httplib::Response& res, std::shared_ptr<const void> owner, const std::string& body,
                 const char* content_type) {
  res.set_content_provider(body.size(), content_type,
                           [owner = std::move(owner), &body](std::size_t offset, std::size_t length,
                                                             httplib::DataSink& sink) {
                             return sink.write(body.data() + offset, length);
                           });
}

// The request's time limit: ?time_limit=S, at most `max_s` (default 10 s).
std::optional<double> time_limit(const httplib::Request& req, double max_s) {
  if (!req.has_param("time_limit")) return std::min(10.0, max_s);
  try {
    std::size_t used = 0;
    const std::string text = req.get_param_value("time_limit");
    const double s = std::stod(text, &used);
    if (used != text.size() || !(s > 0)) return std::nullopt;
    return std::min(s, max_s);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// The server's wall clock in milliseconds since 1970, as the page's Date.now(): each streamed
// event carries it (an SSE field "wall_ms", which EventSource ignores), so that the page can
// measure how long an event took from the executor to the page.
std::string wall_ms() {
  const auto now = std::chrono::system_clock::now().time_since_epoch();
  return std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(now).count());
}

// Unique IDs from the files' stems: "map", "map-2", ...; only letters, digits, '.', '_' and '-'
// (an uploaded file's name is the client's).
std::string unique_id(std::string stem, std::set<std::string>& taken) {
  std::erase_if(stem, [](char c) {
    return !(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-');
  });
  if (stem.size() > 64) stem.resize(64);
  if (stem.empty() || stem.starts_with('.')) stem = "map" + stem;
  std::string id = stem;
  for (int n = 2; taken.contains(id); ++n) id = stem + "-" + std::to_string(n);
  taken.insert(id);
  return id;
}

}  // namespace

struct StationServer::Impl {
  ServerOptions options;
  // The maps given at the start and uploaded since; never removed, so a map a simulation runs on
  // stays while it runs. Guarded by maps_mutex: uploads come while other requests read.
  // IDs given to maps listed and to uploads not yet listed; `uploading` counts the latter, so that
  // the limit of maps holds while their geometry is built outside the lock.
  std::vector<std::shared_ptr<const LoadedMap>> maps;
  std::set<std::string> taken_ids;
  std::size_t uploading = 0;
  mutable std::mutex maps_mutex;
  // Declared before `http`, so that it outlives the requests that use it.
  std::unique_ptr<CampaignService> campaigns;
  std::optional<TileSource> tiles;  // --tiles (basemap.h)
  HttpServer http;
  // Closes connections whose request does not come whole in time (request_deadline.h); made by
  // bind(), which knows the port.
  std::unique_ptr<RequestDeadline> deadline;
  // The request of `req`'s connection has its headers read, or is read whole: the deadlines no
  // longer apply to it.
  void headers_read(const httplib::Request& req) const {
    if (deadline) deadline->headers_read(req.remote_addr, req.remote_port);
  }
  void read_whole(const httplib::Request& req) const {
    if (deadline) deadline->read_whole(req.remote_addr, req.remote_port);
  }
  std::atomic<bool> running{false};
  std::atomic<bool> stopping{false};

  std::shared_ptr<const LoadedMap> find_map(const httplib::Request& req,
                                            httplib::Response& res) const {
    const std::string id = req.matches[1];
    const std::lock_guard lock(maps_mutex);
    for (const auto& m : maps) {
      if (m->id == id) return m;
    }
    send_error(res, kNotFound, Error{ErrorCode::kInvalidArgument, "no map '" + id + "'"});
    return nullptr;
  }

  // The body as a mission on `map`, or a 422 with the CLI's messages.
  static std::optional<Mission> read_body_mission(std::string_view text, const SewerMap& map,
                                                  httplib::Response& res) {
    Diagnostics diagnostics;
    Result<Mission> mission = read_mission_json(text, "mission.json", map, diagnostics);
    if (!mission.has_value()) {
      send_error(res, kUnprocessable, mission.error(), diagnostics);
      return std::nullopt;
    }
    return std::move(*mission);
  }

  // A POST body that is a JSON object with "mission", a mission's JSON object, on `map`, of the
  // endpoint's `fields` (named in the error if it is no object): the body (json_body.h) and its
  // mission, read from the parsed body by the mission file's reader, or empty with the 400 or 422
  // sent. The endpoint reads the other fields, and refuses those not in `fields`
  // (JsonFields::reject_unknown), all in one 400.
  struct MissionBody {
    JsonDocument body;
    Mission mission;
    JsonElement root() const { return body.root(); }
  };
  static std::optional<MissionBody> read_mission_body(
      std::string_view text, const SewerMap& map, std::initializer_list<std::string_view> fields,
      httplib::Response& res) {
    Result<JsonDocument> parsed = parse_json_body(text);
    if (!parsed.has_value()) {
      bad_request(res, parsed.error().message);
      return std::nullopt;
    }
    JsonElement mission_json;
    if (!parsed->root().is_object()) {
      std::string shape;
      for (const std::string_view field : fields) {
        shape += (shape.empty() ? "{\"" : ", \"") + std::string(field) + "\"";
      }
      bad_request(res, std::string(kBodyFile) + ":$: expected a JSON object " + shape + "}, got " +
                           describe_json(parsed->root()));
      return std::nullopt;
    }
    if (parsed->root()["mission"].get(mission_json) != simdjson::SUCCESS ||
        !mission_json.is_object()) {
      bad_request(res, std::string(kBodyFile) + ":$.mission: expected the mission's JSON object");
      return std::nullopt;
    }
    Diagnostics diagnostics;
    Result<Mission> mission =
        read_mission_value(mission_json, "$.mission", std::string(kBodyFile), map, diagnostics);
    if (!mission.has_value()) {
      send_error(res, kUnprocessable, mission.error(), diagnostics);
      return std::nullopt;
    }
    return MissionBody{std::move(*parsed), std::move(*mission)};
  }

  // As the CLI's plan and simulate: the planned manhole passages beside the map (MAP.motion.json,
  // `motion precompute`), unless ?motion=0; a table for another map or robot is a 422, as the
  // CLI's exit code 1. Whether a table is used: the mission's passage_motion.
  static bool attach_motion(const LoadedMap& m, const httplib::Request& req, Mission& mission,
                            httplib::Response& res) {
    if (m.motion_table.empty() || req.get_param_value("motion") == "0") return true;
    Result<PassageMotionTable> table = load_passage_motion(m.motion_table, *m.map, mission.profile);
    if (!table.has_value()) {
      Error error = table.error();
      error.message += " (plan with ?motion=0 to use the angle and step rules)";
      send_error(res, kUnprocessable, error);
      return false;
    }
    mission.passage_motion = std::make_shared<const PassageMotionTable>(std::move(*table));
    return true;
  }

  // As the CLI's plan and simulate (--risk, with the built-in risk table): what the map's
  // inspection findings close (?risk=impassable, the default; avoid: every place with a risk;
  // ignore: nothing), and with ?risk=expected the possible blockages weighed by their expected
  // cost. What was applied, or nullopt after a 400 for an unknown mode.
  struct AppliedRisk {
    RiskMode mode;
    std::string name;
    std::size_t closed = 0;  // places the findings closed
  };
  static std::optional<AppliedRisk> apply_risk(const LoadedMap& m, const httplib::Request& req,
                                               Mission& mission, httplib::Response& res) {
    const std::string name = req.has_param("risk") ? req.get_param_value("risk") : "impassable";
    const std::optional<RiskMode> mode = risk_mode_from_string(name);
    if (!mode) {
      bad_request(res, "risk: expected ignore, impassable, avoid or expected, not '" + name + "'");
      return std::nullopt;
    }
    return AppliedRisk{*mode, name, close_findings(*m.map, mission, *mode, default_risk_table())};
  }
  static domain::RiskCosts risk_costs(RiskMode mode) {
    return mode == RiskMode::kExpected ? domain::kDefaultRiskCosts : domain::RiskCosts{};
  }

  // An upload's place among the maps, from reserve() (its ID, counted against the limit) to
  // list(): the geometry is built between the two, with the maps unlocked. One that is never
  // listed (a failure, an exception) gives its ID and its place back.
  class Upload {
   public:
    explicit Upload(Impl& impl) : impl_(impl) {}
    Upload(const Upload&) = delete;
    Upload& operator=(const Upload&) = delete;
    ~Upload() {
      if (!reserved_ || listed_) return;
      const std::lock_guard lock(impl_.maps_mutex);
      --impl_.uploading;
      impl_.taken_ids.erase(id_);
    }
    // Reserves an ID from the file's stem, or says why the station takes no more maps.
    std::optional<Error> reserve(const std::string& stem) {
      const std::lock_guard lock(impl_.maps_mutex);
      const std::size_t held = impl_.maps.size() + impl_.uploading;
      if (held >= impl_.options.max_maps) {
        return Error{ErrorCode::kInvalidArgument,
                     "the station holds " + std::to_string(held) +
                         " maps (with those being uploaded), its limit: no more uploads"};
      }
      id_ = unique_id(stem, impl_.taken_ids);
      ++impl_.uploading;
      reserved_ = true;
      return std::nullopt;
    }
    const std::string& id() const { return id_; }
    void list(std::shared_ptr<const LoadedMap> loaded) {
      const std::lock_guard lock(impl_.maps_mutex);
      impl_.maps.push_back(std::move(loaded));
      --impl_.uploading;  // counted once, as a map, from here: not twice while the reply is sent
      listed_ = true;
    }

   private:
    Impl& impl_;
    std::string id_;
    bool reserved_ = false;
    bool listed_ = false;
  };

  void routes();
  void list_maps(httplib::Response& res) const;
  void driveability(const httplib::Request& req, httplib::Response& res) const;
  void findings(const httplib::Request& req, httplib::Response& res) const;
  void basemap(const httplib::Request& req, httplib::Response& res) const;
  void tile(const httplib::Request& req, httplib::Response& res) const;
  void upload_map(const httplib::Request& req, const std::string& body, httplib::Response& res);
  void upload_condition(const httplib::Request& req, const std::string& body,
                        httplib::Response& res);
  void validate(const httplib::Request& req, const std::string& body, httplib::Response& res) const;
  void plan(const httplib::Request& req, const std::string& body, httplib::Response& res) const;
  void simulate(const httplib::Request& req, const std::string& body, httplib::Response& res) const;
  void replay(const httplib::Request& req, const std::string& body, httplib::Response& res) const;
  void geojson(const httplib::Request& req, const std::string& body, httplib::Response& res) const;
  void campaign(const httplib::Request& req, const std::string& body, httplib::Response& res);
  // Why an /api/ request is refused for its token, if it is.
  std::optional<std::string> unauthorised(const httplib::Request& req) const;
};

// With a token, an API request needs it in its "Authorization: Bearer" header; one in the URL
// (?token=) is refused, whether right or wrong: URLs end up in logs, proxies and the history.
std::optional<std::string> StationServer::Impl::unauthorised(const httplib::Request& req) const {
  if (options.token.empty()) return std::nullopt;
  if (req.has_param("token")) {
    return "token: not accepted in the URL (?token=), which ends up in logs and the history: send "
           "\"Authorization: Bearer TOKEN\"";
  }
  if (req.get_header_value("Authorization") != "Bearer " + options.token) {
    return "this server needs \"Authorization: Bearer TOKEN\" (--token)";
  }
  return std::nullopt;
}

void StationServer::Impl::list_maps(httplib::Response& res) const {
  Json list = Json::array();
  const std::lock_guard lock(maps_mutex);
  for (const auto& m : maps) {
    list.push_back({{"id", m->id},
                    {"name", m->map->name()},
                    {"manholes", m->map->manhole_count()},
                    {"pipes", m->map->pipe_count()},
                    {"findings", m->map->finding_count()},
                    {"motion_table", !m->motion_table.empty()},
                    {"warnings", m->warnings},
                    {"condition_warnings", m->condition_warnings},
                    // The coordinate reference system of the geometry's x and y (core/crs.h),
                    // or null: local coordinates. The page names it beside the cursor's position.
                    {"crs", m->map->crs() ? Json(m->map->crs()->to_string()) : Json()}});
  }
  // The basemap's tile source (basemap.h), or null: none (`serve --tiles`).
  Json basemap;
  if (tiles) {
    basemap = {{"kind", tiles->kind == TileSource::Kind::kUrl ? "url" : "directory"},
               {"tiles", tiles->url_template},
               {"min_zoom", tiles->min_zoom},
               {"max_zoom", tiles->max_zoom}};
  }
  send_json(
      res,
      {{"maps", list}, {"profiles", builtin_profile_names()}, {"basemap", std::move(basemap)}});
}

// GET /api/maps/ID/basemap?x0=&y0=&x1=&y1=&mpp=: the tiles that cover the view (x0, y0, x1, y1
// in the map's metres, mpp metres a pixel), each with its corners in the map's metres.
void StationServer::Impl::basemap(const httplib::Request& req, httplib::Response& res) const {
  const auto m = find_map(req, res);
  if (!m) return;
  if (!tiles) {
    return send_error(
        res, kNotFound,
        Error{ErrorCode::kInvalidArgument, "no basemap: the station was started without --tiles"});
  }
  BasemapView view;
  const auto number = [&](const char* name, double& out) {
    const std::string text = req.get_param_value(name);
    try {
      std::size_t used = 0;
      out = std::stod(text, &used);
      if (used == text.size() && std::isfinite(out)) return true;
    } catch (const std::exception&) {  // not a number: said below
    }
    bad_request(res, std::string(name) + ": expected a number of metres, not '" + text + "'");
    return false;
  };
  if (!number("x0", view.rect[0]) || !number("y0", view.rect[1]) || !number("x1", view.rect[2]) ||
      !number("y1", view.rect[3]) || !number("mpp", view.metres_per_pixel)) {
    return;
  }
  Result<TileChoice> choice = basemap_tiles(*m->map, *tiles, view, options.gis);
  if (!choice.has_value()) {
    const bool bad_view = m->map->crs() && choice.error().message.starts_with("the view");
    return bad_view ? bad_request(res, choice.error().message)
                    : send_error(res, kUnprocessable, choice.error());
  }
  Json list = Json::array();
  for (const PlacedTile& t : choice->tiles) {
    Json corners = Json::array();
    for (const MapXY& c : t.corners) corners.push_back({c.x, c.y});
    list.push_back({{"z", t.z}, {"x", t.x}, {"y", t.y}, {"url", t.url}, {"corners", corners}});
  }
  send_json(res, {{"crs", m->map->crs()->to_string()},
                  {"zoom", choice->zoom},
                  {"tiles", std::move(list)},
                  {"truncated", choice->truncated},
                  {"note", choice->note}});
}

// GET /api/tiles/Z/X/Y.EXT: a tile of a directory source, or 404; the path's parts are digits
// (the route's pattern), so it names no file but a tile's.
void StationServer::Impl::tile(const httplib::Request& req, httplib::Response& res) const {
  const std::string z = req.matches[1], x = req.matches[2], y = req.matches[3],
                    ext = req.matches[4];
  std::optional<std::string> bytes =
      tiles ? read_tile(*tiles, std::stoi(z), std::stoll(x), std::stoll(y), ext) : std::nullopt;
  if (!bytes) {
    return send_error(res, kNotFound,
                      Error{ErrorCode::kInvalidArgument,
                            tiles ? "no tile " + z + "/" + x + "/" + y + "." + ext
                                  : "no tiles: the station was started without --tiles DIR"});
  }
  const char* type = ext == "png" ? "image/png" : ext == "webp" ? "image/webp" : "image/jpeg";
  res.set_content(std::move(*bytes), type);
}

// POST /api/maps?name=FILE[&format=F]: the body is a map file in any format read_map reads (the
// format from ?format=, else the name's extension, else the content), read in memory: nothing
// is written on the server. Its ID is the name's stem, made unique.
void StationServer::Impl::upload_map(const httplib::Request& req, const std::string& body,
                                     httplib::Response& res) {
  const std::string name = req.has_param("name") ? req.get_param_value("name") : "upload";
  const std::filesystem::path file = std::filesystem::path(name).filename();
  std::optional<MapFormat> format;
  if (req.has_param("format")) {
    format = map_format_from_name(req.get_param_value("format"));
    if (!format) return bad_request(res, "format: expected one of " + map_format_names());
  } else {
    Result<MapFormat> detected = detect_map_format(file, body);
    if (!detected.has_value()) return send_error(res, kUnprocessable, detected.error());
    format = *detected;
  }
  Diagnostics diagnostics;
  Result<SewerMap> map = parse_map(body, file.string(), *format, diagnostics);
  if (!map.has_value()) return send_error(res, kUnprocessable, map.error(), diagnostics);
  Upload upload(*this);
  if (const std::optional<Error> full = upload.reserve(file.stem().string())) {
    return send_error(res, kConflict, *full);
  }
  // The geometry is built with the maps unlocked: a 100,000-manhole map takes a second, and every
  // other request needs the maps.
  auto given = std::make_shared<const SewerMap>(std::move(*map));
  Result<std::shared_ptr<const Geometry>> geometry = build_geometry(*given, upload.id());
  if (!geometry.has_value()) return send_error(res, kUnprocessable, geometry.error());
  if (options.on_geometry_built) options.on_geometry_built(upload.id());
  auto loaded =
      std::make_shared<const LoadedMap>(LoadedMap{upload.id(),
                                                  given,
                                                  given,
                                                  std::move(*geometry),
                                                  {},
                                                  {},
                                                  diagnostics_json(diagnostics, Severity::kWarning),
                                                  Json::array()});
  upload.list(loaded);
  send_json(res,
            {{"id", upload.id()},
             {"name", loaded->map->name()},
             {"manholes", loaded->map->manhole_count()},
             {"pipes", loaded->map->pipe_count()},
             {"warnings", loaded->warnings}},
            201);
}

// POST /api/maps/ID/condition?name=FILE: the body is the map's inspection findings (ISYBAU
// Zustandsdaten, as `--condition FILE`), joined to the map as it was given (a later upload
// replaces them), read in memory. The map keeps its ID; requests already running keep the map
// they started with.
void StationServer::Impl::upload_condition(const httplib::Request& req, const std::string& body,
                                           httplib::Response& res) {
  const auto m = find_map(req, res);
  if (!m) return;
  const std::string name =
      std::filesystem::path(req.has_param("name") ? req.get_param_value("name") : "condition.xml")
          .filename()
          .string();
  Diagnostics diagnostics;
  // The one copy: the joined map owns its findings. The map as given and the geometry are shared.
  Result<SewerMap> joined = read_condition_isybau(*m->given, body, name, diagnostics);
  if (!joined.has_value()) return send_error(res, kUnprocessable, joined.error(), diagnostics);
  auto loaded = std::make_shared<const LoadedMap>(LoadedMap{
      m->id, m->given, std::make_shared<const SewerMap>(std::move(*joined)), m->geometry,
      m->motion_table, name, m->warnings, diagnostics_json(diagnostics, Severity::kWarning)});
  const std::lock_guard lock(maps_mutex);
  for (auto& slot : maps) {
    if (slot->id == loaded->id) slot = loaded;
  }
  send_json(res, {{"id", loaded->id},
                  {"condition", name},
                  {"findings", loaded->map->finding_count()},
                  {"warnings", loaded->condition_warnings}});
}

void StationServer::Impl::driveability(const httplib::Request& req, httplib::Response& res) const {
  const auto m = find_map(req, res);
  if (!m) return;
  const std::string name = req.get_param_value("profile");
  // Built-in profiles only: a profile named by a path would read a file on the server.
  const std::optional<RobotProfile> profile = builtin_profile(name);
  if (!profile) {
    return bad_request(res, "profile: unknown '" + name + "' (built-in: makro-1.1, makro-plus)");
  }
  // As `info --profile`: the motion table beside the map (unless ?motion=0), and what the map's
  // findings close for this robot.
  Mission with_motion;  // only to carry the table, as plan does
  with_motion.profile = *profile;
  if (!attach_motion(*m, req, with_motion, res)) return;
  const RiskTable table = default_risk_table();
  const std::vector<ManholeId> starts = domain::default_starts(*m->map);
  const domain::DriveabilityReport report =
      analyse_profile(*m->map, *profile, starts, with_motion.passage_motion.get(), table);
  Json j = driveability_json(report, *m->map, *profile);
  j.update(closures_json(*m->map, split_closures(*m->map, *profile, table, report)));
  j["motion_table"] = with_motion.passage_motion != nullptr;
  res.set_content(j.dump(), kJsonType);
}

// GET /api/maps/ID/findings?profile=P&risk=MODE: the map's inspection findings with their class
// for the robot and what planning in the mode makes of them (findings_output.h). The risk mode
// as /plan's (default impassable); a built-in profile only, as /driveability.
void StationServer::Impl::findings(const httplib::Request& req, httplib::Response& res) const {
  const auto m = find_map(req, res);
  if (!m) return;
  const std::string name = req.get_param_value("profile");
  const std::optional<RobotProfile> profile = builtin_profile(name);
  if (!profile) {
    return bad_request(res, "profile: unknown '" + name + "' (built-in: makro-1.1, makro-plus)");
  }
  const std::string mode_name =
      req.has_param("risk") ? req.get_param_value("risk") : std::string("impassable");
  const std::optional<RiskMode> mode = risk_mode_from_string(mode_name);
  if (!mode) {
    return bad_request(
        res, "risk: expected ignore, impassable, avoid or expected, not '" + mode_name + "'");
  }
  send_json(res, findings_json(*m->map, *profile, *mode, mode_name, default_risk_table()));
}

void StationServer::Impl::validate(const httplib::Request& req, const std::string& body,
                                   httplib::Response& res) const {
  const auto m = find_map(req, res);
  if (!m) return;
  Diagnostics diagnostics;
  Result<Mission> mission = read_mission_json(body, "mission.json", *m->map, diagnostics);
  Json j = {{"valid", mission.has_value()},
            {"errors", diagnostics_json(diagnostics, Severity::kError)},
            {"warnings", diagnostics_json(diagnostics, Severity::kWarning)}};
  if (!mission.has_value()) {
    j["error"] = error_object(mission.error(), diagnostics, exit_code_for(mission.error()));
  }
  send_json(res, j);
}

void StationServer::Impl::plan(const httplib::Request& req, const std::string& body,
                               httplib::Response& res) const {
  const auto m = find_map(req, res);
  if (!m) return;
  const std::optional<double> limit = time_limit(req, options.max_plan_time_s);
  if (!limit) return bad_request(res, "time_limit: expected seconds > 0");
  std::optional<Mission> mission = read_body_mission(body, *m->map, res);
  if (!mission || !attach_motion(*m, req, *mission, res)) return;
  const std::optional<AppliedRisk> risk = apply_risk(*m, req, *mission, res);
  if (!risk) return;
  search::PlannerOptions planner;
  planner.time_limit_s = *limit;
  planner.risk = risk_costs(risk->mode);
  planner.select_goals = req.get_param_value("select_goals") == "1";
  domain::MissionProgress start = domain::initial_progress(*mission, *m->map);
  const SteadyClock clock;
  const double started_s = clock.now_s();
  Result<search::PlanOutcome> outcome = search::plan_mission(*m->map, *mission, start, planner);
  if (!outcome.has_value()) {
    return send_error(res, kUnprocessable, outcome.error(), {},
                      plan_failure_json(*m->map, *mission, planner, clock.now_s() - started_s));
  }
  const domain::MissionProgress fuse_start = start;
  for (const auto& d : outcome->dropped) start.done[d.task.index()] = true;
  const domain::ValidationReport report =
      domain::validate_plan(outcome->plan, *m->map, *mission, start);
  Json j = plan_json(*outcome, report, *m->map, *mission);
  j["text"] = domain::format_plan(outcome->plan, *m->map, *mission);
  j["motion_table"] = mission->passage_motion != nullptr;
  // With weighed blockages plan_json has put the route's risk (its unobstructed probability, the
  // expected cost of stops, the blockages passed) here already: kept, and what the mode did added.
  j["risk"].update({{"mode", risk->name},
                    {"closed_by_findings", risk->closed},
                    {"possible_blockages", mission->hazards.size()}});
  Json actions = Json::array();
  if (Result<fusion::FusedPlan> fused = fusion::fuse(outcome->plan, *m->map, *mission, fuse_start);
      fused.has_value()) {
    for (const fusion::RobotAction& action : fused->actions) {
      Json a = Json::parse(fusion::write_action_json(action, *m->map, *mission));
      a["text"] = fusion::describe(action, *m->map, *mission);
      actions.push_back(std::move(a));
    }
  }
  j["fused"] = std::move(actions);
  send_json(res, j);
}

void StationServer::Impl::simulate(const httplib::Request& req, const std::string& text,
                                   httplib::Response& res) const {
  const auto m = find_map(req, res);
  if (!m) return;
  std::optional<MissionBody> read = read_mission_body(text, *m->map, kSimulateFields, res);
  if (!read) return;
  std::optional<Mission> mission = std::move(read->mission);
  if (!attach_motion(*m, req, *mission, res)) return;
  const std::optional<AppliedRisk> risk = apply_risk(*m, req, *mission, res);
  if (!risk) return;
  Diagnostics diagnostics;
  JsonFields body(read->root(), "$", kBodyFile, diagnostics);
  body.reject_unknown(kSimulateFields);
  std::optional<std::string> seed_rate;
  if (const std::optional<JsonElement> v =
          body.member("random_faults", JsonFields::Need::kOptional)) {
    std::string_view given;
    if (body.has("faults")) {
      body.error("random_faults", "give faults or random_faults, not both");
    } else if (v->get_string().get(given) != simdjson::SUCCESS) {
      body.error("random_faults", "expected \"SEED[,RATE]\", got " + describe_json(*v));
    } else {
      seed_rate = std::string(given);
    }
  }
  if (diagnostics.has_errors()) return bad_request(res, diagnostics.error_summary());
  Result<hal::FaultScenario> faults = hal::FaultScenario{};
  if (const std::optional<JsonElement> given = body.member("faults", JsonFields::Need::kOptional)) {
    faults =
        hal::read_faults_value(*given, "$.faults", std::string(kBodyFile), *m->map, diagnostics);
  } else if (seed_rate) {
    faults = faults_for("", *seed_rate, *m->map, *mission, diagnostics);
  }
  if (!faults.has_value()) {
    const int status =
        faults.error().code == ErrorCode::kInvalidArgument ? kBadRequest : kUnprocessable;
    return send_error(res, status, faults.error(), diagnostics);
  }
  struct Run {
    std::shared_ptr<const LoadedMap> loaded;  // keeps the map while the stream runs
    const SewerMap* map;
    Mission mission;
    hal::FaultScenario faults;
    domain::RiskCosts risk;
  };
  auto run = std::make_shared<Run>(
      Run{m, m->map.get(), std::move(*mission), std::move(*faults), risk_costs(risk->mode)});
  res.set_header("Cache-Control", "no-cache");
  res.set_chunked_content_provider(
      "text/event-stream", [run](std::size_t, httplib::DataSink& sink) {
        executor::ReplannerOptions replanning;
        replanning.planner.risk = run->risk;
        executor::Replanner replanner(*run->map, run->mission, replanning);
        hal::SimRobot robot(*run->map, run->mission.profile,
                            start_pose(replanner.progress().position), run->faults);
        executor::Executor executor(*run->map, replanner, robot);
        // A closed tab: the write fails, and the mission halts at its next check.
        const auto send = [&](std::string_view type, const std::string& data) {
          const std::string message = "event: " + std::string(type) + "\ndata: " + data +
                                      "\nwall_ms: " + wall_ms() + "\n\n";
          if (!sink.write(message.data(), message.size())) executor.halt();
        };
        executor.subscribe([&](const executor::Event& event) {
          send(executor::type_name(event), executor::to_json_line(event));
        });
        executor.subscribe_plans([&](const executor::PlanResponse& response) {
          send("route", dump(plan_route_json(response.plan, *run->map, replanner.mission())));
        });
        // What the run measured of the map (simulate --corrected-map's measurements).
        executor::Measurer measurer(*run->map, MeasurementSource{.robot = run->mission.profile.name,
                                                                 .mission = run->mission.name,
                                                                 .date = {}});
        executor.subscribe_jobs(measurer.observer());
        const executor::MissionReport report = executor.run();
        // What the robot learnt (closed pipes, dangerous passages) and the map corrections its
        // measurements show, for the page to draw and export (findings_output.h).
        send("learnt",
             dump(learnt_json_document(replanner.learnt(), measurer.measurements(), *run->map)));
        send("report", dump(report_json(report)));
        sink.done();
        return true;
      });
}

void StationServer::Impl::replay(const httplib::Request& req, const std::string& body,
                                 httplib::Response& res) const {
  const auto m = find_map(req, res);
  if (!m) return;
  Diagnostics diagnostics;
  Result<std::vector<executor::Event>> events =
      executor::read_event_log(body, "events.jsonl", diagnostics);
  if (!events.has_value()) return send_error(res, kUnprocessable, events.error(), diagnostics);
  Json list = Json::array();
  for (const executor::Event& e : *events) list.push_back(Json::parse(executor::to_json_line(e)));
  send_json(res, {{"events", list}});
}

// POST /api/maps/ID/geojson: {"mission", "plan": its text, "log": an event log's lines}, the plan
// and the log optional, as `export-geojson --mission --plan --log` writes them (geojson_export.h).
void StationServer::Impl::geojson(const httplib::Request& req, const std::string& text,
                                  httplib::Response& res) const {
  const auto m = find_map(req, res);
  if (!m) return;
  const std::optional<MissionBody> read = read_mission_body(text, *m->map, kGeojsonFields, res);
  if (!read) return;
  Diagnostics diagnostics;
  JsonFields body(read->root(), "$", kBodyFile, diagnostics);
  body.reject_unknown(kGeojsonFields);
  const std::optional<std::string> plan = body.string("plan", JsonFields::Need::kOptional);
  const std::optional<std::string> log = body.string("log", JsonFields::Need::kOptional);
  if (diagnostics.has_errors()) {
    return bad_request(res, diagnostics.error_summary());
  }
  const Mission* mission = &read->mission;
  Result<std::string> geojson = export_geojson(
      *m->map, *mission, {.plan_text = plan.value_or(""), .log_text = log.value_or("")},
      options.gis, diagnostics);
  if (!geojson.has_value()) return send_error(res, kUnprocessable, geojson.error(), diagnostics);
  res.set_content(std::move(*geojson), "application/geo+json");
}

// POST /api/maps/ID/campaign: the mission read as /simulate reads it, the rest by the service.
void StationServer::Impl::campaign(const httplib::Request& req, const std::string& text,
                                   httplib::Response& res) {
  const auto m = find_map(req, res);
  if (!m) return;
  std::optional<MissionBody> read = read_mission_body(text, *m->map, campaign_fields(), res);
  if (!read || !attach_motion(*m, req, read->mission, res)) return;
  // The map stays while the campaign runs and while its runs can be replayed.
  campaigns->start(read->root(), m->map, m->id, std::move(read->mission), res);
}

void StationServer::Impl::routes() {
  // Requests with a Content-Length; a body in another transfer encoding (chunked) is read with the
  // limit by post() below, decompressed bytes counted.
  http.set_payload_max_length(options.max_body_bytes);
  // A browser keeps idle connections open, a simulation holds one while it streams, and any local
  // program can open many that send nothing: each holds a worker, started when needed, up to
  // max_connections (worker_pool.h). One request a connection: no connection waits idle between
  // requests, and no bytes left unread of a refused body are ever read as a request of their own.
  // A connection that sends nothing for 5 s (before its request, or between two reads) is closed.
  http.new_task_queue = [n = options.max_connections] { return new WorkerPool(n); };
  http.set_keep_alive_max_count(1);
  http.set_keep_alive_timeout(kIdleTimeoutS);
  http.set_read_timeout(kIdleTimeoutS, 0);
  http.set_write_timeout(kIdleTimeoutS, 0);
  // Only SO_REUSEADDR (a restart binds while the last run's connections linger), not httplib's
  // SO_REUSEPORT, with which a second server binds the same port and takes half the connections.
  http.set_socket_options([](socket_t sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  const GuardOptions guard{options.host, options.allowed_hosts, options.max_body_bytes};
  // Who may drive the station (request_guard.h), then the token; before the body is read, and
  // before a client that asks ("Expect: 100-continue", as curl does for a large body) sends it.
  const auto refused = [this, guard](const httplib::Request& req, httplib::Response& res) {
    // Answered here, or a request with no body (a GET): read whole. A POST's body is read by
    // post().
    if (req.method != "POST") read_whole(req);
    headers_read(req);
    if (const std::optional<Refusal> r = check_request(req, guard)) {
      read_whole(req);
      send_json(res, {{"error", {{"code", r->code}, {"message", r->message}}}}, r->status);
      return true;
    }
    if (!req.path.starts_with("/api/")) return false;
    if (const std::optional<std::string> why = unauthorised(req)) {
      send_json(res, {{"error", {{"code", "unauthorised"}, {"message", *why}}}}, kUnauthorized);
      return true;
    }
    return false;
  };
  http.set_pre_routing_handler([refused](const httplib::Request& req, httplib::Response& res) {
    return refused(req, res) ? httplib::Server::HandlerResponse::Handled
                             : httplib::Server::HandlerResponse::Unhandled;
  });
  http.set_expect_100_continue_handler(
      [refused](const httplib::Request& req, httplib::Response& res) {
        return refused(req, res) ? res.status : 100;
      });
  // A status without a body of ours (no route, a body over the limit, a bad request line): JSON.
  http.set_error_handler([limit = options.max_body_bytes](const httplib::Request& req,
                                                          httplib::Response& res) {
    if (!res.body.empty()) return;
    const std::string message = res.status == 413   ? body_over_limit(limit)
                                : res.status == 404 ? "nothing at " + req.path
                                                    : "bad request";
    send_json(res,
              {{"error", {{"code", "http-" + std::to_string(res.status)}, {"message", message}}}},
              res.status);
  });
  http.set_exception_handler(
      [](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
        send_json(res, {{"error", {{"code", "internal"}, {"message", "internal error"}}}}, 500);
      });
  using Req = httplib::Request;
  using Res = httplib::Response;
  // Every POST reads its body here, whatever its transfer encoding, and stops at the limit: a
  // chunked body carries no length that httplib's limit could see, and a compressed one is counted
  // as it is decompressed.
  const auto post = [this](const std::string& pattern,
                           std::function<void(const Req&, const std::string&, Res&)> handle) {
    http.Post(pattern, [this, handle = std::move(handle)](const Req& req, Res& res,
                                                          const httplib::ContentReader& reader) {
      const std::size_t limit = options.max_body_bytes;
      std::string body;
      bool over = false;
      const bool read = reader([&](const char* data, std::size_t size) {
        over = size > limit - body.size();
        if (!over) body.append(data, size);
        return !over;
      });
      read_whole(req);
      if (over) {
        return send_json(res,
                         {{"error", {{"code", "http-413"}, {"message", body_over_limit(limit)}}}},
                         kPayloadTooLarge);
      }
      if (!read) {
        // httplib's status: 415 for a Content-Encoding it does not decompress, else 400.
        const std::string message =
            res.status == kUnsupportedMediaType
                ? "Content-Encoding '" + req.get_header_value("Content-Encoding") +
                      "': not one the station reads; send the body as it is"
                : "the request body could not be read (cut short, or a bad chunk)";
        const int status = res.status >= 400 ? res.status : kBadRequest;
        return send_json(
            res, {{"error", {{"code", "http-" + std::to_string(status)}, {"message", message}}}},
            status);
      }
      handle(req, body, res);
    });
  };
  http.Get("/api/maps", [this](const Req&, Res& res) { list_maps(res); });
  post("/api/maps",
       [this](const Req& req, const std::string& body, Res& res) { upload_map(req, body, res); });
  http.Get(R"(/api/maps/([^/]+))", [this](const Req& req, Res& res) {
    if (const auto m = find_map(req, res))
      send_shared(res, m->geometry, m->geometry->json, kJsonType);
  });
  // The page's geometry (map_geometry.h): typed arrays, not compressed by httplib (not text).
  http.Get(R"(/api/maps/([^/]+)/geometry)", [this](const Req& req, Res& res) {
    if (const auto m = find_map(req, res)) {
      send_shared(res, m->geometry, m->geometry->binary, "application/octet-stream");
    }
  });
  post(R"(/api/maps/([^/]+)/condition)", [this](const Req& req, const std::string& body, Res& res) {
    upload_condition(req, body, res);
  });
  http.Get(R"(/api/maps/([^/]+)/driveability)",
           [this](const Req& req, Res& res) { driveability(req, res); });
  http.Get(R"(/api/maps/([^/]+)/findings)",
           [this](const Req& req, Res& res) { findings(req, res); });
  http.Get(R"(/api/maps/([^/]+)/basemap)", [this](const Req& req, Res& res) { basemap(req, res); });
  // Only digits in a tile's path: nothing else reaches the tiles' directory.
  http.Get(R"(/api/tiles/(\d{1,2})/(\d{1,10})/(\d{1,10})\.(png|jpg|jpeg|webp))",
           [this](const Req& req, Res& res) { tile(req, res); });
  post(R"(/api/maps/([^/]+)/validate)",
       [this](const Req& req, const std::string& body, Res& res) { validate(req, body, res); });
  post(R"(/api/maps/([^/]+)/plan)",
       [this](const Req& req, const std::string& body, Res& res) { plan(req, body, res); });
  post(R"(/api/maps/([^/]+)/simulate)",
       [this](const Req& req, const std::string& body, Res& res) { simulate(req, body, res); });
  post(R"(/api/maps/([^/]+)/replay)",
       [this](const Req& req, const std::string& body, Res& res) { replay(req, body, res); });
  post(R"(/api/maps/([^/]+)/geojson)",
       [this](const Req& req, const std::string& body, Res& res) { geojson(req, body, res); });
  post(R"(/api/maps/([^/]+)/campaign)",
       [this](const Req& req, const std::string& body, Res& res) { campaign(req, body, res); });
  http.Get("/api/campaign", [this](const Req&, Res& res) { campaigns->status(res); });
  post("/api/campaign/cancel",
       [this](const Req&, const std::string&, Res& res) { campaigns->cancel(res); });
  http.Get(R"(/api/campaign/runs/([^/]+))",
           [this](const Req& req, Res& res) { campaigns->run_events(req, res); });
  // Any other POST: a 404 without its body read (httplib would read it whole, with no limit if
  // it is chunked).
  http.Post(".*", [this](const Req& req, Res& res, const httplib::ContentReader&) {
    read_whole(req);
    send_json(res, {{"error", {{"code", "http-404"}, {"message", "nothing at " + req.path}}}},
              kNotFound);
  });
  // The page: httplib refuses paths that climb out of the mount ("..").
  if (!options.web_root.empty()) {
    http.set_mount_point("/", options.web_root.string());
    http.set_file_extension_and_mimetype_mapping("js", kJavaScriptType);
    http.set_file_extension_and_mimetype_mapping("mjs", kJavaScriptType);
  }
}

Result<std::unique_ptr<StationServer>> StationServer::create(const ServerOptions& options) {
  auto impl = std::make_unique<Impl>();
  impl->options = options;
  const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
  impl->campaigns = std::make_unique<CampaignService>(CampaignLimits{
      .max_runs = options.max_campaign_runs,
      .max_jobs =
          options.max_campaign_jobs == 0 ? cores : std::min(options.max_campaign_jobs, cores),
      .guard = options.campaign_guard});
  for (const std::filesystem::path& path : options.maps) {
    Diagnostics diagnostics;
    Result<SewerMap> map = options.read_map_with ? options.read_map_with(path, diagnostics)
                                                 : read_map(path, diagnostics);
    if (!map.has_value()) return map.error();
    const std::string id = unique_id(path.stem().string(), impl->taken_ids);
    auto given = std::make_shared<const SewerMap>(std::move(*map));
    Result<std::shared_ptr<const Geometry>> geometry = build_geometry(*given, id);
    if (!geometry.has_value()) {
      return Error{ErrorCode::kInvalidArgument, path.string() + ": " + geometry.error().message};
    }
    std::filesystem::path motion = default_motion_path(path);
    std::error_code ec;
    if (!std::filesystem::exists(motion, ec)) motion.clear();
    impl->maps.push_back(std::make_shared<const LoadedMap>(
        LoadedMap{id,
                  given,
                  given,
                  std::move(*geometry),
                  std::move(motion),
                  {},
                  diagnostics_json(diagnostics, Severity::kWarning),
                  Json::array()}));
  }
  if (!options.tiles.empty()) {
    Result<TileSource> source = parse_tile_source(options.tiles);
    if (!source.has_value()) return source.error();
    impl->tiles = std::move(*source);
  }
  if (!options.web_root.empty() && !std::filesystem::is_directory(options.web_root)) {
    return Error{ErrorCode::kIo, options.web_root.string() + ": no such directory (the page)"};
  }
  impl->routes();
  return std::unique_ptr<StationServer>(new StationServer(std::move(impl)));
}

StationServer::StationServer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
StationServer::~StationServer() { stop(); }

Result<int> StationServer::bind() {
  const int port = impl_->options.port == 0
                       ? impl_->http.bind_to_any_port(impl_->options.host)
                       : (impl_->http.bind_to_port(impl_->options.host, impl_->options.port)
                              ? impl_->options.port
                              : -1);
  if (port < 0) {
    return Error{ErrorCode::kIo, "cannot listen on " + impl_->options.host + ":" +
                                     std::to_string(impl_->options.port)};
  }
  impl_->http.widen_backlog();
  const auto ms = [](double s) {
    return std::chrono::milliseconds(static_cast<std::int64_t>(s * 1000));
  };
  impl_->deadline = std::make_unique<RequestDeadline>(port, ms(impl_->options.headers_deadline_s),
                                                      ms(impl_->options.request_deadline_s));
  return port;
}

// httplib's stop() does nothing before listen_after_bind() is running: stop() waits for run() to
// get there (or to see `stopping` and return) so that a stop right after the start is not lost.
void StationServer::run() {
  impl_->running = true;
  if (impl_->deadline) impl_->deadline->start();
  if (!impl_->stopping) impl_->http.listen_after_bind();
  impl_->running = false;
}

void StationServer::stop() {
  impl_->stopping = true;
  impl_->campaigns->shut_down();  // httplib waits for the requests that run, a campaign's too
  while (impl_->running && !impl_->http.is_running()) std::this_thread::yield();
  impl_->http.stop();
  if (impl_->deadline) impl_->deadline->stop();
}

Result<void> serve_until_signal(const ServerOptions& options,
                                const std::function<void(int port)>& on_listening) {
  Result<std::unique_ptr<StationServer>> created = StationServer::create(options);
  if (!created.has_value()) return created.error();
  StationServer& station = **created;
  // SIGINT and SIGTERM stop the server from a thread of ours, not from a signal handler.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  const Result<int> port = station.bind();
  if (!port.has_value()) return port.error();
  on_listening(*port);
  std::thread waiter([&] {
    int signal = 0;
    sigwait(&signals, &signal);
    station.stop();
  });
  station.run();
  // Stopped by a signal: the waiter has returned. Otherwise wake it so it can be joined.
  pthread_kill(waiter.native_handle(), SIGTERM);
  waiter.join();
  return {};
}

}  // namespace sewerplan::server
