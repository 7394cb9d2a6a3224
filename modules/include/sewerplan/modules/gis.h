// SPDX-License-Identifier: MIT
// The GIS module (gis_table.h), loaded on first use through the module loader (module.h): the one
// place a program reaches GDAL and PROJ without linking them. A module that is missing, cannot be
// loaded or is of another build or configuration is an error (kUnsupportedFormat) naming the file
// and why (both stamps), never a crash.
//
//   Result<const GisTable*> gis = gis_module("reading sewers.gpkg");
//   if (!gis.has_value()) return gis.error();  // "reading ... needs GDAL and PROJ, but ..."
//   server::ServerOptions options{.gis = station_gis()};  // loaded when a page asks
//
// Thread safety: load_module's (any thread).
#pragma once

#include <string>
#include <string_view>

#include "sewerplan/core/result.h"
#include "sewerplan/modules/gis_table.h"
#include "sewerplan/server/station_gis.h"

namespace sewerplan::modules {

// `need`: what asked for it ("reading sewers.gpkg"), for the error: "NEED needs WHAT, but ...".
Result<const GisTable*> gis_module(const std::string& need,
                                   std::string_view what = "GDAL and PROJ");

// The station's GIS functions (server/station_gis.h) through the GIS module, each loading it on
// its first call: the basemap's errors say "the basemap needs PROJ, but ...", the export's "the
// GeoJSON export needs GDAL and PROJ, but ...".
server::StationGis station_gis();

}  // namespace sewerplan::modules
