// SPDX-License-Identifier: MIT
// The server module: the operator station's HTTP server (station_server.h) behind one table in a
// shared module (sewerplan_server.so) that `sewerplan serve` loads with dlopen. cpp-httplib comes
// with OpenSSL (libssl, libcrypto) and brotli; linked into the command, every run paid for loading
// and relocating them, milliseconds of a small plan's process (docs/benchmarks.md). Behind the
// module only `serve` loads them. The JSON documents the CLI shares with the station (documents.h,
// driveability_output.h, sim_setup.h) need no HTTP and stay in the server library the command
// links.
//
// A module of sewerplan (module.h), named "server": it exports sewerplan_server_module_stamp, its
// ABI stamp (server_stamp() below as built into it), and sewerplan_server_module, the table. It
// loads no module itself: what the station needs of GDAL and PROJ comes in ServerOptions::gis,
// functions of the program that loaded it (gis.h: station_gis).
//
// Thread safety: serve_until_signal's (station_server.h): the whole of a program's run.
#pragma once

#include <functional>
#include <string>

#include "sewerplan/core/result.h"
#include "sewerplan/modules/module.h"
#include "sewerplan/server/station_server.h"

namespace sewerplan::modules {

struct ServerTable {
  // serve_until_signal (station_server.h).
  Result<void> (*serve_until_signal)(const server::ServerOptions& options,
                                     const std::function<void(int port)>& on_listening);
};

inline constexpr const char* kServerModule = "server";

// This build's ABI stamp for the table: the size of every type crossing it (module.h).
inline std::string server_stamp() {
  const ModuleType types[] = {
      {"ServerTable", sizeof(ServerTable)},
      {"ServerOptions", sizeof(server::ServerOptions)},
      {"StationGis", sizeof(server::StationGis)},
      {"MapReader", sizeof(server::MapReader)},
      {"Result<SewerMap>", sizeof(Result<SewerMap>)},
      {"SewerMap", sizeof(SewerMap)},
      {"Diagnostics", sizeof(Diagnostics)},
      {"path", sizeof(std::filesystem::path)},
      {"string", sizeof(std::string)},
      {"function<void(int)>", sizeof(std::function<void(int)>)},
      {"Result<void>", sizeof(Result<void>)},
  };
  return module_abi_stamp(types);
}

}  // namespace sewerplan::modules
