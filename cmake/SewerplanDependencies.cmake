# SPDX-License-Identifier: MIT
# Third-party dependencies, all from Debian 12 packages (scripts/install-deps.sh).
find_package(nlohmann_json 3.10 REQUIRED)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(Boost 1.74 REQUIRED)  # Boost.Graph is header-only
find_package(CLI11 2.0 REQUIRED)
find_package(simdjson 3.0 REQUIRED)  # fast JSON reading (sewerplan/core/json_fields.h)
find_package(pugixml 1.13 REQUIRED)  # ISYBAU XML (core/src/xml_support.h)

# OMPL 1.5.2 on Debian ships no CMake target, its OMPL_LIBRARIES names Boost libraries that are not
# installed, and its pkg-config file forces -std=c++14. Wrap libompl.so in an imported target of our
# own, with its headers as SYSTEM includes so that their warnings are not ours.
if(SEWERPLAN_WITH_OMPL)
  find_library(SEWERPLAN_OMPL_LIBRARY NAMES ompl)
  find_path(SEWERPLAN_OMPL_INCLUDE_DIR NAMES ompl/config.h PATH_SUFFIXES ompl-1.5 ompl-1.6 ompl)
  if(SEWERPLAN_OMPL_LIBRARY AND SEWERPLAN_OMPL_INCLUDE_DIR)
    add_library(sewerplan_ompl_imported SHARED IMPORTED GLOBAL)
    set_target_properties(sewerplan_ompl_imported PROPERTIES
      IMPORTED_LOCATION "${SEWERPLAN_OMPL_LIBRARY}"
      INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${SEWERPLAN_OMPL_INCLUDE_DIR}"
      INTERFACE_INCLUDE_DIRECTORIES "${SEWERPLAN_OMPL_INCLUDE_DIR}")
    add_library(sewerplan::ompl ALIAS sewerplan_ompl_imported)
    message(STATUS "OMPL: ${SEWERPLAN_OMPL_LIBRARY}")
  else()
    message(WARNING "OMPL not found: building without motion planning (SEWERPLAN_WITH_OMPL=OFF)")
    set(SEWERPLAN_WITH_OMPL OFF CACHE BOOL "" FORCE)
  endif()
endif()
