// SPDX-License-Identifier: MIT
#include "gis_module.h"

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "sewerplan/version.h"

#include "sewerplan_gis_build_id.h"
#include <dlfcn.h>

namespace sewerplan::cli {
namespace {

struct Loaded {
  const gis::ModuleTable* table = nullptr;
  std::string error;  // why not, when table is null
};

// Where to look, from the executable's directory: where an install puts the module, then where the
// build tree does (cmake/SewerplanGisModule.cmake); once when both are the same.
std::vector<std::filesystem::path> candidates(const std::filesystem::path& exe_dir) {
  std::vector<std::filesystem::path> files{
      (exe_dir / SEWERPLAN_GIS_MODULE_INSTALL_RELATIVE).lexically_normal()};
  const std::filesystem::path build =
      (exe_dir / SEWERPLAN_GIS_MODULE_BUILD_RELATIVE).lexically_normal();
  if (build != files.front()) files.push_back(build);
  return files;
}

// The module in `file`, if it loads and its ABI stamp is this program's.
Loaded load_file(const std::filesystem::path& file) {
  // RTLD_LOCAL: GDAL's closure stays out of the program's symbol lookups.
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* why = dlerror();
    return {.error = "the GIS module " + file.string() +
                     " cannot be loaded: " + (why != nullptr ? why : "unknown reason")};
  }
  // dlsym's void* to a function pointer: POSIX guarantees the conversion. The stamp is a plain C
  // string, read before anything of the table's C++ types is touched.
  const auto stamp_entry =
      reinterpret_cast<gis::ModuleStampEntry>(dlsym(handle, gis::kModuleStampEntry));
  if (stamp_entry == nullptr) {
    return {.error = "the GIS module " + file.string() + " has no ABI stamp (" +
                     gis::kModuleStampEntry + "): it is of another sewerplan"};
  }
  const std::string ours = gis::module_abi_stamp(kVersion, SEWERPLAN_GIS_BUILD_ID);
  const char* theirs = stamp_entry();
  if (theirs == nullptr || ours != theirs) {
    return {.error = "the GIS module " + file.string() +
                     " is of another build or configuration of sewerplan (its ABI stamp: \"" +
                     (theirs != nullptr ? theirs : "") + "\", this sewerplan's: \"" + ours + "\")"};
  }
  const auto entry = reinterpret_cast<gis::ModuleEntry>(dlsym(handle, gis::kModuleEntry));
  const gis::ModuleTable* table = entry != nullptr ? entry() : nullptr;
  if (table == nullptr) {
    return {.error = "the GIS module " + file.string() + " has no " + gis::kModuleEntry};
  }
  return {.table = table};  // never unloaded: GDAL registers atexit handlers
}

Loaded load() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec)
    return {.error = "cannot find the sewerplan executable (/proc/self/exe): " + ec.message()};
  const std::vector<std::filesystem::path> files = candidates(exe.parent_path());
  // The first that loads; else why the first that exists did not.
  Loaded first_failure;
  for (const std::filesystem::path& file : files) {
    if (!std::filesystem::exists(file, ec)) continue;
    Loaded loaded = load_file(file);
    if (loaded.table != nullptr) return loaded;
    if (first_failure.error.empty()) first_failure = std::move(loaded);
  }
  if (!first_failure.error.empty()) return first_failure;
  std::string where = files.front().string();
  if (files.size() > 1) where += " (nor " + files.back().string() + ")";
  return {.error = "the GIS module " + where +
                   " is missing (it is built and installed with SEWERPLAN_WITH_GIS)"};
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
