// SPDX-License-Identifier: MIT
// The GIS module (sewerplan/gis/module.h), loaded on first use: the one place the sewerplan command
// reaches GDAL and PROJ. The module is found relative to the executable, at
// SEWERPLAN_GIS_MODULE_RELATIVE (../lib/sewerplan/sewerplan_gis.so), which holds both in the build
// tree (bin/ and lib/sewerplan/ under the build directory) and in an install (cmake --install, the
// Debian package). A module that is missing, cannot be loaded or is of another version is an error
// (kUnsupportedFormat) naming the file and why, never a crash.
//
// Thread safety: the first call loads the module under a lock (a function-local static); later
// calls only read.
#pragma once

#include "sewerplan/core/result.h"
#include "sewerplan/gis/module.h"

namespace sewerplan::cli {

// `need`: what asked for it ("reading sewers.gpkg"), for the error.
Result<const gis::ModuleTable*> gis_module(const std::string& need);

}  // namespace sewerplan::cli
