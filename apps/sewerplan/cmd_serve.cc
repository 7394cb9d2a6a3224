// SPDX-License-Identifier: MIT
// sewerplan serve [--map FILE ...] [--host 127.0.0.1] [--port 8080] [--token T] [--web DIR]
//                 [--allow-host NAME ...] [--tiles URL|DIR] [--max-connections 256]
// The operator station (docs/operator-station.md): the server of server/station_server.h, loaded
// from the server module (sewerplan/modules/server_table.h), and the page.
#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "sewerplan/core/map_io.h"
#include "sewerplan/modules/module.h"
#include "sewerplan/modules/server_table.h"
#if SEWERPLAN_WITH_GIS
#include "sewerplan/modules/gis.h"
#endif

#include "command.h"
#include "json_output.h"
#include "map_input.h"

namespace sewerplan::cli {
namespace {

struct ServeOptions {
  std::vector<std::string> maps;
  std::string gis_fields;  // --gis-fields: for the GIS sources among the maps
  std::string host = "127.0.0.1";
  int port = 8080;
  std::string token;
  std::string web;
  std::vector<std::string> allowed_hosts;
  std::string tiles;
  int max_connections = static_cast<int>(server::ServerOptions{}.max_connections);
};

// The host as the socket takes it: an IPv6 address without the brackets a URL puts around it.
std::string bare_host(const std::string& host) {
  if (host.size() > 2 && host.front() == '[' && host.back() == ']') {
    return host.substr(1, host.size() - 2);
  }
  return host;
}

// The station's address: an IPv6 address in brackets ("http://[::1]:8080/"), as every URL has it
// (RFC 3986): "http://::1:8080/" is no address a browser opens.
std::string station_url(const std::string& host, int port) {
  const bool ipv6 = host.find(':') != std::string::npos;
  return "http://" + (ipv6 ? "[" + host + "]" : host) + ":" + std::to_string(port) + "/";
}

// The built page: --web, else the build tree's (while developing), else the install's
// share/sewerplan/web beside bin/.
std::filesystem::path web_root(const std::string& option) {
  if (!option.empty()) return option;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path installed = exe.parent_path().parent_path() / "share/sewerplan/web";
    if (std::filesystem::is_directory(installed / "assets")) return installed;
  }
#ifdef SEWERPLAN_WEB_BUILD_DIR
  if (std::filesystem::is_directory(SEWERPLAN_WEB_BUILD_DIR)) return SEWERPLAN_WEB_BUILD_DIR;
#endif
  return {};
}

int run(const ServeOptions& o, Context& c) {
  // A mapping applies to the GIS maps only; with none among them it would be ignored silently.
  if (!o.gis_fields.empty() && std::none_of(o.maps.begin(), o.maps.end(), is_gis_source_path)) {
    return usage_error(c, false,
                       "serve: --gis-fields " + o.gis_fields +
                           ": none of the maps is a GIS source (GeoPackage, Shapefile or a "
                           "directory of them)");
  }
  // The station, with cpp-httplib and OpenSSL, is a module (sewerplan/modules/server_table.h):
  // loaded by this command only.
  static const std::string stamp = modules::server_stamp();
  const Result<const modules::ServerTable*> module =
      modules::load_module_table<modules::ServerTable>(modules::kServerModule, stamp);
  if (!module.has_value()) {
    return fail(c, false,
                Error{module.error().code,
                      "serve needs cpp-httplib and OpenSSL, but " + module.error().message});
  }
  const std::string host = bare_host(o.host);
  server::ServerOptions options{
      .host = host, .port = o.port, .token = o.token, .allowed_hosts = o.allowed_hosts};
  options.tiles = o.tiles;
  options.max_connections = static_cast<std::size_t>(o.max_connections);
  for (const std::string& m : o.maps) options.maps.emplace_back(m);
  // The reader's warnings on stderr, as every command's (an error fails the start with its own
  // message); the page lists them too, each linked to its objects on the map.
  options.read_map_with = [fields = o.gis_fields, &c](const std::filesystem::path& path,
                                                      Diagnostics& diagnostics) {
    Result<SewerMap> map = read_input_map(
        {path.string(), is_gis_source_path(path) ? fields : std::string()}, diagnostics);
    if (map.has_value()) print_diagnostics(diagnostics, c.err);
    return map;
  };
#if SEWERPLAN_WITH_GIS
  // The basemap and the GeoJSON export through this program's GIS module, loaded when a page asks.
  options.gis = modules::station_gis();
#endif
  options.web_root = web_root(o.web);
  if (options.web_root.empty()) {
    c.err << "sewerplan serve: the page is not built (SEWERPLAN_WEB=ON, or --web DIR): API only\n";
  }
  if (host != "127.0.0.1" && host != "localhost" && host != "::1") {
    c.err << "sewerplan serve: warning: listening on " << host << ", reachable from other machines"
          << (o.token.empty() ? " without a --token" : "") << '\n';
  }
  Result<void> served = (*module)->serve_until_signal(options, [&](int port) {
    // The token in the fragment, which the browser keeps to itself: never in a request's URL, so
    // in no server's or proxy's log (the page sends it as a header, web/src/api.js).
    c.out << "sewerplan serve: " << station_url(host, port)
          << (o.token.empty() ? "" : "#token=" + o.token) << std::endl;
  });
  if (!served.has_value()) return fail(c, false, served.error());
  return kExitOk;
}

}  // namespace

void add_serve_command(CLI::App& app, Context& context) {
  // Shared with the callback, which CLI11 keeps after this function returns.
  auto o = std::make_shared<ServeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "serve",
      "The operator station: a web server with the maps, and the page (docs/operator-station.md)");
  cmd->add_option("--map", o->maps, "A map to offer (any format of docs/formats/); repeatable");
  add_gis_fields_option(*cmd, o->gis_fields);
  cmd->add_option("--host", o->host, "Address to listen on")->capture_default_str();
  cmd->add_option("--port", o->port, "Port to listen on (0: any free port)")
      ->capture_default_str()
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--token", o->token,
                  "Require \"Authorization: Bearer TOKEN\" on the API (the printed address "
                  "carries it in its #fragment, for the page)");
  cmd->add_option("--allow-host", o->allowed_hosts,
                  "A name the page may be opened under besides IP addresses, localhost and --host "
                  "(requests naming another Host are refused: DNS rebinding); repeatable");
  cmd->add_option(
      "--tiles", o->tiles,
      "A basemap for the page, off until the operator turns it on: an XYZ template "
      "(https://.../{z}/{x}/{y}.png, the browser fetches it) or a directory of Z/X/Y.png "
      "tiles (served by the station: no internet needed)");
  cmd->add_option("--max-connections", o->max_connections,
                  "Connections served at once, each on a thread of its own; more wait their turn "
                  "(a connection serves one request, and one that sends nothing for 5 s is closed)")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--web", o->web, "Serve the page from this directory (default: the built one)");
  cmd->callback([o, &context] { context.exit_code = run(*o, context); });
}

}  // namespace sewerplan::cli
