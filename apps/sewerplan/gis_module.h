// SPDX-License-Identifier: MIT
// The GIS module (sewerplan/gis/module.h), loaded on first use: the one place the sewerplan command
// reaches GDAL and PROJ. The module is found relative to the executable: first where an install
// puts it (SEWERPLAN_GIS_MODULE_INSTALL_RELATIVE, from CMAKE_INSTALL_BINDIR to
// CMAKE_INSTALL_LIBDIR/sewerplan, e.g. ../lib/sewerplan/sewerplan_gis.so), then where the build
// tree does (SEWERPLAN_GIS_MODULE_BUILD_RELATIVE, bin/ to lib/sewerplan/); the first that loads
// with this program's ABI stamp (sewerplan/gis/module.h) is used. A module that is missing, cannot
// be loaded or is of another build or configuration is an error (kUnsupportedFormat) naming the
// file and why (both stamps), never a crash.
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
