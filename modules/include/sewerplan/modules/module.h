// SPDX-License-Identifier: MIT
// A module: a part of sewerplan built as a shared object of its own (sewerplan_NAME.so) that a
// program loads with dlopen the first time it needs it. A dependency that is costly to load lives
// in a module (OMPL with Boost, cairo with fontconfig and X11, httplib with OpenSSL, GDAL and
// PROJ): linked into a program, every run paid for mapping and relocating its libraries, most of a
// small plan's process (docs/benchmarks.md); behind a module only the runs that need it do.
//
// This library (sewerplan::modules, modules/) is the programs' floor: the command, the tests and
// the benchmarks link it; no library an embedder links does (core, fusion, render, ... have no
// dlopen). A library that needs what a module holds takes it injected (fusion's HeadPathPlanner,
// the station's ServerOptions::gis, render's Canvas), and the program gets it from the module
// (ompl.h, gis.h, png.h beside this header).
//
// A module exports two C symbols:
//   extern "C" const char* sewerplan_NAME_module_stamp();  // its ABI stamp, a plain C string
//   extern "C" const void* sewerplan_NAME_module();        // its table of entry points
// The table is a struct of function pointers over sewerplan's own C++ types, so the module and the
// program must come from the same build: same sources, compiler and flags. The stamp says which:
// the version, the build id (a hash of every library's headers, public and private, and of the
// compiler and flags, cmake/module_build_id.cmake) and the size of every type that crosses the
// table (module_abi_stamp). load_module reads the stamp before it touches the table and refuses a
// module whose stamp is not the program's.
//
//   Result<const OmplTable*> table = load_module_table<OmplTable>(kOmplModule, ompl_stamp());
//   if (!table.has_value()) return Error{table.error().code, "... need OMPL, but " + ...};
//
// Where (module_search_dirs): the directories SEWERPLAN_MODULE_DIR lists (DIR[:DIR...], as PATH),
// if it is set, and only they.
// Else, for code in a shared object (the loader linked into a shared object, such as a module
// that loads another: none does today), its own directory first; then from the directory of the
// binary this code is linked into (the program, or that shared object): where an install puts the
// modules (CMAKE_INSTALL_LIBDIR/sewerplan relative to CMAKE_INSTALL_BINDIR), then where the build
// tree does (lib/sewerplan, one level up from bin/, tests/ and bench/); last the absolute
// directories of the install this tree was configured for and of the Debian package (/usr), for a
// program elsewhere that links sewerplan's libraries. The first file that loads with this build's
// stamp is used; if none does, the error names the first one found and why (not loadable, of
// another build), or every place looked in: never a crash. A refused module stays loaded too (its
// libraries' constructors have run).
//
// Thread safety: load_module may be called from any thread. Each module is loaded once per process
// (under a lock) and never unloaded; a failure is remembered too, so every later call gets the same
// answer.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sewerplan/core/result.h"

namespace sewerplan::modules {

// One type that crosses a module's table, by name and size.
struct ModuleType {
  std::string_view name;
  std::size_t size = 0;
};

// This build's ABI stamp for a table crossed by `types`, e.g.
// "sewerplan 0.1.0 build 3f09c2a1d4e5b6a7; sizes Table 24 SewerMap 1096 ...".
std::string module_abi_stamp(std::span<const ModuleType> types);

// Where load_module looks, in order (see above).
std::vector<std::filesystem::path> module_search_dirs();

// The table of module `name` (file sewerplan_NAME.so), loaded on the first call, if its stamp is
// `stamp`. Otherwise kUnsupportedFormat, the message naming the module's file (or where it was
// looked for) and why: missing, not loadable (dlerror's words), without the entry symbols, or of
// another build (both stamps). `name`: lower case letters, digits and '_'.
Result<const void*> load_module(std::string_view name, const std::string& stamp);

template <class Table>
Result<const Table*> load_module_table(std::string_view name, const std::string& stamp) {
  Result<const void*> table = load_module(name, stamp);
  if (!table.has_value()) return table.error();
  return static_cast<const Table*>(*table);
}

}  // namespace sewerplan::modules
