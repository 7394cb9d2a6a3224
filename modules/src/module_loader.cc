// SPDX-License-Identifier: MIT
#include <cstdlib>
#include <map>
#include <mutex>
#include <system_error>
#include <utility>

#include "sewerplan/modules/module.h"

#include <dlfcn.h>
#include <link.h>

namespace sewerplan::modules {
namespace {

struct Loaded {
  const void* table = nullptr;
  std::string error;  // why not, when table is null
};

// The binary this code is linked into: the program (/proc/self/exe), or the shared object holding
// it (its link map names it as it was loaded), such as a module or the Python module.
struct OwnBinary {
  std::filesystem::path directory;  // empty if unknown
  bool shared_object = false;
};

OwnBinary own_binary() {
  static const char anchor = 0;
  Dl_info info{};
  link_map* map = nullptr;
  if (dladdr1(&anchor, &info, reinterpret_cast<void**>(&map), RTLD_DL_LINKMAP) != 0 &&
      map != nullptr && map->l_name != nullptr && map->l_name[0] != '\0') {
    std::error_code ec;
    const std::filesystem::path object = std::filesystem::canonical(map->l_name, ec);
    if (!ec) return {.directory = object.parent_path(), .shared_object = true};
  }
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return {.directory = ec ? std::filesystem::path{} : exe.parent_path()};
}

bool valid_name(std::string_view name) {
  if (name.empty()) return false;
  for (const char c : name) {
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
  }
  return true;
}

// The module in `file`, if it loads and its stamp is `stamp`.
Loaded load_file(const std::filesystem::path& file, const std::string& name,
                 const std::string& stamp) {
  const std::string what = "the " + name + " module " + file.string();
  // RTLD_LOCAL: the module's libraries stay out of the program's symbol lookups.
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* why = dlerror();
    return {.error = what + " cannot be loaded: " + (why != nullptr ? why : "unknown reason")};
  }
  // dlsym's void* to a function pointer: POSIX guarantees the conversion. The stamp is a plain C
  // string, read before anything of the table's C++ types is touched.
  const std::string stamp_symbol = "sewerplan_" + name + "_module_stamp";
  using StampEntry = const char* (*)();
  const auto stamp_entry = reinterpret_cast<StampEntry>(dlsym(handle, stamp_symbol.c_str()));
  if (stamp_entry == nullptr) {
    return {.error = what + " has no ABI stamp (" + stamp_symbol + "): it is of another sewerplan"};
  }
  const char* theirs = stamp_entry();
  if (theirs == nullptr || stamp != theirs) {
    std::string error =
        what + " is of another build or configuration of sewerplan (its ABI stamp: \"" +
        (theirs != nullptr ? theirs : "") + "\", this sewerplan's: \"" + stamp + "\")";
    return {.error = std::move(error)};
  }
  const std::string table_symbol = "sewerplan_" + name + "_module";
  using TableEntry = const void* (*)();
  const auto entry = reinterpret_cast<TableEntry>(dlsym(handle, table_symbol.c_str()));
  const void* table = entry != nullptr ? entry() : nullptr;
  if (table == nullptr) {
    return {.error = what + " has no table (" + table_symbol + ")"};
  }
  // Never unloaded, nor is a refused one: its libraries' constructors have run (RTLD_NOW), and one
  // may have registered atexit handlers or threads that an unload would leave dangling.
  return {.table = table};
}

// The first file in the search directories that loads with this stamp; else why the first one that
// exists did not (a stale module of another install earlier on the path does not hide a good one
// later), or where it was looked for.
Loaded load(const std::string& name, const std::string& stamp) {
  const std::string file = "sewerplan_" + name + ".so";
  const std::vector<std::filesystem::path> dirs = module_search_dirs();
  std::error_code ec;
  Loaded first_failure;
  for (const std::filesystem::path& dir : dirs) {
    if (!std::filesystem::exists(dir / file, ec)) continue;
    Loaded loaded = load_file(dir / file, name, stamp);
    if (loaded.table != nullptr) return loaded;
    if (first_failure.error.empty()) first_failure = std::move(loaded);
  }
  if (!first_failure.error.empty()) return first_failure;
  std::string where;
  for (const std::filesystem::path& dir : dirs) {
    where += (where.empty() ? "" : ", ") + (dir / file).string();
  }
  return {.error = "the " + name + " module is missing (looked for " + where + ")"};
}

}  // namespace

std::vector<std::filesystem::path> module_search_dirs() {
  // getenv: read when a module is first looked for; nothing in sewerplan sets the environment.
  if (const char* dir = std::getenv("SEWERPLAN_MODULE_DIR"); dir != nullptr && dir[0] != '\0') {
    std::vector<std::filesystem::path> dirs;  // a list, as PATH: DIR[:DIR...]
    std::string_view rest(dir);
    while (!rest.empty()) {
      const std::size_t colon = rest.find(':');
      const std::string_view one = rest.substr(0, colon);
      if (!one.empty()) dirs.emplace_back(one);
      rest = colon == std::string_view::npos ? std::string_view{} : rest.substr(colon + 1);
    }
    return dirs;
  }
  std::vector<std::filesystem::path> dirs;
  auto add = [&](const std::filesystem::path& dir) {
    const std::filesystem::path normal = dir.lexically_normal();
    for (const std::filesystem::path& d : dirs) {
      if (d == normal) return;
    }
    dirs.push_back(normal);
  };
  const OwnBinary own = own_binary();
  if (!own.directory.empty()) {
    // The loader in a shared object (a module in lib/sewerplan that loads another; none does
    // today): the modules beside it first, wherever the install was moved.
    if (own.shared_object) add(own.directory);
    add(own.directory / SEWERPLAN_MODULE_INSTALL_RELATIVE);
    add(own.directory / ".." / "lib" / "sewerplan");
  }
  // For a program elsewhere that links sewerplan's libraries: the install this tree was configured
  // for, then the Debian package's (cpack installs under /usr, whatever the configured prefix).
  add(SEWERPLAN_MODULE_INSTALL_DIR);
  add(SEWERPLAN_MODULE_PACKAGE_DIR);
  return dirs;
}

Result<const void*> load_module(std::string_view name, const std::string& stamp) {
  if (!valid_name(name)) {
    return Error{ErrorCode::kInvalidArgument,
                 "load_module: \"" + std::string(name) +
                     "\" is not a module name (lower case letters, digits and '_')"};
  }
  // Never destroyed: a thread may still ask while the process exits, and the modules stay loaded.
  static auto* const mutex = new std::mutex;
  static auto* const loaded = new std::map<std::string, Loaded, std::less<>>;
  const std::lock_guard lock(*mutex);
  auto it = loaded->find(name);
  if (it == loaded->end()) {
    const std::string key(name);
    it = loaded->emplace(key, load(key, stamp)).first;
  }
  if (it->second.table == nullptr) return Error{ErrorCode::kUnsupportedFormat, it->second.error};
  return it->second.table;
}

}  // namespace sewerplan::modules
