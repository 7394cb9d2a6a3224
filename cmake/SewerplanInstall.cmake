# SPDX-License-Identifier: MIT
# `cmake --install` puts the libraries, their public headers, the CLI and a CMake package config
# under the prefix, so that another project can find_package(sewerplan) and link sewerplan::core.
include(CMakePackageConfigHelpers)

get_property(sewerplan_libraries GLOBAL PROPERTY SEWERPLAN_LIBRARIES)
install(TARGETS ${sewerplan_libraries}
  EXPORT sewerplanTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(lib IN LISTS sewerplan_libraries)
  get_target_property(lib_dir ${lib} SOURCE_DIR)
  install(DIRECTORY ${lib_dir}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()
if(TARGET sewerplan_cli)
  install(TARGETS sewerplan_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/sewerplan)
install(EXPORT sewerplanTargets NAMESPACE sewerplan:: DESTINATION ${config_dir})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/sewerplanConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/sewerplanConfig.cmake INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/sewerplanConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/sewerplanConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/sewerplanConfigVersion.cmake
        DESTINATION ${config_dir})
