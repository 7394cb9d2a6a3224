# SPDX-License-Identifier: MIT
# `cmake --install` puts the libraries, their public headers, the CLI and a CMake package config
# under the prefix, so that another project can find_package(sewerplan) and link sewerplan::core;
# and beside it a pkg-config file, sewerplan.pc, for a project built without CMake. The libraries'
# files are the install component dev (the Debian package sewerplan-dev), the CLI runtime.
include(CMakePackageConfigHelpers)

get_property(sewerplan_libraries GLOBAL PROPERTY SEWERPLAN_LIBRARIES)
install(TARGETS ${sewerplan_libraries}
  EXPORT sewerplanTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(lib IN LISTS sewerplan_libraries)
  get_target_property(lib_dir ${lib} SOURCE_DIR)
  install(DIRECTORY ${lib_dir}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT dev)
endforeach()
if(TARGET sewerplan_cli)
  install(TARGETS sewerplan_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/sewerplan)
install(EXPORT sewerplanTargets NAMESPACE sewerplan:: DESTINATION ${config_dir} COMPONENT dev)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/sewerplanConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/sewerplanConfig.cmake INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/sewerplanConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/sewerplanConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/sewerplanConfigVersion.cmake
        DESTINATION ${config_dir} COMPONENT dev)

# sewerplan.pc (LIBDIR/pkgconfig): every installed library, dependents first, and what they need,
# from the same target lists as the CMake package. Static libraries need their private
# dependencies on every link, so those go into Requires and Libs; shared ones into the .private
# fields. The headers need C++20: the consumer compiles with -std=c++20 or later.
set(pc_known_dependencies  # the dependency as the libraries link it, then its pkg-config module
    simdjson::simdjson simdjson nlohmann_json::nlohmann_json nlohmann_json Eigen3::Eigen eigen3
    pugixml::pugixml pugixml proj proj gdal gdal)
set(pc_libs)
set(pc_seen)
set(pc_public)
set(pc_private)
set(pc_system_libs)
set(sewerplan_static_libraries OFF)
foreach(lib IN LISTS sewerplan_libraries)
  get_target_property(lib_type ${lib} TYPE)
  if(lib_type STREQUAL "STATIC_LIBRARY")
    set(sewerplan_static_libraries ON)
  endif()
  get_target_property(lib_name ${lib} OUTPUT_NAME)
  list(PREPEND pc_libs "-l${lib_name}")  # registered after what it uses: dependents first
  list(APPEND pc_seen ${lib})
  get_target_property(lib_public ${lib} INTERFACE_LINK_LIBRARIES)
  get_target_property(lib_all ${lib} LINK_LIBRARIES)
  foreach(dep IN LISTS lib_all)
    if(dep MATCHES "^sewerplan::(.*)$")
      # Linked after what it uses only if that was registered first (add_subdirectory's order).
      if(NOT "sewerplan_${CMAKE_MATCH_1}" IN_LIST pc_seen)
        message(FATAL_ERROR "sewerplan.pc: ${lib} uses ${dep}, registered after it")
      endif()
      continue()
    elseif(dep IN_LIST CMAKE_DL_LIBS)
      list(APPEND pc_system_libs "-l${dep}")
      continue()
    endif()
    list(FIND pc_known_dependencies ${dep} at)
    math(EXPR parity "${at} % 2")
    if(at EQUAL -1 OR parity EQUAL 1)
      message(FATAL_ERROR "sewerplan.pc: ${lib} links ${dep}, which has no pkg-config module in "
                          "cmake/SewerplanInstall.cmake's pc_known_dependencies")
    endif()
    math(EXPR at "${at} + 1")
    list(GET pc_known_dependencies ${at} module)
    if(dep IN_LIST lib_public)
      list(APPEND pc_public ${module})
    else()
      list(APPEND pc_private ${module})
    endif()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES pc_public)
list(REMOVE_DUPLICATES pc_private)
list(REMOVE_ITEM pc_private ${pc_public})
list(REMOVE_DUPLICATES pc_system_libs)
string(JOIN " " SEWERPLAN_PC_LIBS ${pc_libs})
if(sewerplan_static_libraries)
  string(JOIN ", " SEWERPLAN_PC_REQUIRES ${pc_public} ${pc_private})
  set(SEWERPLAN_PC_REQUIRES_PRIVATE "")
  string(JOIN " " pc_system ${pc_system_libs})
  string(APPEND SEWERPLAN_PC_LIBS " ${pc_system}")
  set(SEWERPLAN_PC_LIBS_PRIVATE "")
else()
  string(JOIN ", " SEWERPLAN_PC_REQUIRES ${pc_public})
  string(JOIN ", " SEWERPLAN_PC_REQUIRES_PRIVATE ${pc_private})
  string(JOIN " " SEWERPLAN_PC_LIBS_PRIVATE ${pc_system_libs})
endif()
file(RELATIVE_PATH SEWERPLAN_PC_TO_PREFIX /${CMAKE_INSTALL_LIBDIR}/pkgconfig /)
string(REGEX REPLACE "/$" "" SEWERPLAN_PC_TO_PREFIX "${SEWERPLAN_PC_TO_PREFIX}")
configure_file(${CMAKE_CURRENT_LIST_DIR}/sewerplan.pc.in ${CMAKE_CURRENT_BINARY_DIR}/sewerplan.pc
               @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/sewerplan.pc
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT dev)
