// SPDX-License-Identifier: MIT
// The server module's two exported symbols (sewerplan/server/module.h, sewerplan/core/module.h):
// its ABI stamp and the table of the station's entry point, built into sewerplan_server.so with
// everything else, cpp-httplib's users among it, hidden.
#include <string>

#include "sewerplan/server/module.h"
#include "sewerplan/server/station_server.h"

namespace sewerplan::server {
namespace {

const ModuleTable kTable{.serve_until_signal = &serve_until_signal};

}  // namespace
}  // namespace sewerplan::server

extern "C" __attribute__((visibility("default"))) const char* sewerplan_server_module_stamp() {
  static const std::string stamp = sewerplan::server::module_stamp();
  return stamp.c_str();
}

extern "C" __attribute__((visibility("default"))) const void* sewerplan_server_module() {
  return &sewerplan::server::kTable;
}
