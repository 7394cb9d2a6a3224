# SPDX-License-Identifier: MIT
# The Debian package: `cpack -G DEB` in a build tree writes sewerplan_<version>_amd64.deb with what
# `cmake --install` puts under the prefix (the CLI and sewerplan-compare, the libraries and their
# headers, the CMake package, version.h), plus the docs, the AIS test environment as example data,
# the man page and the bash completion. Binaries and libraries are stripped of their debug info in
# the package; with SEWERPLAN_PYTHON the Python module goes into Debian's python3 dist-packages;
# its run-time dependencies come from dpkg-shlibdeps, and the -dev packages that
# find_package(sewerplan) needs (cmake/sewerplanConfig.cmake.in) are listed. tests/install/deb_test.sh
# builds it and installs it into a scratch root.
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/LICENSE
        DESTINATION ${CMAKE_INSTALL_DOCDIR} OPTIONAL)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/datasets/ais-testbed
        DESTINATION ${CMAKE_INSTALL_DATADIR}/sewerplan/datasets)
# (The bash completion is written and installed by apps/CMakeLists.txt.)
if(TARGET sewerplan_python)  # finds the example data beside it: ../../datasets/ais-testbed
  install(PROGRAMS ${PROJECT_SOURCE_DIR}/examples/python/plan_ais.py
          DESTINATION ${CMAKE_INSTALL_DATADIR}/sewerplan/examples/python)
endif()
if(TARGET sewerplan-compare)
  install(TARGETS sewerplan-compare RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

# CPACK_STRIP_FILES strips executables but not static libraries: strip their debug info too when
# the install strips (cpack, cmake --install --strip).
install(CODE "
  if(CMAKE_INSTALL_DO_STRIP)
    file(GLOB sewerplan_static_libs
         \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/libsewerplan_*.a\")
    foreach(lib IN LISTS sewerplan_static_libs)
      execute_process(COMMAND \"${CMAKE_STRIP}\" --strip-debug \"\${lib}\")
    endforeach()
  endif()")

set(CPACK_PACKAGE_NAME sewerplan)
set(CPACK_PACKAGE_VENDOR "sewerplan")
set(CPACK_PACKAGE_CONTACT "sewerplan maintainers <sewerplan@example.org>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX ${SEWERPLAN_PACKAGE_PREFIX})  # cmake/SewerplanModule.cmake
set(CPACK_STRIP_FILES ON)
set(CPACK_GENERATOR DEB)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # sewerplan_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(sewerplan_dev_depends "nlohmann-json3-dev (>= 3.10), libeigen3-dev (>= 3.3), libsimdjson-dev, libpugixml-dev")
# No libompl-dev or libcairo2-dev: OMPL and cairo are linked by their modules only
# (docs/modules.md), whose runtime dependencies (libompl16, libcairo2) dpkg-shlibdeps finds.
if(TARGET sewerplan_python)  # built for one python3 version (python/CMakeLists.txt)
  string(APPEND sewerplan_dev_depends ", ${SEWERPLAN_PYTHON_DEB_DEPENDS}")
endif()
if(SEWERPLAN_WITH_GIS)  # the static gis library links -lproj and -lgdal; shlibdeps adds libgdal32
  string(APPEND sewerplan_dev_depends ", libproj-dev, libgdal-dev")
endif()
set(CPACK_DEBIAN_PACKAGE_DEPENDS "${sewerplan_dev_depends}")
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "${PROJECT_DESCRIPTION}
 The sewerplan command (plan, check, simulate, campaign, render, ...) and the C++ libraries
 with their headers and CMake package (find_package(sewerplan)), man page, bash completion,
 documentation and the MAKRO paper's AIS test environment as example data.")
include(CPack)
