// SPDX-License-Identifier: MIT
// The GIS module (sewerplan/gis/module.h), loaded on first use through the module loader
// (sewerplan/core/module.h): the one place the sewerplan command reaches GDAL and PROJ. A module
// that is missing, cannot be loaded or is of another build or configuration is an error
// (kUnsupportedFormat) naming the file and why (both stamps), never a crash.
//
// Thread safety: load_module's (any thread).
#pragma once

#include "sewerplan/core/result.h"
#include "sewerplan/gis/module.h"

namespace sewerplan::cli {

// `need`: what asked for it ("reading sewers.gpkg"), for the error.
Result<const gis::ModuleTable*> gis_module(const std::string& need);

}  // namespace sewerplan::cli
