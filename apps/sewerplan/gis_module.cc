// SPDX-License-Identifier: MIT
#include "gis_module.h"

#include <string>

#include "sewerplan/core/module.h"

namespace sewerplan::cli {

Result<const gis::ModuleTable*> gis_module(const std::string& need) {
  static const std::string stamp = gis::module_stamp();
  Result<const gis::ModuleTable*> table =
      load_module_table<gis::ModuleTable>(gis::kModuleName, stamp);
  if (!table.has_value()) {
    return Error{table.error().code, need + " needs GDAL and PROJ, but " + table.error().message};
  }
  return *table;
}

}  // namespace sewerplan::cli
