// SPDX-License-Identifier: MIT
// The server module's two exported symbols (sewerplan/modules/server_table.h, module.h): its ABI
// stamp and the table of the station's entry point, built into sewerplan_server.so with
// everything else, cpp-httplib's users among it, hidden.
#include <string>

#include "sewerplan/modules/server_table.h"
#include "sewerplan/server/station_server.h"

namespace sewerplan::modules {
namespace {

const ServerTable kTable{.serve_until_signal = &server::serve_until_signal};

}  // namespace
}  // namespace sewerplan::modules

extern "C" __attribute__((visibility("default"))) const char* sewerplan_server_module_stamp() {
  static const std::string stamp = sewerplan::modules::server_stamp();
  return stamp.c_str();
}

extern "C" __attribute__((visibility("default"))) const void* sewerplan_server_module() {
  return &sewerplan::modules::kTable;
}
