// SPDX-License-Identifier: MIT
// module_abi_stamp (module.h): apart from the loader, so that a module, which needs its own stamp
// but loads nothing, links no dlopen.
#include <string>

#include "sewerplan/modules/module.h"

#include "sewerplan_module_build_id.h"

namespace sewerplan::modules {

std::string module_abi_stamp(std::span<const ModuleType> types) {
  std::string stamp =
      "sewerplan " SEWERPLAN_MODULE_VERSION " build " SEWERPLAN_MODULE_BUILD_ID "; sizes";
  for (const ModuleType& t : types) {
    stamp += ' ';
    stamp += t.name;
    stamp += ' ';
    stamp += std::to_string(t.size);
  }
  return stamp;
}

}  // namespace sewerplan::modules
