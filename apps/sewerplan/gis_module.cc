// SPDX-License-Identifier: MIT
#include "gis_module.h"

#include <filesystem>
#include <string>
#include <system_error>

#include <dlfcn.h>

namespace sewerplan::cli {
namespace {

struct Loaded {
  const gis::ModuleTable* table = nullptr;
  std::string error;  // why not, when table is null
};

Loaded load() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec)
    return {.error = "cannot find the sewerplan executable (/proc/self/exe): " + ec.message()};
  const std::filesystem::path file =
      (exe.parent_path() / SEWERPLAN_GIS_MODULE_RELATIVE).lexically_normal();
  if (!std::filesystem::exists(file, ec)) {
    return {.error = "the GIS module " + file.string() +
                     " is missing (it is built and installed with SEWERPLAN_WITH_GIS)"};
  }
  // RTLD_LOCAL: GDAL's closure stays out of the program's symbol lookups.
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* why = dlerror();
    return {.error = "the GIS module " + file.string() +
                     " cannot be loaded: " + (why != nullptr ? why : "unknown reason")};
  }
  // dlsym's void* to a function pointer: POSIX guarantees the conversion.
  const auto entry = reinterpret_cast<gis::ModuleEntry>(dlsym(handle, gis::kModuleEntry));
  if (entry == nullptr) {
    return {.error = "the GIS module " + file.string() + " has no " + gis::kModuleEntry};
  }
  const gis::ModuleTable* table = entry();
  if (table == nullptr || std::string(table->version) != SEWERPLAN_GIS_MODULE_VERSION) {
    return {.error = "the GIS module " + file.string() + " is of version " +
                     (table != nullptr ? table->version : "?") + ", this sewerplan of " +
                     SEWERPLAN_GIS_MODULE_VERSION};
  }
  return {.table = table};  // never unloaded: GDAL registers atexit handlers
}

}  // namespace

Result<const gis::ModuleTable*> gis_module(const std::string& need) {
  static const Loaded loaded = load();
  if (loaded.table == nullptr) {
    return Error{ErrorCode::kUnsupportedFormat, need + " needs GDAL and PROJ, but " + loaded.error};
  }
  return loaded.table;
}

}  // namespace sewerplan::cli
